// The job store on a real SQLite file: exactly-once submission, group commit of concurrent
// submits, queue limits, leases and fencing, terminal states with reasons, the append-only
// event log and schema versioning. Times are passed in, so lease expiry needs no sleeping.
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
#include <latch>
#include <map>
#include <set>
#include <thread>
#include <variant>

#include "common/job_state.h"
#include "server/events/event_feed.h"
#include "server/lease_reaper.h"
#include "server/store/job_store.h"
#include "server/store/schema.h"
#include "server/store/sqlite.h"

namespace sph::server::store {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kLeaseMs = 1000;
constexpr std::int64_t kT0 = 1'700'000'000'000;

// What one submit came back with: the result, or the error's kind and message.
struct Outcome {
  std::optional<SubmitResult> result;
  std::string error;  // "conflict: ...", "queue full: ..." or "sqlite: ..."
};

Outcome submit_outcome(JobStore& store, const NewJob& job, const QueueLimits& limits = {}) {
  Outcome o;
  try {
    o.result = store.submit(job, kT0, limits);
  } catch (const JobError& e) {
    o.error = (e.kind() == JobError::Kind::kRequestConflict ? "conflict: " : "job error: ") +
              std::string(e.what());
  } catch (const QueueFull& e) {
    o.error = e.what();
  } catch (const SqliteError& e) {
    o.error = std::string("sqlite: ") + e.what();
  }
  return o;
}

// Holds the database's write lock from a second connection: the store's next batch waits in
// BEGIN IMMEDIATE (for up to its busy timeout) while more submits queue up behind it, so a
// test decides which submits share a transaction.
class WriteLockHolder {
 public:
  explicit WriteLockHolder(const std::string& path) : db_(path) { db_.exec("BEGIN IMMEDIATE"); }
  void release() { db_.exec("COMMIT"); }

 private:
  Database db_;
};

class StoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "sphd-store-XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
    open();
  }
  void TearDown() override {
    store_.reset();
    fs::remove_all(dir_);
  }
  void open(int max_lost = 3) {
    store_.reset();
    store_ = std::make_unique<JobStore>(db(), ResultLayout(dir_ + "/results"),
                                        StoreOptions{kLeaseMs, max_lost}, feed_);
  }
  std::string db() const { return dir_ + "/jobs.db"; }

  // Submits `first` while the write lock is held, then `batch` behind it, releases the lock
  // once all of `batch` is queued and returns every outcome (first's, then batch's in order):
  // `batch` is committed as one transaction after first's.
  std::vector<Outcome> submit_as_one_batch(const NewJob& first, const std::vector<NewJob>& batch,
                                           const QueueLimits& limits = {}) {
    WriteLockHolder lock(db());
    const auto before = store_->submit_stats().batches;
    std::vector<std::future<Outcome>> pending;
    pending.push_back(std::async(std::launch::async,
                                 [&, j = first] { return submit_outcome(*store_, j, limits); }));
    wait_for([&] { return store_->submit_stats().committing == 1; });
    for (const NewJob& j : batch) {
      const std::size_t queued = pending.size();
      pending.push_back(
          std::async(std::launch::async, [&, j] { return submit_outcome(*store_, j, limits); }));
      // One at a time, so that the batch keeps the order given.
      wait_for([&] { return store_->submit_stats().waiting == queued; });
    }
    lock.release();
    std::vector<Outcome> out;
    for (auto& f : pending) out.push_back(f.get());
    const auto stats = store_->submit_stats();
    EXPECT_EQ(stats.batches - before, 2) << "the batch was not committed as one";
    return out;
  }

  template <typename Predicate>
  static void wait_for(Predicate done) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(4);
    while (!done()) {
      ASSERT_LT(std::chrono::steady_clock::now(), until) << "timed out";
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  NewJob job(const std::string& request_id, const std::string& text = "name: \"a\"") {
    return NewJob{request_id, "a", text, "sha-of-" + text, 100, ""};
  }
  std::int64_t submit(const std::string& request_id) {
    const auto r = store_->submit(job(request_id), kT0);
    return std::stoll(r.job.id().substr(4));
  }
  v1::ClaimResponse claim(std::int64_t now, const std::string& pool = "pool-a") {
    auto c = store_->claim(ClaimInfo{pool, "host", 2}, now);
    EXPECT_TRUE(c.has_value());
    return c.value_or(v1::ClaimResponse{});
  }
  v1::ReportRequest report_for(const v1::ClaimResponse& c) {
    v1::ReportRequest r;
    r.set_job_id(c.job_id());
    r.set_attempt(c.attempt());
    return r;
  }
  v1::FinishRequest finish_for(const v1::ClaimResponse& c, v1::AttemptOutcome outcome) {
    v1::FinishRequest r;
    r.set_job_id(c.job_id());
    r.set_attempt(c.attempt());
    r.set_outcome(outcome);
    return r;
  }

  std::string dir_;
  EventFeed feed_;
  std::unique_ptr<JobStore> store_;
};

