// The job store on a real SQLite file: exactly-once submission, leases and fencing, terminal
// states with reasons, the append-only event log and schema versioning. Times are passed in,
// so lease expiry needs no sleeping.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "server/common/job_state.h"
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
    raw.exec("PRAGMA user_version = 1");
  }
  open();  // migrates to the current version
  EXPECT_EQ(current_schema_version(), 4);
  {
    Database raw(db());
    auto st = raw.prepare("PRAGMA user_version");
    st.step();
    EXPECT_EQ(st.int64(0), 4);
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
  for (int i = 0; i < 5; ++i) submit("r" + std::to_string(i));
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
