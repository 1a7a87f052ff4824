#pragma once
// Lines of a data file that a case inlines (point files, reference data), read with a bound on
// the length of each line: std::getline would read a file without line breaks whole.
#include <istream>
#include <string>
#include <vector>

namespace sph {

class DataLines {
 public:
  DataLines(std::istream& in, std::string path) : in_(in), path_(std::move(path)) {}
  // The next line without its '\n' (and a '\r' before it); false at the end of the file.
  // Throws std::runtime_error "PATH:LINE: longer than 4096 bytes..." for a longer line.
  bool next(std::string& line);
  int line_number() const { return line_number_; }
  const std::string& path() const { return path_; }

 private:
  std::istream& in_;
  std::string path_;
  int line_number_ = 0;
  std::vector<char> buf_;
};

}  // namespace sph