TEST_F(StoreTest, SameRequestIdGivesTheSameJob) {
  const auto first = store_->submit(job("r1"), kT0);
  const auto again = store_->submit(job("r1"), kT0 + 5);
  EXPECT_TRUE(first.created);
  EXPECT_FALSE(again.created);
  EXPECT_EQ(first.job.id(), again.job.id());
  EXPECT_EQ(store_->list({}, 100, 0).jobs.size(), 1u);
}

TEST_F(StoreTest, RequestIdReusedWithAnotherCaseIsAConflict) {
  store_->submit(job("r1", "name: \"a\""), kT0);
  try {
    store_->submit(job("r1", "name: \"b\""), kT0);
    FAIL() << "expected a conflict";
  } catch (const JobError& e) {
    EXPECT_EQ(e.kind(), JobError::Kind::kRequestConflict);
    EXPECT_NE(std::string(e.what()).find("r1"), std::string::npos);
  }
  EXPECT_EQ(store_->list({}, 100, 0).jobs.size(), 1u);
}

// Many submits at once, with request ids repeated (same case: the same job) and reused with
// another case (a conflict): every job is stored once, every caller gets its own answer, and
// the submits share transactions.
TEST_F(StoreTest, ConcurrentSubmitsAreStoredOnceAndShareTransactions) {
  constexpr int kUnique = 64, kRepeated = 16, kConflicting = 8;
  std::vector<NewJob> jobs;
  for (int i = 0; i < kUnique; ++i) jobs.push_back(job("u" + std::to_string(i)));
  for (int i = 0; i < kRepeated; ++i)
    for (int k = 0; k < 2; ++k) jobs.push_back(job("d" + std::to_string(i)));
  for (int i = 0; i < kConflicting; ++i) {
    jobs.push_back(job("c" + std::to_string(i), "name: \"a\""));
    jobs.push_back(job("c" + std::to_string(i), "name: \"b\""));
  }
  const int n = static_cast<int>(jobs.size());
  std::vector<Outcome> outcomes(jobs.size());
  std::latch start(n);
  std::vector<std::thread> threads;
  for (int i = 0; i < n; ++i)
    threads.emplace_back([&, i] {
      start.arrive_and_wait();
      outcomes[static_cast<size_t>(i)] = submit_outcome(*store_, jobs[static_cast<size_t>(i)]);
    });
  for (auto& t : threads) t.join();

  std::map<std::string, std::vector<const Outcome*>> by_request;
  for (int i = 0; i < n; ++i)
    by_request[jobs[static_cast<size_t>(i)].request_id].push_back(
        &outcomes[static_cast<size_t>(i)]);
  std::set<std::string> job_ids;
  for (const auto& [request_id, answers] : by_request) {
    int created = 0, conflicts = 0;
    std::set<std::string> ids;
    for (const Outcome* o : answers) {
      if (o->result) {
        created += o->result->created;
        ids.insert(o->result->job.id());
        EXPECT_EQ(o->result->job.request_id(), request_id);
      } else {
        EXPECT_EQ(o->error.rfind("conflict: ", 0), 0u) << request_id << ": " << o->error;
        EXPECT_NE(o->error.find("'" + request_id + "'"), std::string::npos) << o->error;
        ++conflicts;
      }
    }
    EXPECT_EQ(created, 1) << request_id;
    EXPECT_EQ(ids.size(), 1u) << request_id << " answered with different jobs";
    EXPECT_EQ(conflicts, request_id[0] == 'c' ? 1 : 0) << request_id;
    job_ids.insert(ids.begin(), ids.end());
  }
  const auto stored = store_->list({}, 1000, 0).jobs;
  EXPECT_EQ(stored.size(), by_request.size());
  EXPECT_EQ(job_ids.size(), by_request.size());
  std::set<std::string> stored_requests;
  for (const auto& j : stored) {
    stored_requests.insert(j.request_id());
    const auto events = store_->events_after(std::stoll(j.id().substr(4)), 0, 10);
    ASSERT_EQ(events.size(), 1u) << j.id();
    EXPECT_EQ(events[0].state_change().state(), v1::JOB_STATE_QUEUED);
  }
  EXPECT_EQ(stored_requests.size(), by_request.size());

  const auto stats = store_->submit_stats();
  std::printf("%d concurrent submits: %lld transactions, the largest of %zu submits\n", n,
              static_cast<long long>(stats.batches), stats.largest);
  EXPECT_EQ(stats.requests, n);
  EXPECT_LT(stats.batches, n);
  EXPECT_GT(stats.largest, 1u);
}

