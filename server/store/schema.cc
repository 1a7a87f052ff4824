#include "server/store/schema.h"

#include <array>
#include <string>

namespace sph::server::store {
namespace {

// Never edit a migration that has shipped; append a new one.
constexpr std::array<const char*, 5> kMigrations = {
    // 1: jobs, attempts and the append-only event log.
    R"sql(
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  request_id TEXT NOT NULL UNIQUE,
  case_sha256 TEXT NOT NULL,
  name TEXT NOT NULL,
  case_text TEXT NOT NULL,
  estimated_particles REAL NOT NULL,
  state TEXT NOT NULL
    CHECK (state IN ('QUEUED', 'RUNNING', 'SUCCEEDED', 'FAILED', 'CANCELLED')),
  reason TEXT NOT NULL DEFAULT '',
  attempt INTEGER NOT NULL DEFAULT 0,
  cancel_requested INTEGER NOT NULL DEFAULT 0,
  lease_expires_ms INTEGER,
  created_ms INTEGER NOT NULL,
  started_ms INTEGER,
  finished_ms INTEGER,
  progress BLOB,    -- sph.v1.ProgressInfo, newest report
  checkpoint BLOB,  -- sph.v1.Checkpoint, newest
  result BLOB,      -- sph.v1.ResultManifest
  last_event INTEGER NOT NULL DEFAULT 0,
  CHECK (state NOT IN ('SUCCEEDED', 'FAILED', 'CANCELLED') OR reason <> '')
) STRICT;
CREATE INDEX jobs_by_state ON jobs (state, id);

CREATE TABLE attempts (
  job_id INTEGER NOT NULL REFERENCES jobs (id),
  number INTEGER NOT NULL,
  pool TEXT NOT NULL,
  ranks INTEGER NOT NULL,
  hostname TEXT NOT NULL,
  started_ms INTEGER NOT NULL,
  ended_ms INTEGER,
  outcome TEXT NOT NULL DEFAULT 'RUNNING',
  reason TEXT NOT NULL DEFAULT '',
  resumed_from TEXT NOT NULL DEFAULT '',
  output_dir TEXT NOT NULL,
  unit_seconds BLOB,  -- sph.v1.Attempt with only unit_seconds set
  PRIMARY KEY (job_id, number)
) STRICT;

CREATE TABLE events (
  job_id INTEGER NOT NULL REFERENCES jobs (id),
  sequence INTEGER NOT NULL,
  time_ms INTEGER NOT NULL,
  kind TEXT NOT NULL,     -- for people reading the table with sqlite3
  payload BLOB NOT NULL,  -- sph.v1.JobEvent
  PRIMARY KEY (job_id, sequence)
) STRICT, WITHOUT ROWID;
CREATE TRIGGER events_no_update BEFORE UPDATE ON events
BEGIN SELECT RAISE(ABORT, 'events are append-only'); END;
CREATE TRIGGER events_no_delete BEFORE DELETE ON events
BEGIN SELECT RAISE(ABORT, 'events are append-only'); END;
)sql",
    // 2: convergence-study jobs carry their ladder (sph.v1.StudySpec); NULL for single runs.
    R"sql(
ALTER TABLE jobs ADD COLUMN study BLOB;
)sql",
    // 3: DeleteJobFiles records when it removed a finished job's files and what that freed.
    R"sql(
ALTER TABLE jobs ADD COLUMN files_deleted_ms INTEGER;
ALTER TABLE jobs ADD COLUMN files_deleted_bytes INTEGER;
)sql",
    // 4: an identity of the database, written into the results directory it uses, so that a
    // new database (whose job ids restart at job-1) is never pointed at another one's results.
    R"sql(
CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL) STRICT;
INSERT INTO meta (key, value) VALUES ('database_id', lower(hex(randomblob(16))));
)sql",
    // 5: the pools' log lines per attempt (sphctl logs), the newest 256 KiB of each attempt.
    R"sql(
CREATE TABLE log_lines (
  job_id INTEGER NOT NULL REFERENCES jobs (id),
  sequence INTEGER NOT NULL,
  attempt INTEGER NOT NULL,
  time_ms INTEGER NOT NULL,
  text TEXT NOT NULL,
  PRIMARY KEY (job_id, sequence)
) STRICT, WITHOUT ROWID;
CREATE INDEX log_lines_by_attempt ON log_lines (job_id, attempt, sequence);
ALTER TABLE attempts ADD COLUMN log_bytes INTEGER NOT NULL DEFAULT 0;
ALTER TABLE attempts ADD COLUMN log_dropped INTEGER NOT NULL DEFAULT 0;
)sql",
};

int user_version(Database& db) {
  auto st = db.prepare("PRAGMA user_version");
  st.step();
  return static_cast<int>(st.int64(0));
}

}  // namespace

int current_schema_version() {
  return static_cast<int>(kMigrations.size());
}

void migrate(Database& db) {
  while (true) {
    WriteTransaction tx(db);
    // Read inside the write lock so two servers started on one file cannot both migrate.
    const int version = user_version(db);
    if (version > current_schema_version())
      throw SqliteError(SQLITE_ERROR, "the database has schema version " + std::to_string(version) +
                                          " but this sph-server knows " +
                                          std::to_string(current_schema_version()) +
                                          ": it was written by a newer release");
    if (version == current_schema_version()) return;
    db.exec(kMigrations[static_cast<size_t>(version)]);
    db.exec("PRAGMA user_version = " + std::to_string(version + 1));
    tx.commit();
  }
}

}  // namespace sph::server::store
