#include "common/time_text.h"

#include <ctime>

namespace sph::service {

std::string format_unix_seconds(std::int64_t unix_seconds, bool utc) {
  const std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  if (utc)
    gmtime_r(&t, &tm);
  else
    localtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, utc ? "%Y-%m-%d %H:%M:%S UTC" : "%Y-%m-%d %H:%M:%S", &tm);
  return buf;
}

}  // namespace sph::service