// The job a submit returns is built without reading the row back: it must be the stored one.
TEST_F(StoreTest, SubmitReturnsTheStoredJob) {
  v1::StudySpec spec;
  spec.set_refine(3);
  NewJob study = job("study", "name: \"s\"");
  study.study = spec.SerializeAsString();
  for (const NewJob& j : {job("plain"), study}) {
    const auto submitted = store_->submit(j, kT0 + 7);
    ASSERT_TRUE(submitted.created);
    const v1::Job stored = store_->get(std::stoll(submitted.job.id().substr(4)), false);
    std::string diff;
    google::protobuf::util::MessageDifferencer d;
    d.ReportDifferencesToString(&diff);
    EXPECT_TRUE(d.Compare(submitted.job, stored)) << diff;
    EXPECT_EQ(stored.last_event_sequence(), 1);
    const auto again = store_->submit(j, kT0 + 8);
    EXPECT_FALSE(again.created);
    EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(again.job, stored));
  }
}

// A transaction that fails fails every submit in it, stores nothing of it, and leaves the
// batches before and after alone.
TEST_F(StoreTest, AFailedTransactionFailsItsWholeBatchAndNothingElse) {
  {
    Database raw(db());
    raw.exec(
        "CREATE TRIGGER poison BEFORE INSERT ON jobs WHEN NEW.request_id = 'poison' "
        "BEGIN SELECT RAISE(ABORT, 'poisoned request'); END");
  }
  const auto out = submit_as_one_batch(job("first"), {job("b1"), job("poison"), job("b2")});
  ASSERT_EQ(out.size(), 4u);
  ASSERT_TRUE(out[0].result) << out[0].error;
  EXPECT_TRUE(out[0].result->created);
  for (size_t i = 1; i < out.size(); ++i) {
    EXPECT_FALSE(out[i].result) << i;
    EXPECT_NE(out[i].error.find("poisoned request"), std::string::npos)
        << i << ": " << out[i].error;
  }
  std::set<std::string> stored;
  for (const auto& j : store_->list({}, 100, 0).jobs) stored.insert(j.request_id());
  EXPECT_EQ(stored, std::set<std::string>({"first"}));
  // The next batch is not affected (and b1 can be submitted again).
  EXPECT_TRUE(store_->submit(job("b1"), kT0).created);
  EXPECT_EQ(store_->list({}, 100, 0).jobs.size(), 2u);
  EXPECT_EQ(store_->events_after(2, 0, 10).size(), 1u);
}

TEST_F(StoreTest, TheQueuedJobsLimitCountsTheJobsOfTheSameBatch) {
  const QueueLimits limits{3, 0};
  store_->submit(job("old"), kT0, limits);
  const auto out =
      submit_as_one_batch(job("first"), {job("q1"), job("q2"), job("old"), job("q3")}, limits);
  ASSERT_TRUE(out[0].result && out[0].result->created);
  ASSERT_TRUE(out[1].result && out[1].result->created);  // the third job
  const std::string full =
      "queue full: 3 jobs are queued or running; the limit is 3 (--max-queued-jobs)";
  EXPECT_EQ(out[2].error, full);
  // A request id stored before is answered, full or not.
  ASSERT_TRUE(out[3].result) << out[3].error;
  EXPECT_FALSE(out[3].result->created);
  EXPECT_EQ(out[3].result->job.request_id(), "old");
  EXPECT_EQ(out[4].error, full);
  EXPECT_EQ(store_->list({}, 100, 0).jobs.size(), 3u);
  std::printf("%s\n", full.c_str());

  // Running jobs count; a finished one frees its place.
  const auto c = claim(kT0);
  EXPECT_EQ(submit_outcome(*store_, job("q4"), limits).error, full);
  store_->finish(finish_for(c, v1::ATTEMPT_COMPLETED), kT0 + 1);
  EXPECT_TRUE(store_->submit(job("q4"), kT0, limits).created);
  EXPECT_EQ(submit_outcome(*store_, job("q5"), limits).error, full);
  store_->cancel(3, "", kT0 + 2);
  EXPECT_TRUE(store_->submit(job("q5"), kT0, limits).created);
  // Without a limit nothing is refused.
  EXPECT_TRUE(store_->submit(job("q6"), kT0).created);
}

