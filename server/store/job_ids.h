#pragma once
// Job ids as users see them ("job-42") and as the database stores them (42). There is one
// written form of each id: results live in RESULTS/<id as text>/, so two spellings of one job
// ("8", "job-08") would name two folders.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sph::server::store {

std::string format_job_id(std::int64_t id);
// Accepts exactly what format_job_id writes ("job-42": no sign, no leading zero); nullopt for
// anything else.
std::optional<std::int64_t> parse_job_id(std::string_view text);
// A ListJobs page token: the decimal id to continue below, as ListJobs writes it.
std::optional<std::int64_t> parse_page_token(std::string_view text);

}  // namespace sph::server::store
