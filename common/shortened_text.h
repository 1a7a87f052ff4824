#pragma once
// Cutting a text that would come back in every listing to a bounded length, at a character
// boundary: a proto3 string must stay valid UTF-8, or the client cannot parse the message.
#include <cstddef>
#include <string>

namespace sph::service {

// Cuts `text` to at most `max_bytes` (backing up to the start of a UTF-8 character) and marks
// the cut with "..."; shorter texts stay as they are.
inline void shorten_text(std::string& text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return;
  std::size_t end = max_bytes;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
  text.resize(end);
  text += "...";
}

}  // namespace sph::service