TEST_F(StoreTest, TheQueuedParticlesLimitCountsTheJobsOfTheSameBatch) {
  const QueueLimits limits{0, 250};  // each job() is estimated at 100 particles
  const auto out = submit_as_one_batch(job("first"), {job("p1"), job("p2"), job("p3")}, limits);
  ASSERT_TRUE(out[0].result && out[0].result->created);
  ASSERT_TRUE(out[1].result && out[1].result->created);
  const std::string full =
      "queue full: queued and running jobs are estimated at 200 particles and this case at "
      "100; the limit is 250 (--max-queued-particles)";
  EXPECT_EQ(out[2].error, full);
  EXPECT_EQ(out[3].error, full);
  std::printf("%s\n", full.c_str());
  NewJob small = job("small");
  small.estimated_particles = 50;
  EXPECT_TRUE(store_->submit(small, kT0, limits).created);
  const auto c = claim(kT0);
  store_->finish(finish_for(c, v1::ATTEMPT_FAILED), kT0 + 1);
  EXPECT_TRUE(store_->submit(job("p2"), kT0, limits).created);
  EXPECT_EQ(store_->list({}, 100, 0).jobs.size(), 4u);
}

TEST_F(StoreTest, PreparedStatementsAreKeptAndLentOneAtATime) {
  Database raw(db());
  const auto count = [&](const std::string& sql) {
    auto st = raw.prepare(sql);
    st.step();
    return st.int64(0);
  };
  const auto cached = raw.cached_statements();
  submit("a");
  submit("b");
  EXPECT_EQ(count("SELECT COUNT(*) FROM jobs"), 2);
  EXPECT_EQ(count("SELECT COUNT(*) FROM jobs"), 2);
  EXPECT_EQ(raw.cached_statements(), cached + 1);
  // The same text again while the first is still lent (and half stepped): a statement of its
  // own; the bindings of a returned statement are cleared.
  auto outer = raw.prepare("SELECT id FROM jobs WHERE id >= ?1 ORDER BY id");
  outer.bind(1, 1);
  ASSERT_TRUE(outer.step());
  {
    auto inner = raw.prepare("SELECT id FROM jobs WHERE id >= ?1 ORDER BY id");
    inner.bind(1, 2);
    ASSERT_TRUE(inner.step());
    EXPECT_EQ(inner.int64(0), 2);
  }
  EXPECT_EQ(outer.int64(0), 1);
  ASSERT_TRUE(outer.step());
  EXPECT_EQ(outer.int64(0), 2);
  EXPECT_FALSE(outer.step());
}

TEST_F(StoreTest, ClaimsOldestFirstAndEmptyQueueGivesNothing) {
  const auto a = submit("a");
  const auto b = submit("b");
  EXPECT_EQ(claim(kT0).job_id(), "job-" + std::to_string(a));
  EXPECT_EQ(claim(kT0).job_id(), "job-" + std::to_string(b));
  EXPECT_FALSE(store_->claim(ClaimInfo{"p", "h", 1}, kT0).has_value());
}

TEST_F(StoreTest, ExpiredLeaseRequeuesWithCheckpointAndFencesTheOldAttempt) {
  const auto id = submit("a");
  const auto c1 = claim(kT0);
  EXPECT_EQ(c1.attempt(), 1);
  EXPECT_TRUE(c1.resume_from().empty());
  const std::string cp = c1.output_dir() + "/checkpoints/ckpt_10.h5";
  auto r = report_for(c1);
  r.add_checkpoints()->set_path(cp);
  r.mutable_checkpoints(0)->set_step(10);
  store_->report(r, kT0 + 500);  // renews the lease to kT0 + 1500

  EXPECT_EQ(store_->expire_leases(kT0 + 1400), 0);
  EXPECT_EQ(store_->expire_leases(kT0 + 1600), 1);
  const auto j = store_->get(id, false);
  EXPECT_EQ(j.state(), v1::JOB_STATE_QUEUED);
  EXPECT_NE(j.reason().find("step 10"), std::string::npos) << j.reason();
  ASSERT_EQ(j.attempts_size(), 1);
  EXPECT_EQ(j.attempts(0).outcome(), v1::ATTEMPT_LEASE_EXPIRED);

  const auto c2 = claim(kT0 + 1700, "pool-b");
  EXPECT_EQ(c2.attempt(), 2);
  EXPECT_EQ(c2.resume_from(), cp);
  EXPECT_EQ(c2.previous_result(), c1.output_dir() + "/result.h5");

  // The first pool comes back: everything it says is refused.
  try {
    store_->report(report_for(c1), kT0 + 1800);
    FAIL() << "a stale report was accepted";
  } catch (const JobError& e) {
    EXPECT_EQ(e.kind(), JobError::Kind::kStaleAttempt);
  }
  try {
    store_->finish(finish_for(c1, v1::ATTEMPT_COMPLETED), kT0 + 1800);
    FAIL() << "a stale finish was accepted";
  } catch (const JobError& e) {
    EXPECT_EQ(e.kind(), JobError::Kind::kStaleAttempt);
  }
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_RUNNING);
  EXPECT_EQ(store_->finish(finish_for(c2, v1::ATTEMPT_COMPLETED), kT0 + 1900),
            v1::JOB_STATE_SUCCEEDED);
}

