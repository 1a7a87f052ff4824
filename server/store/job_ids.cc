#include "server/store/job_ids.h"

#include <charconv>

namespace sph::server::store {
namespace {

// A positive decimal integer without sign, leading zero or anything around it.
std::optional<std::int64_t> parse_positive_decimal(std::string_view text) {
  if (text.empty() || text.front() < '1' || text.front() > '9') return std::nullopt;
  std::int64_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return id;
}

}  // namespace

std::string format_job_id(std::int64_t id) {
  return "job-" + std::to_string(id);
}

std::optional<std::int64_t> parse_job_id(std::string_view text) {
  if (text.rfind("job-", 0) != 0) return std::nullopt;
  return parse_positive_decimal(text.substr(4));
}

std::optional<std::int64_t> parse_page_token(std::string_view text) {
  return parse_positive_decimal(text);
}

}  // namespace sph::server::store
