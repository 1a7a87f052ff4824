#pragma once
// The text a submitted case is stored as, bounded by a small multiple of what was submitted.
// The canonical text puts every field on its own line, indented by its depth, so a case
// written compactly with deeply nested shapes grows with the square of its depth when printed
// that way (the same fields, but each closing brace on a line of its own far to the right).
// Such a case is stored on one line instead: same fields, same values, parsed the same.
#include <cstddef>
#include <optional>
#include <string>

#include "sph/v1/case.pb.h"

namespace sph::server::api {

// At most this many bytes are stored for a request of `request_bytes`.
constexpr std::size_t max_stored_case_bytes(std::size_t request_bytes) {
  return 4 * request_bytes + (64 << 10);
}

// The canonical multi-line text when it fits max_stored_case_bytes(request_bytes), else the
// one-line text when that fits, else nullopt.
std::optional<std::string> stored_case_text(const v1::Case& c, std::size_t request_bytes);

}  // namespace sph::server::api
