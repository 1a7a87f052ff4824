#pragma once
// A results directory belongs to one database. Job ids restart at job-1 in a new database, so
// a new database pointed at an old results directory would write its job-1 over the old
// job-1's files (and `sphctl delete` would remove them). The server therefore writes its
// database's identity into RESULTS/.sphd-database-id and refuses to start on a results
// directory that carries another identity.
#include <string>

#include "server/results/result_layout.h"

namespace sph::server {

inline constexpr const char* kDatabaseIdFile = ".sphd-database-id";

// Writes the identity into a results directory that has none, or checks it against the one
// there. A directory without one that already holds job folders is taken over only by a
// database that has jobs (an installation from before the identity existed); for a new
// database it is refused. Throws std::runtime_error saying what to do.
void claim_results_directory(const ResultLayout& layout, const std::string& database_id,
                             bool database_has_jobs);

}  // namespace sph::server
