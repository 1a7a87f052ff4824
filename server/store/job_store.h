#pragma once
// The job queue and its history in SQLite: submission (exactly once per request id), claims
// with leases, fenced worker reports, terminal states with reasons, and the append-only event
// log that WatchJob replays. Every method is one transaction and thread-safe; times are
// passed in (unix milliseconds) so that lease expiry is testable without sleeping. Concurrent
// submits share transactions (group commit); each returns once its own row is durable.
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/group_commit.h"
#include "server/store/job_error.h"
#include "server/store/sqlite.h"
#include "sph/v1/service.pb.h"

namespace sph::server::store {

struct StoreOptions {
  std::int64_t lease_ms = 30'000;
  // A job whose lease expires this many times fails instead of being queued again (a case
  // that crashes its pool every time must not loop forever).
  int max_lost_leases = 5;
};

struct NewJob {
  std::string request_id;
  std::string name;
  std::string case_text;  // canonical text
  std::string case_sha256;
  double estimated_particles = 0;
  std::string study;  // serialized sph.v1.StudySpec; empty for a single run
};

struct SubmitResult {
  v1::Job job;
  bool created = false;
};

// What all unfinished (queued or running) jobs together may hold; 0 = no limit.
struct QueueLimits {
  double max_jobs = 0;
  double max_particles = 0;  // the sum of their estimated particles
};

// A new job refused because the queue is at a QueueLimits limit; the message has the numbers.
class QueueFull : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ClaimInfo {
  std::string pool;
  std::string hostname;
  int ranks = 1;
};

// What the store holds, for sph-server's metrics (server/metrics/): read from the database at
// each scrape, so the numbers survive a restart and agree with ListJobs.
struct StoreCounts {
  std::map<std::string, std::int64_t> jobs_by_state;        // every state, 0 when none
  double queued_particles = 0;                              // estimated, over queued jobs
  std::map<std::string, std::int64_t> attempts_by_outcome;  // RUNNING for unfinished ones
  std::int64_t attempts_requeued = 0;      // attempts after a job's first: each followed a requeue
  std::int64_t result_bytes = 0;           // files in the result manifests of jobs not deleted
  std::int64_t results_deleted_bytes = 0;  // freed by DeleteJobFiles
};

struct LogPage {
  std::vector<v1::LogLine> lines;
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::int64_t dropped_lines = 0;
};

// Per attempt the store keeps the newest this many bytes of log text (sphctl logs).
inline constexpr std::int64_t kMaxLogBytesPerAttempt = 256 << 10;
inline constexpr std::size_t kMaxLogLineBytes = 1024;

struct JobPage {
  std::vector<v1::Job> jobs;
  std::int64_t next_before = 0;  // id to continue below, 0 on the last page
};

class JobStore {
 public:
  JobStore(const std::string& db_path, ResultLayout layout, StoreOptions options, EventFeed& feed);

  // Stores the job, or returns the job stored before under the same request id (created =
  // false, whether or not the queue is full). Throws JobError kRequestConflict for a request id
  // used with another case, QueueFull when a new job would exceed `limits` (counting the jobs
  // committed before it in the same transaction), and SqliteError when the transaction fails,
  // in which case nothing of it was stored.
  SubmitResult submit(const NewJob& job, std::int64_t now_ms, const QueueLimits& limits = {});
  // Transactions and submits so far (group commit at work: fewer batches than submits).
  GroupCommitStats submit_stats() const { return submits_.stats(); }
  v1::Job get(std::int64_t id, bool include_case);
  // Newest first, ids below `before` (0: from the newest).
  JobPage list(const std::vector<v1::JobState>& states, int page_size, std::int64_t before);
  v1::Job cancel(std::int64_t id, const std::string& reason, std::int64_t now_ms);
  // The job, when it is finished (a terminal state, which never changes again); throws
  // kPrecondition otherwise, saying what to do.
  v1::Job get_finished(std::int64_t id);
  // Records that a finished job's files were removed (the caller removes them first: a
  // terminal job never runs again, so nothing writes there in between). Returns the job and
  // whether this call recorded it (false when an earlier one had). Throws kPrecondition for
  // a job that is not finished.
  std::pair<v1::Job, bool> record_files_deleted(std::int64_t id, std::int64_t bytes,
                                                std::int64_t now_ms);