TEST_F(StoreTest, FinishIsIdempotentForTheSameAttempt) {
  submit("a");
  const auto c = claim(kT0);
  EXPECT_EQ(store_->finish(finish_for(c, v1::ATTEMPT_COMPLETED), kT0 + 10),
            v1::JOB_STATE_SUCCEEDED);
  const auto events = store_->events_after(1, 0, 100).size();
  EXPECT_EQ(store_->finish(finish_for(c, v1::ATTEMPT_COMPLETED), kT0 + 20),
            v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(store_->events_after(1, 0, 100).size(), events) << "a retried Finish added events";
  EXPECT_THROW(store_->finish(finish_for(c, v1::ATTEMPT_FAILED), kT0 + 30), JobError);
}

TEST_F(StoreTest, ACheckpointReportedTwiceIsOneEvent) {
  const auto id = submit("a");
  const auto c = claim(kT0);
  auto r = report_for(c);
  r.add_checkpoints()->set_path(c.output_dir() + "/checkpoints/ckpt_5.h5");
  store_->report(r, kT0 + 1);
  auto f = finish_for(c, v1::ATTEMPT_COMPLETED);
  *f.mutable_checkpoint() = r.checkpoints(0);  // Finish repeats the newest checkpoint
  store_->finish(f, kT0 + 2);
  int checkpoints = 0;
  for (const auto& e : store_->events_after(id, 0, 100)) checkpoints += e.has_checkpoint();
  EXPECT_EQ(checkpoints, 1);
}

TEST_F(StoreTest, InterruptedAttemptGoesBackToTheQueueAtOnce) {
  const auto id = submit("a");
  const auto c = claim(kT0);
  auto f = finish_for(c, v1::ATTEMPT_INTERRUPTED);
  f.mutable_checkpoint()->set_path(c.output_dir() + "/checkpoints/ckpt_7.h5");
  f.mutable_checkpoint()->set_step(7);
  EXPECT_EQ(store_->finish(f, kT0 + 10), v1::JOB_STATE_QUEUED);
  EXPECT_EQ(claim(kT0 + 20).resume_from(), c.output_dir() + "/checkpoints/ckpt_7.h5");
  EXPECT_EQ(store_->get(id, false).attempts_size(), 2);
}

TEST_F(StoreTest, CancelIsIdempotentAndEndsQueuedJobsAtOnce) {
  const auto running = submit("a");
  const auto queued = submit("b");
  const auto c = claim(kT0);  // the oldest: `running`

  const auto j1 = store_->cancel(queued, "", kT0 + 1);
  EXPECT_EQ(j1.state(), v1::JOB_STATE_CANCELLED);
  EXPECT_FALSE(j1.reason().empty());
  const auto events = store_->events_after(queued, 0, 100).size();
  EXPECT_EQ(store_->cancel(queued, "", kT0 + 2).state(), v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(store_->events_after(queued, 0, 100).size(), events);

  const auto j2 = store_->cancel(running, "user", kT0 + 3);
  EXPECT_EQ(j2.state(), v1::JOB_STATE_RUNNING);
  EXPECT_TRUE(j2.cancel_requested());
  store_->cancel(running, "user", kT0 + 4);
  EXPECT_TRUE(store_->report(report_for(c), kT0 + 5).cancel_requested());
  EXPECT_EQ(store_->finish(finish_for(c, v1::ATTEMPT_CANCELLED), kT0 + 6), v1::JOB_STATE_CANCELLED);
  int cancel_events = 0;
  for (const auto& e : store_->events_after(running, 0, 100))
    cancel_events += e.has_cancel_requested();
  EXPECT_EQ(cancel_events, 1);
}

TEST_F(StoreTest, LostTooOftenFailsWithAReason) {
  open(/*max_lost=*/2);
  const auto id = submit("a");
  claim(kT0);
  store_->expire_leases(kT0 + 2 * kLeaseMs);
  claim(kT0 + 3 * kLeaseMs);
  store_->expire_leases(kT0 + 5 * kLeaseMs);
  const auto j = store_->get(id, false);
  EXPECT_EQ(j.state(), v1::JOB_STATE_FAILED);
  EXPECT_NE(j.reason().find("2 times"), std::string::npos) << j.reason();
}

TEST_F(StoreTest, EventsAreNumberedWithoutGapsAndAppendOnly) {
  const auto id = submit("a");
  const auto c = claim(kT0);
  auto r = report_for(c);
  r.mutable_progress()->set_step(5);
  store_->report(r, kT0 + 1);
  store_->finish(finish_for(c, v1::ATTEMPT_COMPLETED), kT0 + 2);
  const auto events = store_->events_after(id, 0, 100);
  ASSERT_EQ(events.size(), 4u);  // QUEUED, RUNNING, progress, SUCCEEDED
  for (size_t i = 0; i < events.size(); ++i)
    EXPECT_EQ(events[i].sequence(), static_cast<int>(i + 1));
  EXPECT_EQ(store_->events_after(id, 2, 100).front().sequence(), 3);
  EXPECT_EQ(events.back().state_change().state(), v1::JOB_STATE_SUCCEEDED);

  store_.reset();
  Database raw(db());
  EXPECT_THROW(raw.exec("UPDATE events SET kind = 'x'"), SqliteError);
  EXPECT_THROW(raw.exec("DELETE FROM events"), SqliteError);
}

TEST_F(StoreTest, TerminalStatesNeedAReason) {
  submit("a");
  store_.reset();
  Database raw(db());
  EXPECT_THROW(raw.exec("UPDATE jobs SET state = 'FAILED', reason = ''"), SqliteError);
}

TEST_F(StoreTest, StateSurvivesReopeningAndLeasesAreRenewed) {
  const auto id = submit("a");
  claim(kT0);
  open();
  store_->renew_all_leases(kT0 + 10 * kLeaseMs);
  EXPECT_EQ(store_->expire_leases(kT0 + 10 * kLeaseMs + kLeaseMs / 2), 0);
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_RUNNING);
}

// Lease deadlines are wall-clock times; the reaper notices a step of the wall clock against
// the monotonic one and renews every running lease instead of expiring them all at once
// (forward) or keeping a dead pool's job for as long as the step (back).
TEST_F(StoreTest, AWallClockStepGivesRunningJobsAFreshLease) {
  using namespace std::chrono_literals;
  const auto id = submit("a");
  claim(kT0);
  LeaseReaper reaper(*store_, 1h);  // its own rounds come too late to matter; the test drives
  const auto s0 = std::chrono::steady_clock::now();
  reaper.check(kT0 + 100, s0);
  // The clock is stepped an hour forward while 200 ms pass.
  const std::int64_t t1 = kT0 + 300 + 3'600'000;
  reaper.check(t1, s0 + 200ms);
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_RUNNING);
  // Without a step the lease runs out as usual.
  const std::int64_t t2 = t1 + kLeaseMs + 100;
  reaper.check(t2, s0 + 200ms + std::chrono::milliseconds(kLeaseMs + 100));
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_QUEUED);

  // Claimed again, then the clock is stepped an hour back: the lease still ends one lease
  // after the step, not an hour later.
  claim(t2);
  const auto s2 = s0 + 200ms + std::chrono::milliseconds(kLeaseMs + 100);
  reaper.check(t2 + 10 - 3'600'000, s2 + 10ms);
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_RUNNING);
  reaper.check(t2 + 20 - 3'600'000 + kLeaseMs + 100,
               s2 + 20ms + std::chrono::milliseconds(kLeaseMs + 100));
  EXPECT_EQ(store_->get(id, false).state(), v1::JOB_STATE_QUEUED);
}

