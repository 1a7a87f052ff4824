#pragma once
// Frees the disk a finished job holds: RESULTS/<job>/, every attempt's result files and
// checkpoints (sphctl delete). The job's record stays in the database.
#include <cstdint>
#include <string>

#include "server/results/result_layout.h"

namespace sph::server {

struct RemovedFiles {
  std::int64_t files = 0;
  std::int64_t bytes = 0;  // sizes of the regular files removed
};

// Removes the job's directory and everything below it; a missing directory removes nothing.
// Symbolic links are removed, never followed. Throws std::filesystem::filesystem_error naming
// the path when something cannot be removed (what was removed before stays removed, and a
// repeated call goes on from there).
RemovedFiles remove_job_files(const ResultLayout& layout, const std::string& job_id);

}  // namespace sph::server
