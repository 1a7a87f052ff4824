#pragma once
// Frees the disk a finished job holds: RESULTS/<job>/, every attempt's result files and
// checkpoints (sphctl delete). The job's record stays in the database.
#include <cstdint>
#include <string>

#include "server/results/result_layout.h"

namespace sph::server {

struct JobFiles {
  std::int64_t files = 0;
  std::int64_t bytes = 0;  // sizes of the regular files
};

// What lies in the job's directory (nothing when it is missing). Symbolic links are not
// followed, so nothing outside the directory is counted.
JobFiles measure_job_files(const ResultLayout& layout, const std::string& job_id);

// Removes the job's directory and everything below it; a missing directory removes nothing.
// Symbolic links are removed, never followed. Throws std::filesystem::filesystem_error naming
// the path when something cannot be removed (what was removed before stays removed, and a
// repeated call goes on from there).
void remove_job_files(const ResultLayout& layout, const std::string& job_id);

}  // namespace sph::server