  // The oldest queued job as a new attempt, or nullopt when the queue is empty.
  std::optional<v1::ClaimResponse> claim(const ClaimInfo& who, std::int64_t now_ms);
  // Renews the lease; throws kStaleAttempt unless the attempt is the job's current one.
  v1::ReportResponse report(const v1::ReportRequest& r, std::int64_t now_ms);
  // Ends the attempt; idempotent for a repeated call with the same outcome.
  v1::JobState finish(const v1::FinishRequest& r, std::int64_t now_ms);

  // Re-queues (or fails, or cancels) running jobs whose lease ended before now. Returns how
  // many jobs were affected.
  int expire_leases(std::int64_t now_ms);
  // After a server restart pools could not report while the server was away: give every
  // running job a full lease from now.
  void renew_all_leases(std::int64_t now_ms);

  // A random identity made with the database (schema version 4).
  std::string database_id();
  // Whether any job was ever submitted to this database.
  bool has_jobs();

  StoreCounts counts();
  // Log lines of job `id` with sequence > after (of `attempt` only, when > 0), at most limit.
  LogPage logs(std::int64_t id, int attempt, std::int64_t after, int limit);

  std::vector<v1::JobEvent> events_after(std::int64_t id, std::int64_t after, int limit);
  v1::JobState state(std::int64_t id);

  const StoreOptions& options() const { return options_; }

 private:
  struct PendingSubmit {
    const NewJob* job = nullptr;
    std::int64_t now_ms = 0;
    QueueLimits limits;
  };
  using SubmitGroup = GroupCommit<PendingSubmit, SubmitResult>;
  struct QueueTotals {
    std::int64_t jobs = 0;
    double particles = 0;
  };
  void commit_submits(std::span<SubmitGroup::Entry* const> batch);
  SubmitResult insert_job(const PendingSubmit& s, std::optional<QueueTotals>& totals);
  QueueTotals count_unfinished();

  struct Row;  // a job row as read for state transitions
  Row load_row(std::int64_t id);
  std::int64_t append_event(std::int64_t id, v1::JobEvent& event, std::int64_t now_ms);
  void set_state(std::int64_t id, v1::JobState state, const std::string& reason, int attempt,
                 std::int64_t now_ms, const std::string& pool = "");
  void end_attempt(std::int64_t id, int attempt, v1::AttemptOutcome outcome,
                   const std::string& reason, std::int64_t now_ms,
                   const google::protobuf::Map<std::string, double>* unit_seconds = nullptr);
  void store_checkpoint(std::int64_t id, v1::Checkpoint cp, int attempt, std::int64_t now_ms);
  void store_progress(std::int64_t id, const v1::ProgressInfo& p, std::int64_t now_ms);
  void store_log(std::int64_t id, int attempt,
                 const google::protobuf::RepeatedPtrField<v1::LogLine>& lines, std::int64_t now_ms);
  v1::Job read_job(std::int64_t id, bool include_case, bool include_attempts);
  void publish();

  Database db_;
  ResultLayout layout_;
  StoreOptions options_;
  EventFeed& feed_;
  std::mutex mu_;
  // Events appended by the current transaction, published to the feed after it commits.
  std::vector<std::pair<std::int64_t, std::int64_t>> pending_events_;
  bool pending_queue_wakeup_ = false;
  // The unfinished jobs as last counted, kept up to date by submits; every state change
  // forgets it (set_state), so the next submit that needs it counts again in its transaction.
  std::optional<QueueTotals> queue_totals_;
  // Last: its batches call into the members above.
  SubmitGroup submits_;
};

}  // namespace sph::server::store
