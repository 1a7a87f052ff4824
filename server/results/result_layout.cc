#include "server/results/result_layout.h"

#include <algorithm>
#include <stdexcept>

#include "server/store/job_ids.h"

namespace sph::server {
namespace fs = std::filesystem;

namespace {

// Lexical containment after normalisation: `child` equals `dir` or lies below it.
bool is_below(const fs::path& dir, const fs::path& child) {
  const fs::path d = dir.lexically_normal();
  const fs::path c = child.lexically_normal();
  auto [dend, cend] = std::mismatch(d.begin(), d.end(), c.begin(), c.end());
  // A trailing empty element ("dir/") matches anything.
  return dend == d.end() || (std::next(dend) == d.end() && dend->empty());
}

}  // namespace

ResultLayout::ResultLayout(const fs::path& root) : root_(fs::absolute(root).lexically_normal()) {}

fs::path ResultLayout::job_dir(const std::string& job_id) const {
  // Paths are built only from the canonical form the database gives ("job-42"): anything else
  // ("/etc", "8", "..") would name a folder that is not this job's. Callers resolve the job
  // first, so this throwing means a bug, not bad input.
  if (!store::parse_job_id(job_id))
    throw std::invalid_argument("not a canonical job id: '" + job_id + "'");
  return root_ / job_id;
}

fs::path ResultLayout::attempt_dir(const std::string& job_id, int attempt) const {
  return job_dir(job_id) / std::to_string(attempt);
}

bool ResultLayout::inside_job(const std::string& job_id, const fs::path& path) const {
  if (!path.is_absolute()) return false;
  std::error_code ec;
  // Resolve symbolic links where the file exists, so a link cannot point outside.
  const fs::path real = fs::weakly_canonical(path, ec);
  const fs::path real_dir = fs::weakly_canonical(job_dir(job_id), ec);
  return !ec && is_below(real_dir, real) && real.lexically_normal() != real_dir.lexically_normal();
}

std::optional<std::string> ResultLayout::check_result_name(const std::string& job_id, int attempt,
                                                           const std::string& name) const {
  const fs::path p(name);
  if (name.empty()) return "is empty";
  if (p.is_absolute()) return "must be relative to the output directory";
  for (const auto& part : p)
    if (part == "..") return "must not contain '..'";
  const fs::path full = attempt_dir(job_id, attempt) / p;
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(full, ec);
  if (ec || !is_below(fs::weakly_canonical(attempt_dir(job_id, attempt), ec), real))
    return "resolves outside the output directory";
  if (!fs::is_regular_file(real, ec))
    return "is not a regular file in " + full.parent_path().string();
  return std::nullopt;
}

}  // namespace sph::server
