#include "case/data_lines.h"

#include <stdexcept>

#include "case/case_limits.h"

namespace sph {

bool DataLines::next(std::string& line) {
  buf_.resize(kMaxDataLineBytes + 1);
  in_.getline(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  const std::streamsize got = in_.gcount();
  if (in_.bad()) throw std::runtime_error(path_ + ": read error");
  if (in_.fail()) {
    if (in_.eof() && got == 0) return false;
    // getline stops with failbit when the buffer filled before a line break.
    throw std::runtime_error(path_ + ":" + std::to_string(line_number_ + 1) +
                             ": a line longer than " + std::to_string(kMaxDataLineBytes) +
                             " bytes; the limit is " + std::to_string(kMaxDataLineBytes));
  }
  ++line_number_;
  line.assign(buf_.data());
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

}  // namespace sph
