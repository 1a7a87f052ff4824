#include "server/store/job_store.h"

#include <cmath>
#include <cstdio>

#include "case/number_text.h"
#include "common/job_state.h"
#include "server/store/job_ids.h"
#include "server/store/schema.h"

namespace sph::server::store {
namespace {

using service::is_terminal;
using service::outcome_name;
using service::state_name;

constexpr const char* kJobColumns =
    "id, request_id, name, state, reason, attempt, cancel_requested, created_ms, started_ms, "
    "finished_ms, estimated_particles, progress, checkpoint, result, last_event, study, "
    "files_deleted_ms, files_deleted_bytes";

v1::JobState state_from_text(const std::string& s) {
  const auto parsed = service::parse_state(s);
  if (!parsed) throw SqliteError(SQLITE_CORRUPT, "unknown job state '" + s + "' in database");
  return *parsed;
}

v1::AttemptOutcome outcome_from_text(const std::string& s) {
  for (v1::AttemptOutcome o : {v1::ATTEMPT_COMPLETED, v1::ATTEMPT_FAILED, v1::ATTEMPT_CANCELLED,
                               v1::ATTEMPT_INTERRUPTED, v1::ATTEMPT_LEASE_EXPIRED})
    if (s == outcome_name(o)) return o;
  return v1::ATTEMPT_OUTCOME_UNSPECIFIED;
}

template <typename Message>
void parse_blob(const Statement& st, int column, Message* out) {
  if (!st.is_null(column)) out->ParseFromString(st.blob(column));
}

// Reads the columns of kJobColumns (and case_text at column 18 when asked).
v1::Job job_from_row(const Statement& st, bool with_case) {
  v1::Job j;
  j.set_id(format_job_id(st.int64(0)));
  j.set_request_id(st.text(1));
  j.set_name(st.text(2));
  j.set_state(state_from_text(st.text(3)));
  j.set_reason(st.text(4));
  j.set_attempt(static_cast<int>(st.int64(5)));
  j.set_cancel_requested(st.int64(6) != 0);
  j.set_created_unix_ms(st.int64(7));
  j.set_started_unix_ms(st.int64(8));
  j.set_finished_unix_ms(st.int64(9));
  j.set_estimated_particles(st.real(10));
  if (!st.is_null(11)) parse_blob(st, 11, j.mutable_progress());
  if (!st.is_null(12)) parse_blob(st, 12, j.mutable_checkpoint());
  if (!st.is_null(13)) parse_blob(st, 13, j.mutable_result());
  j.set_last_event_sequence(st.int64(14));
  if (!st.is_null(15)) parse_blob(st, 15, j.mutable_study());
  if (!st.is_null(16)) {
    j.set_files_deleted_unix_ms(st.int64(16));
    j.set_files_deleted_bytes(st.int64(17));
  }
  if (with_case) j.set_case_text(st.text(18));
  return j;
}

std::string event_kind(const v1::JobEvent& e) {
  switch (e.kind_case()) {
    case v1::JobEvent::kStateChange:
      return std::string("state:") + state_name(e.state_change().state());
    case v1::JobEvent::kProgress:
      return "progress";
    case v1::JobEvent::kCheckpoint:
      return "checkpoint";
    case v1::JobEvent::kResultReady:
      return "result_ready";
    case v1::JobEvent::kCancelRequested:
      return "cancel_requested";
    default:
      return "unknown";
  }
}

std::string finished_only_message(std::int64_t id, v1::JobState state) {
  const std::string job = format_job_id(id);
  return job + " is " + state_name(state) +
         ": only a finished job's files can be deleted (cancel it first: sphctl cancel " + job +
         ")";
}

// A count of jobs or particles in a message: every digit, no exponent.
std::string count_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

std::string resume_phrase(const v1::Job& j) {
  if (!j.has_checkpoint()) return "starts over (no checkpoint yet)";
  return "resumes from the checkpoint at step " + std::to_string(j.checkpoint().step()) +
         ", t = " + number_text(j.checkpoint().time());
}

}  // namespace

struct JobStore::Row {
  std::int64_t id = 0;
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  int attempt = 0;
  bool cancel_requested = false;
};

JobStore::JobStore(const std::string& db_path, ResultLayout layout, StoreOptions options,
                   EventFeed& feed)
    : db_(db_path),
      layout_(std::move(layout)),
      options_(options),
      feed_(feed),
      submits_([this](std::span<SubmitGroup::Entry* const> batch) { commit_submits(batch); }) {
  migrate(db_);
}

void JobStore::publish() {
  for (const auto& [job, seq] : pending_events_) feed_.published(job, seq);
  if (pending_queue_wakeup_) feed_.job_queued();
  pending_events_.clear();
  pending_queue_wakeup_ = false;
}

JobStore::Row JobStore::load_row(std::int64_t id) {
  auto st = db_.prepare("SELECT state, attempt, cancel_requested FROM jobs WHERE id = ?1");
  st.bind(1, id);
  if (!st.step()) throw JobError(JobError::Kind::kNotFound, format_job_id(id) + " does not exist");
  Row r;
  r.id = id;
  r.state = state_from_text(st.text(0));
  r.attempt = static_cast<int>(st.int64(1));
  r.cancel_requested = st.int64(2) != 0;
  return r;
}

std::int64_t JobStore::append_event(std::int64_t id, v1::JobEvent& event, std::int64_t now_ms) {
  std::int64_t seq = 0;
  {
    auto st = db_.prepare(
        "UPDATE jobs SET last_event = last_event + 1 WHERE id = ?1 RETURNING last_event");
    st.bind(1, id);
    if (!st.step())
      throw JobError(JobError::Kind::kNotFound, format_job_id(id) + " does not exist");
    seq = st.int64(0);
    st.run();
  }
  event.set_job_id(format_job_id(id));
  event.set_sequence(seq);
  event.set_time_unix_ms(now_ms);
  db_.prepare(
         "INSERT INTO events (job_id, sequence, time_ms, kind, payload) VALUES (?1, ?2, ?3, ?4, "
         "?5)")
      .bind(1, id)
      .bind(2, seq)
      .bind(3, now_ms)
      .bind(4, event_kind(event))
      .bind_blob(5, event.SerializeAsString())
      .run();
  pending_events_.emplace_back(id, seq);
  return seq;
}

void JobStore::set_state(std::int64_t id, v1::JobState state, const std::string& reason,
                         int attempt, std::int64_t now_ms, const std::string& pool) {
  const bool terminal = is_terminal(state);
  auto st = db_.prepare(
      "UPDATE jobs SET state = ?2, reason = ?3, "
      "finished_ms = CASE WHEN ?4 THEN ?5 ELSE finished_ms END, "
      "lease_expires_ms = CASE WHEN ?2 = 'RUNNING' THEN lease_expires_ms END "
      "WHERE id = ?1");
  st.bind(1, id)
      .bind(2, state_name(state))
      .bind(3, reason)
      .bind(4, terminal ? 1 : 0)
      .bind(5, now_ms);
  st.run();
  queue_totals_.reset();
  v1::JobEvent e;
  auto* sc = e.mutable_state_change();
  sc->set_state(state);
  sc->set_attempt(attempt);
  sc->set_reason(reason);
  sc->set_pool(pool);
  append_event(id, e, now_ms);
  if (state == v1::JOB_STATE_QUEUED) pending_queue_wakeup_ = true;
}

void JobStore::end_attempt(std::int64_t id, int attempt, v1::AttemptOutcome outcome,
                           const std::string& reason, std::int64_t now_ms,
                           const google::protobuf::Map<std::string, double>* unit_seconds) {
  auto st = db_.prepare(
      "UPDATE attempts SET ended_ms = ?3, outcome = ?4, reason = ?5, unit_seconds = ?6 "
      "WHERE job_id = ?1 AND number = ?2");
  st.bind(1, id).bind(2, attempt).bind(3, now_ms).bind(4, outcome_name(outcome)).bind(5, reason);
  if (unit_seconds != nullptr && !unit_seconds->empty()) {
    v1::Attempt units;
    *units.mutable_unit_seconds() = *unit_seconds;
    st.bind_blob(6, units.SerializeAsString());
  } else {
    st.bind_null(6);
  }
  st.run();
}

void JobStore::store_checkpoint(std::int64_t id, v1::Checkpoint cp, int attempt,
                                std::int64_t now_ms) {
  cp.set_attempt(attempt);
  {
    // Finish repeats the newest checkpoint a Report may already have carried.
    auto st = db_.prepare("SELECT checkpoint FROM jobs WHERE id = ?1");
    st.bind(1, id);
    v1::Checkpoint current;
    if (st.step() && !st.is_null(0)) parse_blob(st, 0, &current);
    if (current.path() == cp.path()) return;
  }
  db_.prepare("UPDATE jobs SET checkpoint = ?2 WHERE id = ?1")
      .bind(1, id)
      .bind_blob(2, cp.SerializeAsString())
      .run();
  v1::JobEvent e;
  *e.mutable_checkpoint() = cp;
  append_event(id, e, now_ms);
}

void JobStore::store_progress(std::int64_t id, const v1::ProgressInfo& p, std::int64_t now_ms) {
  db_.prepare("UPDATE jobs SET progress = ?2 WHERE id = ?1")
      .bind(1, id)
      .bind_blob(2, p.SerializeAsString())
      .run();
  v1::JobEvent e;
  *e.mutable_progress() = p;
  append_event(id, e, now_ms);
}

v1::Job JobStore::read_job(std::int64_t id, bool include_case, bool include_attempts) {
  v1::Job j;
  {
    auto st = db_.prepare(std::string("SELECT ") + kJobColumns +
                          (include_case ? ", case_text" : "") + " FROM jobs WHERE id = ?1");
    st.bind(1, id);
    if (!st.step())
      throw JobError(JobError::Kind::kNotFound, format_job_id(id) + " does not exist");
    j = job_from_row(st, include_case);
  }
  if (include_attempts) {
    auto st = db_.prepare(
        "SELECT number, pool, ranks, hostname, started_ms, ended_ms, outcome, reason, "
        "resumed_from, output_dir, unit_seconds FROM attempts WHERE job_id = ?1 ORDER BY "
        "number");
    st.bind(1, id);
    while (st.step()) {
      auto* a = j.add_attempts();
      a->set_number(static_cast<int>(st.int64(0)));
      a->set_pool(st.text(1));
      a->set_ranks(static_cast<int>(st.int64(2)));
      a->set_hostname(st.text(3));
      a->set_started_unix_ms(st.int64(4));
      a->set_ended_unix_ms(st.int64(5));
      a->set_outcome(outcome_from_text(st.text(6)));
      a->set_reason(st.text(7));
      a->set_resumed_from(st.text(8));
      a->set_output_dir(st.text(9));
      if (!st.is_null(10)) {
        v1::Attempt units;
        parse_blob(st, 10, &units);
        *a->mutable_unit_seconds() = units.unit_seconds();
      }
    }
  }
  return j;
}

SubmitResult JobStore::submit(const NewJob& job, std::int64_t now_ms, const QueueLimits& limits) {
  return submits_.submit(PendingSubmit{&job, now_ms, limits});
}

void JobStore::commit_submits(std::span<SubmitGroup::Entry* const> batch) {
  std::lock_guard lock(mu_);
  pending_events_.clear();
  pending_queue_wakeup_ = false;
  std::optional<QueueTotals> totals = queue_totals_;
  try {
    WriteTransaction tx(db_);
    for (SubmitGroup::Entry* e : batch) {
      // A refusal of one submit leaves the others (and the transaction) alone; any other error
      // fails the whole batch below.
      try {
        e->result = insert_job(*e->request, totals);
      } catch (const JobError&) {
        e->error = std::current_exception();
      } catch (const QueueFull&) {
        e->error = std::current_exception();
      }
    }
    tx.commit();
  } catch (...) {
    // Rolled back: nothing of the batch was stored, and every submit in it fails alike.
    queue_totals_.reset();
    pending_events_.clear();
    pending_queue_wakeup_ = false;
    for (SubmitGroup::Entry* e : batch) {
      e->result.reset();
      e->error = std::current_exception();
    }
    return;
  }
  queue_totals_ = totals;
  publish();
}

JobStore::QueueTotals JobStore::count_unfinished() {
  auto st = db_.prepare(
      "SELECT COUNT(*), TOTAL(estimated_particles) FROM jobs WHERE state IN ('QUEUED', "
      "'RUNNING')");
  st.step();
  return {st.int64(0), st.real(1)};
}

SubmitResult JobStore::insert_job(const PendingSubmit& s, std::optional<QueueTotals>& totals) {
  const NewJob& job = *s.job;
  {
    auto st = db_.prepare("SELECT id, case_sha256 FROM jobs WHERE request_id = ?1");
    st.bind(1, job.request_id);
    if (st.step()) {
      const std::int64_t id = st.int64(0);
      if (st.text(1) != job.case_sha256)
        throw JobError(JobError::Kind::kRequestConflict,
                       "request_id '" + job.request_id + "' was already used for " +
                           format_job_id(id) + " with a different case");
      return {read_job(id, false, false), false};
    }
  }
  if (s.limits.max_jobs > 0 || s.limits.max_particles > 0) {
    if (!totals) totals = count_unfinished();
    if (s.limits.max_jobs > 0 && static_cast<double>(totals->jobs) + 1 > s.limits.max_jobs)
      throw QueueFull("queue full: " + count_text(static_cast<double>(totals->jobs)) +
                      (totals->jobs == 1 ? " job is" : " jobs are") +
                      " queued or running; the limit is " + count_text(s.limits.max_jobs) +
                      " (--max-queued-jobs)");
    if (s.limits.max_particles > 0 &&
        totals->particles + job.estimated_particles > s.limits.max_particles)
      throw QueueFull("queue full: queued and running jobs are estimated at " +
                      count_text(totals->particles) + " particles and this case at " +
                      count_text(job.estimated_particles) + "; the limit is " +
                      count_text(s.limits.max_particles) + " (--max-queued-particles)");
  }
  // The job starts with its first event (QUEUED), so last_event is 1 from the insert on.
  auto insert = db_.prepare(
      "INSERT INTO jobs (request_id, case_sha256, name, case_text, estimated_particles, "
      "state, reason, created_ms, study, last_event) VALUES (?1, ?2, ?3, ?4, ?5, 'QUEUED', "
      "'submitted', ?6, ?7, 1)");
  insert.bind(1, job.request_id)
      .bind(2, job.case_sha256)
      .bind(3, job.name)
      .bind(4, job.case_text)
      .bind(5, job.estimated_particles)
      .bind(6, s.now_ms);
  if (job.study.empty())
    insert.bind_null(7);
  else
    insert.bind_blob(7, job.study);
  insert.run();
  const std::int64_t id = sqlite3_last_insert_rowid(db_.handle());

  // The row as job_from_row would read it back (StoreTest.SubmitReturnsTheStoredJob).
  SubmitResult result;
  result.created = true;
  v1::Job& j = result.job;
  j.set_id(format_job_id(id));
  j.set_request_id(job.request_id);
  j.set_name(job.name);
  j.set_state(v1::JOB_STATE_QUEUED);
  j.set_reason("submitted");
  j.set_created_unix_ms(s.now_ms);
  j.set_estimated_particles(job.estimated_particles);
  j.set_last_event_sequence(1);
  if (!job.study.empty()) j.mutable_study()->ParseFromString(job.study);

  v1::JobEvent e;
  e.set_job_id(j.id());
  e.set_sequence(1);
  e.set_time_unix_ms(s.now_ms);
  e.mutable_state_change()->set_state(v1::JOB_STATE_QUEUED);
  e.mutable_state_change()->set_reason("submitted");
  db_.prepare(
         "INSERT INTO events (job_id, sequence, time_ms, kind, payload) VALUES (?1, 1, ?2, ?3, "
         "?4)")
      .bind(1, id)
      .bind(2, s.now_ms)
      .bind(3, event_kind(e))
      .bind_blob(4, e.SerializeAsString())
      .run();
  pending_events_.emplace_back(id, 1);
  pending_queue_wakeup_ = true;
  if (totals) {
    ++totals->jobs;
    totals->particles += job.estimated_particles;
  }
  return result;
}

v1::Job JobStore::get(std::int64_t id, bool include_case) {
  std::lock_guard lock(mu_);
  return read_job(id, include_case, true);
}

void JobStore::store_log(std::int64_t id, int attempt,
                         const google::protobuf::RepeatedPtrField<v1::LogLine>& lines,
                         std::int64_t now_ms) {
  if (lines.empty()) return;
  std::int64_t sequence = 0;
  {
    auto st = db_.prepare("SELECT COALESCE(MAX(sequence), 0) FROM log_lines WHERE job_id = ?1");
    st.bind(1, id);
    st.step();
    sequence = st.int64(0);
  }
  std::int64_t added = 0;
  for (const auto& l : lines) {
    std::string text = l.text().substr(0, kMaxLogLineBytes);
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    added += static_cast<std::int64_t>(text.size());
    db_.prepare(
           "INSERT INTO log_lines (job_id, sequence, attempt, time_ms, text) "
           "VALUES (?1, ?2, ?3, ?4, ?5)")
        .bind(1, id)
        .bind(2, ++sequence)
        .bind(3, attempt)
        .bind(4, l.time_unix_ms() > 0 ? l.time_unix_ms() : now_ms)
        .bind(5, text)
        .run();
  }
  std::int64_t bytes = 0;
  {
    auto st = db_.prepare(
        "UPDATE attempts SET log_bytes = log_bytes + ?3 WHERE job_id = ?1 AND number = ?2 "
        "RETURNING log_bytes");
    st.bind(1, id).bind(2, attempt).bind(3, added);
    if (st.step()) bytes = st.int64(0);
  }
  // Over the cap: the oldest lines of this attempt go, so the end (a guard's diagnosis) stays.
  while (bytes > kMaxLogBytesPerAttempt) {
    auto st = db_.prepare(
        "DELETE FROM log_lines WHERE job_id = ?1 AND sequence = (SELECT MIN(sequence) FROM "
        "log_lines WHERE job_id = ?1 AND attempt = ?2) RETURNING LENGTH(text)");
    st.bind(1, id).bind(2, attempt);
    if (!st.step()) break;
    const std::int64_t freed = st.int64(0);
    while (st.step()) {
    }
    bytes -= freed;
    db_.prepare(
           "UPDATE attempts SET log_bytes = log_bytes - ?3, log_dropped = log_dropped + 1 "
           "WHERE job_id = ?1 AND number = ?2")
        .bind(1, id)
        .bind(2, attempt)
        .bind(3, freed)
        .run();
  }
}

LogPage JobStore::logs(std::int64_t id, int attempt, std::int64_t after, int limit) {
  std::lock_guard lock(mu_);
  LogPage page;
  page.state = load_row(id).state;  // NOT_FOUND for a job that does not exist
  auto st = db_.prepare(
      "SELECT attempt, sequence, time_ms, text FROM log_lines WHERE job_id = ?1 AND sequence > "
      "?2 AND (?3 = 0 OR attempt = ?3) ORDER BY sequence LIMIT ?4");
  st.bind(1, id).bind(2, after).bind(3, attempt).bind(4, limit);
  while (st.step()) {
    v1::LogLine& l = page.lines.emplace_back();
    l.set_attempt(static_cast<int>(st.int64(0)));
    l.set_sequence(st.int64(1));
    l.set_time_unix_ms(st.int64(2));
    l.set_text(st.text(3));
  }
  auto dropped = db_.prepare(
      "SELECT TOTAL(log_dropped) FROM attempts WHERE job_id = ?1 AND (?2 = 0 OR number = ?2)");
  dropped.bind(1, id).bind(2, attempt);
  if (dropped.step()) page.dropped_lines = static_cast<std::int64_t>(dropped.real(0));
  return page;
}

StoreCounts JobStore::counts() {
  std::lock_guard lock(mu_);
  StoreCounts c;
  for (auto st : {v1::JOB_STATE_QUEUED, v1::JOB_STATE_RUNNING, v1::JOB_STATE_SUCCEEDED,
                  v1::JOB_STATE_FAILED, v1::JOB_STATE_CANCELLED})
    c.jobs_by_state[service::state_name(st)] = 0;
  {
    auto st =
        db_.prepare("SELECT state, COUNT(*), TOTAL(estimated_particles) FROM jobs GROUP BY state");
    while (st.step()) {
      c.jobs_by_state[st.text(0)] = st.int64(1);
      if (st.text(0) == "QUEUED") c.queued_particles = st.real(2);
    }
  }
  for (auto o : {v1::ATTEMPT_OUTCOME_UNSPECIFIED, v1::ATTEMPT_COMPLETED, v1::ATTEMPT_FAILED,
                 v1::ATTEMPT_CANCELLED, v1::ATTEMPT_INTERRUPTED, v1::ATTEMPT_LEASE_EXPIRED})
    c.attempts_by_outcome[outcome_name(o)] = 0;
  {
    auto st =
        db_.prepare("SELECT outcome, COUNT(*), TOTAL(number > 1) FROM attempts GROUP BY outcome");
    while (st.step()) {
      c.attempts_by_outcome[st.text(0)] = st.int64(1);
      c.attempts_requeued += static_cast<std::int64_t>(st.real(2));
    }
  }
  {
    auto st = db_.prepare(
        "SELECT result, files_deleted_bytes FROM jobs WHERE result IS NOT NULL OR "
        "files_deleted_ms IS NOT NULL");
    while (st.step()) {
      if (!st.is_null(1)) {
        c.results_deleted_bytes += st.int64(1);
        continue;
      }
      v1::ResultManifest m;
      if (!m.ParseFromString(st.blob(0))) continue;
      for (const auto& f : m.files()) c.result_bytes += f.size();
    }
  }
  return c;
}

JobPage JobStore::list(const std::vector<v1::JobState>& states, int page_size,
                       std::int64_t before) {
  std::lock_guard lock(mu_);
  std::string sql = std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id < ?1";
  if (!states.empty()) {
    sql += " AND state IN (";
    for (size_t i = 0; i < states.size(); ++i) sql += (i ? ", ?" : "?") + std::to_string(i + 3);
    sql += ")";
  }
  sql += " ORDER BY id DESC LIMIT ?2";
  auto st = db_.prepare(sql);
  st.bind(1, before > 0 ? before : INT64_MAX).bind(2, page_size + 1);
  for (size_t i = 0; i < states.size(); ++i)
    st.bind(static_cast<int>(i + 3), state_name(states[i]));
  JobPage page;
  while (st.step()) {
    if (static_cast<int>(page.jobs.size()) == page_size) {
      page.next_before = st.int64(0) + 1;
      break;
    }
    page.jobs.push_back(job_from_row(st, false));
  }
  return page;
}

v1::Job JobStore::cancel(std::int64_t id, const std::string& reason, std::int64_t now_ms) {
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  const Row r = load_row(id);
  const std::string why = reason.empty() ? "cancelled by request" : "cancelled: " + reason;
  if (r.state == v1::JOB_STATE_QUEUED || r.state == v1::JOB_STATE_RUNNING) {
    if (!r.cancel_requested) {
      db_.prepare("UPDATE jobs SET cancel_requested = 1 WHERE id = ?1").bind(1, id).run();
      v1::JobEvent e;
      e.mutable_cancel_requested()->set_reason(why);
      append_event(id, e, now_ms);
    }
    // A queued job has no worker to tell: it ends here. A running one ends when its pool
    // confirms (Finish) or loses its lease.
    if (r.state == v1::JOB_STATE_QUEUED)
      set_state(id, v1::JOB_STATE_CANCELLED, why + " (before it started running)", r.attempt,
                now_ms);
  }
  v1::Job j = read_job(id, false, true);
  tx.commit();
  publish();
  return j;
}

std::string JobStore::database_id() {
  std::lock_guard lock(mu_);
  auto st = db_.prepare("SELECT value FROM meta WHERE key = 'database_id'");
  if (!st.step()) throw SqliteError(SQLITE_CORRUPT, "the database has no database_id");
  return st.text(0);
}

bool JobStore::has_jobs() {
  std::lock_guard lock(mu_);
  auto st = db_.prepare("SELECT EXISTS (SELECT 1 FROM jobs)");
  st.step();
  return st.int64(0) != 0;
}

v1::Job JobStore::get_finished(std::int64_t id) {
  std::lock_guard lock(mu_);
  v1::Job j = read_job(id, false, false);
  if (!is_terminal(j.state()))
    throw JobError(JobError::Kind::kPrecondition, finished_only_message(id, j.state()));
  return j;
}

std::pair<v1::Job, bool> JobStore::record_files_deleted(std::int64_t id, std::int64_t bytes,
                                                        std::int64_t now_ms) {
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  const Row r = load_row(id);
  if (!is_terminal(r.state))
    throw JobError(JobError::Kind::kPrecondition, finished_only_message(id, r.state));
  auto st = db_.prepare(
      "UPDATE jobs SET files_deleted_ms = ?2, files_deleted_bytes = ?3 WHERE id = ?1 AND "
      "files_deleted_ms IS NULL");
  st.bind(1, id).bind(2, now_ms).bind(3, bytes).run();
  const bool now = sqlite3_changes(db_.handle()) > 0;
  v1::Job j = read_job(id, false, true);
  tx.commit();
  return {std::move(j), now};
}

std::optional<v1::ClaimResponse> JobStore::claim(const ClaimInfo& who, std::int64_t now_ms) {
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  std::int64_t id = 0;
  int attempt = 0;
  v1::ClaimResponse out;
  v1::Checkpoint cp;
  bool has_cp = false;
  {
    auto st = db_.prepare(
        "SELECT id, attempt, checkpoint, case_text, study FROM jobs WHERE state = 'QUEUED' "
        "ORDER BY id LIMIT 1");
    if (!st.step()) return std::nullopt;
    id = st.int64(0);
    attempt = static_cast<int>(st.int64(1)) + 1;
    has_cp = !st.is_null(2);
    if (has_cp) parse_blob(st, 2, &cp);
    out.set_case_text(st.text(3));
    if (!st.is_null(4)) parse_blob(st, 4, out.mutable_study());
  }
  if (out.has_study()) {
    // A study's later attempt reuses the levels its earlier attempts finished.
    auto st = db_.prepare("SELECT output_dir FROM attempts WHERE job_id = ?1 ORDER BY number DESC");
    st.bind(1, id);
    while (st.step()) out.add_previous_output_dirs(st.text(0));
  }
  const std::string job_id = format_job_id(id);
  const std::int64_t lease = now_ms + options_.lease_ms;
  out.set_job_id(job_id);
  out.set_attempt(attempt);
  out.set_lease_expires_unix_ms(lease);
  out.set_lease_seconds(static_cast<double>(options_.lease_ms) / 1000.0);
  out.set_output_dir(layout_.attempt_dir(job_id, attempt).string());
  if (has_cp) {
    out.set_resume_from(cp.path());
    out.set_previous_result((layout_.attempt_dir(job_id, cp.attempt()) / "result.h5").string());
  }
  db_.prepare(
         "INSERT INTO attempts (job_id, number, pool, ranks, hostname, started_ms, "
         "resumed_from, output_dir) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)")
      .bind(1, id)
      .bind(2, attempt)
      .bind(3, who.pool)
      .bind(4, who.ranks)
      .bind(5, who.hostname)
      .bind(6, now_ms)
      .bind(7, out.resume_from())
      .bind(8, out.output_dir())
      .run();
  db_.prepare(
         "UPDATE jobs SET attempt = ?2, lease_expires_ms = ?3, started_ms = "
         "COALESCE(started_ms, ?4) WHERE id = ?1")
      .bind(1, id)
      .bind(2, attempt)
      .bind(3, lease)
      .bind(4, now_ms)
      .run();
  std::string reason = "attempt " + std::to_string(attempt) + " on pool " + who.pool + " (" +
                       std::to_string(who.ranks) + " ranks)";
  if (has_cp) reason += ", resuming from step " + std::to_string(cp.step());
  set_state(id, v1::JOB_STATE_RUNNING, reason, attempt, now_ms, who.pool);
  // set_state clears the lease for non-running states only; RUNNING keeps the one set above.
  tx.commit();
  publish();
  return out;
}

v1::ReportResponse JobStore::report(const v1::ReportRequest& r, std::int64_t now_ms) {
  const auto id = parse_job_id(r.job_id());
  if (!id) throw JobError(JobError::Kind::kNotFound, "job_id: no job '" + r.job_id() + "'");
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  const Row row = load_row(*id);
  if (row.state != v1::JOB_STATE_RUNNING || row.attempt != r.attempt())
    throw JobError(JobError::Kind::kStaleAttempt,
                   "attempt " + std::to_string(r.attempt()) + " of " + r.job_id() +
                       " is no longer current (the job is " + state_name(row.state) +
                       " at attempt " + std::to_string(row.attempt) + ")");
  const std::int64_t lease = now_ms + options_.lease_ms;
  db_.prepare("UPDATE jobs SET lease_expires_ms = ?2 WHERE id = ?1")
      .bind(1, *id)
      .bind(2, lease)
      .run();
  for (const auto& cp : r.checkpoints()) store_checkpoint(*id, cp, row.attempt, now_ms);
  if (r.has_progress()) store_progress(*id, r.progress(), now_ms);
  store_log(*id, row.attempt, r.log(), now_ms);
  tx.commit();
  publish();
  v1::ReportResponse out;
  out.set_cancel_requested(row.cancel_requested);
  out.set_lease_expires_unix_ms(lease);
  return out;
}

v1::JobState JobStore::finish(const v1::FinishRequest& r, std::int64_t now_ms) {
  const auto id = parse_job_id(r.job_id());
  if (!id) throw JobError(JobError::Kind::kNotFound, "job_id: no job '" + r.job_id() + "'");
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  const Row row = load_row(*id);
  const std::string attempt_name = "attempt " + std::to_string(r.attempt()) + " of " + r.job_id();
  std::string pool;
  {
    auto st = db_.prepare("SELECT outcome, pool FROM attempts WHERE job_id = ?1 AND number = ?2");
    st.bind(1, *id).bind(2, r.attempt());
    if (!st.step()) throw JobError(JobError::Kind::kStaleAttempt, attempt_name + " does not exist");
    const v1::AttemptOutcome ended = outcome_from_text(st.text(0));
    pool = st.text(1);
    if (ended == r.outcome()) return row.state;  // a retry of a Finish that was committed
    if (ended != v1::ATTEMPT_OUTCOME_UNSPECIFIED)
      throw JobError(JobError::Kind::kStaleAttempt,
                     attempt_name + " has already ended (" + outcome_name(ended) + ")");
  }
  if (row.state != v1::JOB_STATE_RUNNING || row.attempt != r.attempt())
    throw JobError(JobError::Kind::kStaleAttempt, attempt_name + " is no longer current");

  if (r.has_checkpoint() && !r.checkpoint().path().empty())
    store_checkpoint(*id, r.checkpoint(), r.attempt(), now_ms);
  if (r.has_progress()) store_progress(*id, r.progress(), now_ms);
  store_log(*id, r.attempt(), r.log(), now_ms);
  if (r.files_size() > 0) {
    v1::ResultManifest m;
    m.set_attempt(r.attempt());
    m.set_output_dir(layout_.attempt_dir(r.job_id(), r.attempt()).string());
    *m.mutable_files() = r.files();
    db_.prepare("UPDATE jobs SET result = ?2 WHERE id = ?1")
        .bind(1, *id)
        .bind_blob(2, m.SerializeAsString())
        .run();
    v1::JobEvent e;
    *e.mutable_result_ready() = m;
    append_event(*id, e, now_ms);
  }

  const std::string msg = r.message();
  v1::JobState next = v1::JOB_STATE_FAILED;
  std::string reason;
  switch (r.outcome()) {
    case v1::ATTEMPT_COMPLETED:
      next = v1::JOB_STATE_SUCCEEDED;
      reason = msg.empty() ? "completed" : msg;
      break;
    case v1::ATTEMPT_FAILED:
      next = v1::JOB_STATE_FAILED;
      reason = msg.empty() ? "failed (the pool gave no diagnosis)" : msg;
      break;
    case v1::ATTEMPT_CANCELLED:
      next = v1::JOB_STATE_CANCELLED;
      reason = "cancelled" + (msg.empty() ? std::string() : ": " + msg);
      break;
    case v1::ATTEMPT_INTERRUPTED:
      if (row.cancel_requested) {
        next = v1::JOB_STATE_CANCELLED;
        reason = "cancelled: the pool was interrupted after the cancel request";
      } else {
        next = v1::JOB_STATE_QUEUED;
        reason = attempt_name + " was interrupted on pool " + pool +
                 (msg.empty() ? "" : " (" + msg + ")") + "; " +
                 resume_phrase(read_job(*id, false, false));
      }
      break;
    default:
      throw JobError(JobError::Kind::kInvalid,
                     "outcome: must be COMPLETED, FAILED, CANCELLED or INTERRUPTED");
  }
  end_attempt(*id, r.attempt(), r.outcome(), msg, now_ms, &r.unit_seconds());
  set_state(*id, next, reason, r.attempt(), now_ms, pool);
  tx.commit();
  publish();
  return next;
}

int JobStore::expire_leases(std::int64_t now_ms) {
  std::lock_guard lock(mu_);
  pending_events_.clear();
  WriteTransaction tx(db_);
  std::vector<Row> expired;
  {
    auto st = db_.prepare(
        "SELECT id, attempt, cancel_requested FROM jobs WHERE state = 'RUNNING' AND "
        "lease_expires_ms < ?1");
    st.bind(1, now_ms);
    while (st.step())
      expired.push_back(
          {st.int64(0), v1::JOB_STATE_RUNNING, static_cast<int>(st.int64(1)), st.int64(2) != 0});
  }
  for (const Row& r : expired) {
    std::string pool;
    {
      auto st = db_.prepare("SELECT pool FROM attempts WHERE job_id = ?1 AND number = ?2");
      st.bind(1, r.id).bind(2, r.attempt);
      if (st.step()) pool = st.text(0);
    }
    const std::string lost_why = "no report from pool " + pool + " within the lease (" +
                                 number_text(static_cast<double>(options_.lease_ms) / 1000.0) +
                                 " s)";
    end_attempt(r.id, r.attempt, v1::ATTEMPT_LEASE_EXPIRED, lost_why, now_ms);
    std::int64_t lost = 0;
    {
      auto st = db_.prepare(
          "SELECT COUNT(*) FROM attempts WHERE job_id = ?1 AND outcome = 'LEASE_EXPIRED'");
      st.bind(1, r.id);
      st.step();
      lost = st.int64(0);
    }
    const std::string job_id = format_job_id(r.id);
    if (r.cancel_requested) {
      set_state(r.id, v1::JOB_STATE_CANCELLED,
                "cancelled; the pool stopped reporting before it confirmed (" + lost_why + ")",
                r.attempt, now_ms, pool);
    } else if (lost >= options_.max_lost_leases) {
      set_state(r.id, v1::JOB_STATE_FAILED,
                "lost its pool " + std::to_string(lost) + " times (the last: " + lost_why +
                    "); not retried again",
                r.attempt, now_ms, pool);
    } else {
      set_state(r.id, v1::JOB_STATE_QUEUED,
                "attempt " + std::to_string(r.attempt) + " lost: " + lost_why + "; " +
                    resume_phrase(read_job(r.id, false, false)),
                r.attempt, now_ms, pool);
    }
  }
  tx.commit();
  publish();
  return static_cast<int>(expired.size());
}

void JobStore::renew_all_leases(std::int64_t now_ms) {
  std::lock_guard lock(mu_);
  WriteTransaction tx(db_);
  db_.prepare("UPDATE jobs SET lease_expires_ms = ?1 WHERE state = 'RUNNING'")
      .bind(1, now_ms + options_.lease_ms)
      .run();
  tx.commit();
}

std::vector<v1::JobEvent> JobStore::events_after(std::int64_t id, std::int64_t after, int limit) {
  std::lock_guard lock(mu_);
  std::vector<v1::JobEvent> out;
  auto st = db_.prepare(
      "SELECT payload FROM events WHERE job_id = ?1 AND sequence > ?2 ORDER BY sequence "
      "LIMIT ?3");
  st.bind(1, id).bind(2, after).bind(3, limit);
  while (st.step()) {
    out.emplace_back();
    out.back().ParseFromString(st.blob(0));
  }
  return out;
}

v1::JobState JobStore::state(std::int64_t id) {
  std::lock_guard lock(mu_);
  return load_row(id).state;
}

}  // namespace sph::server::store
