#pragma once
// Wall-clock times as people read them in logs, sphctl output and error messages.
#include <cstdint>
#include <string>

namespace sph::service {

// "2026-11-24 05:32:45" in the local time zone, or "2026-11-24 05:32:45 UTC" with `utc`
// (for messages a server sends to clients in other time zones).
std::string format_unix_seconds(std::int64_t unix_seconds, bool utc = false);

}  // namespace sph::service
