#include "server/store/job_ids.h"

#include <charconv>

namespace sph::server::store {

std::string format_job_id(std::int64_t id) {
  return "job-" + std::to_string(id);
}

std::optional<std::int64_t> parse_job_id(std::string_view text) {
  if (text.rfind("job-", 0) == 0) text.remove_prefix(4);
  std::int64_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || end != text.data() + text.size() || id <= 0 || text.empty())
    return std::nullopt;
  return id;
}

}  // namespace sph::server::store
