#pragma once
// Job ids as users see them ("job-42") and as the database stores them (42).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sph::server::store {

std::string format_job_id(std::int64_t id);
// Accepts "job-42" and "42"; nullopt for anything else.
std::optional<std::int64_t> parse_job_id(std::string_view text);

}  // namespace sph::server::store
