#pragma once
#include <chrono>
#include <cstdint>

namespace sph::server {

// Wall-clock unix time in milliseconds: stored timestamps and lease deadlines must survive a
// server restart, so they cannot use a monotonic clock.
inline std::int64_t now_unix_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace sph::server