TEST_F(StoreTest, RefusesADatabaseFromANewerRelease) {
  store_.reset();
  {
    Database raw(db());
    raw.exec("PRAGMA user_version = " + std::to_string(current_schema_version() + 1));
  }
  EXPECT_THROW(open(), SqliteError);
}

TEST_F(StoreTest, MigratesAVersion1DatabaseAndKeepsStudiesWithTheirJobs) {
  // A database of the first release: no jobs.study column (migration 2), no record of
  // deleted files (migration 3) and no identity (migration 4), user_version 1.
  const auto old_job = submit("before");
  store_.reset();
  {
    Database raw(db());
    raw.exec("ALTER TABLE jobs DROP COLUMN study");
    raw.exec("ALTER TABLE jobs DROP COLUMN files_deleted_ms");
    raw.exec("ALTER TABLE jobs DROP COLUMN files_deleted_bytes");
    raw.exec("DROP TABLE meta");
    raw.exec("DROP TABLE log_lines");
    raw.exec("ALTER TABLE attempts DROP COLUMN log_bytes");
    raw.exec("ALTER TABLE attempts DROP COLUMN log_dropped");
    raw.exec("PRAGMA user_version = 1");
  }
  open();  // migrates to the current version
  EXPECT_EQ(current_schema_version(), 5);
  {
    Database raw(db());
    auto st = raw.prepare("PRAGMA user_version");
    st.step();
    EXPECT_EQ(st.int64(0), 5);
  }
  EXPECT_EQ(store_->database_id().size(), 32u);
  EXPECT_TRUE(store_->has_jobs());
  const v1::Job before = store_->get(old_job, true);
  EXPECT_EQ(before.state(), v1::JOB_STATE_QUEUED);
  EXPECT_FALSE(before.has_study());
  EXPECT_EQ(before.files_deleted_unix_ms(), 0);

  // A study job keeps its ladder, and every attempt after the first learns where the earlier
  // ones wrote (their finished levels are reused).
  v1::StudySpec spec;
  spec.set_refine(4);
  spec.set_ratio(2);
  NewJob study = job("study", "name: \"s\"");
  study.study = spec.SerializeAsString();
  const auto submitted = store_->submit(study, kT0);
  ASSERT_TRUE(submitted.job.has_study());
  EXPECT_EQ(submitted.job.study().refine(), 4);
  EXPECT_EQ(submitted.job.study().ratio(), 2);
  claim(kT0);  // the older plain job
  const auto first = claim(kT0);
  EXPECT_EQ(first.job_id(), submitted.job.id());
  ASSERT_TRUE(first.has_study());
  EXPECT_EQ(first.previous_output_dirs_size(), 0);
  EXPECT_EQ(store_->expire_leases(kT0 + 2 * kLeaseMs), 2);
  claim(kT0 + 3 * kLeaseMs);
  const auto second = claim(kT0 + 3 * kLeaseMs);
  EXPECT_EQ(second.job_id(), submitted.job.id());
  EXPECT_EQ(second.attempt(), 2);
  ASSERT_EQ(second.previous_output_dirs_size(), 1);
  EXPECT_EQ(second.previous_output_dirs(0), first.output_dir());
  EXPECT_EQ(store_->list({}, 10, 0).jobs.front().study().refine(), 4);
}

