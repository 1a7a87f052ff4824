#pragma once
// The database schema as an ordered list of migrations; PRAGMA user_version records how many
// have been applied.
#include "server/store/sqlite.h"

namespace sph::server::store {

// The schema version this build writes.
int current_schema_version();

// Applies the migrations the database lacks, each in its own write transaction. Throws when
// the database was written by a newer sph-server (its version is above ours).
void migrate(Database& db);

}  // namespace sph::server::store
