#include "server/api/stored_case_text.h"

#include <google/protobuf/text_format.h>

#include "case/load.h"

namespace sph::server::api {

std::optional<std::string> stored_case_text(const v1::Case& c, std::size_t request_bytes) {
  const std::size_t bound = max_stored_case_bytes(request_bytes);
  std::string text = case_to_text(c);
  if (text.size() <= bound) return text;
  google::protobuf::TextFormat::Printer printer;
  printer.SetSingleLineMode(true);
  // Names and descriptions as UTF-8, not as octal escapes four times their size.
  printer.SetUseUtf8StringEscaping(true);
  // Long lists of numbers (output.times, time tables) as [a, b, ...], not "times: a" each.
  printer.SetUseShortRepeatedPrimitives(true);
  text.clear();
  printer.PrintToString(c, &text);
  if (text.size() <= bound) return text;
  return std::nullopt;
}

}  // namespace sph::server::api