TEST_F(StoreTest, DeletedFilesAreRecordedOnceAndOnlyForAFinishedJob) {
  const auto id = submit("a");
  auto refused = [&](const char* when) {
    try {
      store_->record_files_deleted(id, 1, kT0);
      ADD_FAILURE() << "recorded for a job that is " << when;
    } catch (const JobError& e) {
      EXPECT_EQ(e.kind(), JobError::Kind::kPrecondition);
      EXPECT_NE(std::string(e.what()).find("cancel it first"), std::string::npos) << e.what();
    }
    EXPECT_THROW(store_->get_finished(id), JobError) << when;
  };
  refused("queued");
  const auto c = claim(kT0);
  refused("running");
  EXPECT_EQ(store_->finish(finish_for(c, v1::ATTEMPT_COMPLETED), kT0 + 10),
            v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(store_->get_finished(id).state(), v1::JOB_STATE_SUCCEEDED);
  const std::int64_t last_event = store_->get(id, false).last_event_sequence();

  const auto [first, first_now] = store_->record_files_deleted(id, 12345, kT0 + 20);
  EXPECT_TRUE(first_now);
  EXPECT_EQ(first.files_deleted_unix_ms(), kT0 + 20);
  EXPECT_EQ(first.files_deleted_bytes(), 12345);
  EXPECT_EQ(first.state(), v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(first.attempts_size(), 1);
  // A second call changes nothing; the history has no new event (it ended with the job).
  const auto [second, second_now] = store_->record_files_deleted(id, 0, kT0 + 30);
  EXPECT_FALSE(second_now);
  EXPECT_EQ(second.files_deleted_unix_ms(), kT0 + 20);
  EXPECT_EQ(second.files_deleted_bytes(), 12345);
  EXPECT_EQ(second.last_event_sequence(), last_event);
  open();
  const v1::Job reopened = store_->get(id, false);
  EXPECT_EQ(reopened.files_deleted_unix_ms(), kT0 + 20);
  EXPECT_EQ(reopened.files_deleted_bytes(), 12345);
  EXPECT_EQ(store_->list({}, 10, 0).jobs.front().files_deleted_bytes(), 12345);
}

TEST_F(StoreTest, ListsNewestFirstInPagesAndByState) {
  for (const char* id : {"r0", "r1", "r2", "r3", "r4"}) submit(id);
  claim(kT0);
  const auto p1 = store_->list({}, 2, 0);
  ASSERT_EQ(p1.jobs.size(), 2u);
  EXPECT_EQ(p1.jobs[0].id(), "job-5");
  const auto p2 = store_->list({}, 2, p1.next_before);
  EXPECT_EQ(p2.jobs[0].id(), "job-3");
  const auto p3 = store_->list({}, 2, p2.next_before);
  EXPECT_EQ(p3.jobs.size(), 1u);
  EXPECT_EQ(p3.next_before, 0);
  const auto running = store_->list({v1::JOB_STATE_RUNNING}, 10, 0);
  ASSERT_EQ(running.jobs.size(), 1u);
  EXPECT_EQ(running.jobs[0].id(), "job-1");
}

}  // namespace
}  // namespace sph::server::store

namespace sph::server::store {
namespace {

// sphctl logs: lines in order with sequences across attempts, filtered by attempt, and the
// newest kMaxLogBytesPerAttempt bytes of each attempt kept (the end holds the diagnosis).
TEST_F(StoreTest, LogLinesAreKeptPerAttemptUpToTheCap) {
  const auto id = submit("a");
  const auto c1 = claim(kT0);
  auto r = report_for(c1);
  for (const char* text : {"first", "second\nwith a newline"}) r.add_log()->set_text(text);
  store_->report(r, kT0 + 10);
  // The pool is lost; the second attempt writes far more than the cap.
  store_->expire_leases(kT0 + 100000);
  const auto c2 = claim(kT0 + 100001, "pool-b");
  ASSERT_EQ(c2.attempt(), 2);
  const std::string filler(200, 'x');
  int sent = 0;
  for (int call = 0; call < 3; ++call) {
    auto more = report_for(c2);
    for (int i = 0; i < 1000; ++i) more.add_log()->set_text(std::to_string(sent++) + " " + filler);
    store_->report(more, kT0 + 100002 + call);
  }
  auto fin = finish_for(c2, v1::ATTEMPT_FAILED);
  fin.set_message("diagnosis");
  fin.add_log()->set_text("the diagnosis, last");
  store_->finish(fin, kT0 + 100010);

  const auto first = store_->logs(id, 1, 0, 1000);
  ASSERT_EQ(first.lines.size(), 2u);
  EXPECT_EQ(first.lines[0].text(), "first");
  EXPECT_EQ(first.lines[1].text(), "second with a newline");
  EXPECT_EQ(first.lines[0].sequence(), 1);
  EXPECT_EQ(first.dropped_lines, 0);
  EXPECT_EQ(first.state, v1::JOB_STATE_FAILED);

  std::int64_t bytes = 0, count = 0, after = 0, last_seq = 0;
  std::string last;
  while (true) {
    const auto page = store_->logs(id, 2, after, 1000);
    if (page.lines.empty()) break;
    for (const auto& l : page.lines) {
      EXPECT_EQ(l.attempt(), 2);
      EXPECT_GT(l.sequence(), last_seq);
      last_seq = l.sequence();
      bytes += static_cast<std::int64_t>(l.text().size());
      ++count;
      last = l.text();
    }
    after = page.lines.back().sequence();
  }
  const auto dropped = store_->logs(id, 2, 0, 1).dropped_lines;
  std::printf("attempt 2: %lld lines, %lld bytes kept, %lld dropped of %d + 1 sent\n",
              static_cast<long long>(count), static_cast<long long>(bytes),
              static_cast<long long>(dropped), sent);
  EXPECT_LE(bytes, kMaxLogBytesPerAttempt);
  EXPECT_GT(bytes, kMaxLogBytesPerAttempt - 300);
  EXPECT_EQ(count + dropped, sent + 1);
  EXPECT_EQ(last, "the diagnosis, last");
  // Attempt 1's lines were not touched by attempt 2's cap; 0 lists both.
  EXPECT_EQ(store_->logs(id, 0, 0, 2).lines[0].text(), "first");
  EXPECT_THROW(store_->logs(id + 7, 0, 0, 10), JobError);
}

}  // namespace
}  // namespace sph::server::store
