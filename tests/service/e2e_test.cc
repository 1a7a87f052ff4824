// The whole service with real processes: sph-server, `mpirun -np 2 sph-worker --server` pools
// running the real solver on tiny 2D cases, and sphctl.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

#include "common/job_state.h"
#include "harness/service_harness.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;

// The channel case runs about 1500 steps per simulated second on two ranks of this machine
// at a few thousand steps per second; end times below are chosen for run lengths in seconds.
std::string channel(double end_time) {
  return with_end_time(read_test_case("channel_2d.textproto"), end_time);
}

std::string write_case(ServiceHarness& h, const std::string& name, const std::string& text) {
  const std::string path = h.dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

bool has_progress(const v1::Job& j) {
  return j.has_progress() && j.progress().step() > 0;
}

TEST(ServiceEndToEnd, SubmitWatchFetchOnATwoRankPool) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--max-jobs", "1", "--idle-exit", "60"});
  const auto submit =
      h.sphctl({"submit", test_case_path("tiny_dam_break_2d.textproto"), "--watch"}, 120s);
  ASSERT_EQ(submit.exit_code, 0) << submit.out << submit.err << h.logs();
  EXPECT_NE(submit.out.find("submitted job-1"), std::string::npos) << submit.out;
  EXPECT_NE(submit.out.find("RUNNING attempt 1"), std::string::npos) << submit.out;
  EXPECT_NE(submit.out.find("progress step"), std::string::npos) << submit.out;
  EXPECT_NE(submit.out.find("SUCCEEDED"), std::string::npos) << submit.out;

  const auto fetched = h.sphctl({"fetch", "job-1", "-o", h.dir() + "/fetched"});
  ASSERT_EQ(fetched.exit_code, 0) << fetched.err;
  EXPECT_NE(fetched.out.find("sha256 verified"), std::string::npos);
  std::string out;
  EXPECT_EQ(h5check({"snapshots", h.dir() + "/fetched/result.h5", "606", "0", "0.02", "0.04",
                     "0.06", "0.08", "0.1"},
                    h.dir(), out),
            0)
      << out;
  EXPECT_TRUE(fs::exists(h.dir() + "/fetched/result.xmf"));

  const auto status = h.sphctl({"status", "job-1", "--json"});
  EXPECT_EQ(status.exit_code, 0);
  EXPECT_NE(status.out.find("\"state\":\"JOB_STATE_SUCCEEDED\""), std::string::npos) << status.out;
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << "--max-jobs 1 did not end the pool\n" << h.logs();
}

TEST(ServiceEndToEnd, WatchDrawsAProgressBarOnATerminal) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--max-jobs", "1"});
  const auto job = h.submit_text(channel(1));
  // script(1) gives sphctl a pseudo-terminal.
  const std::string command =
      std::string(SPHCTL_BIN) + " --server " + h.address() + " watch " + job.id();
  const auto r = run_command({"/usr/bin/script", "-qfec", command, "/dev/null"}, h.dir(), 120s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("\r\x1b[K" + job.id() + " [#"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("100.0%  t=1/1 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ETA"), std::string::npos);
  EXPECT_NE(r.out.find("SUCCEEDED"), std::string::npos);
}

TEST(ServiceEndToEnd, CancelStopsARunningJobAndKeepsItsPartialOutput) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--idle-exit", "60"});
  const auto job = h.submit_text(channel(200));  // a minute or more if left alone
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, has_progress)) << h.logs();

  const auto t0 = std::chrono::steady_clock::now();
  const auto cancel = h.sphctl({"cancel", job.id(), "--reason", "test"});
  ASSERT_EQ(cancel.exit_code, 0) << cancel.err;
  EXPECT_NE(cancel.out.find("cancel requested"), std::string::npos) << cancel.out;
  ASSERT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_CANCELLED, 10s)) << h.logs();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);

  const auto done = h.get_job(job.id());
  EXPECT_NE(done.reason().find("cancel"), std::string::npos) << done.reason();
  ASSERT_TRUE(done.has_result()) << "the partial output is not in the manifest";
  EXPECT_EQ(done.result().files(0).name(), "result.h5");
  EXPECT_EQ(h.sphctl({"cancel", job.id()}).exit_code, 0) << "cancel is not idempotent";
  EXPECT_EQ(h.sphctl({"watch", job.id()}).exit_code, 11);
  const auto fetched = h.sphctl({"fetch", job.id(), "-o", h.dir() + "/partial"});
  EXPECT_EQ(fetched.exit_code, 0) << fetched.err;
  EXPECT_TRUE(fs::exists(h.dir() + "/partial/result.h5"));
}

TEST(ServiceEndToEnd, KilledPoolsJobResumesFromItsCheckpointOnAnotherPool) {
  ServiceHarness h;
  h.start_server(ServerSettings().lease(2));
  const std::string text = channel(3);
  const auto job = h.submit_text(text);
  auto first = h.start_pool(2, {"--checkpoint-interval", "0.25"}, "pool1");
  // Kill it once the server knows of a checkpoint and before the end.
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, [](const v1::Job& j) {
    return j.has_checkpoint() && j.checkpoint().step() > 0;
  })) << h.logs();
  first.kill_all();  // kill -9 of mpirun and every rank
  ASSERT_NE(h.get_job(job.id()).state(), v1::JOB_STATE_SUCCEEDED) << "the run ended too soon";

  ASSERT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_QUEUED, 15s)) << h.logs();
  auto second = h.start_pool(2, {"--max-jobs", "1"}, "pool2");
  ASSERT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_SUCCEEDED, 120s)) << h.logs();
  const auto done = h.get_job(job.id());
  ASSERT_EQ(done.attempts_size(), 2);
  EXPECT_EQ(done.attempts(0).outcome(), v1::ATTEMPT_LEASE_EXPIRED);
  EXPECT_FALSE(done.attempts(1).resumed_from().empty()) << "the second attempt started over";
  EXPECT_EQ(done.result().attempt(), 2);

  // The resumed result equals an uninterrupted run of the same case.
  const std::string reference = h.dir() + "/reference";
  ASSERT_EQ(h.run_local(2, write_case(h, "case.textproto", text), reference), 0);
  std::string out;
  EXPECT_EQ(h5check({"same", done.result().output_dir() + "/result.h5", reference + "/result.h5"},
                    h.dir(), out),
            0)
      << out;
  EXPECT_EQ(second.wait(30s).value_or(-1), 0);
}

TEST(ServiceEndToEnd, ServerKilledAndRestartedLosesNothing) {
  ServiceHarness h;
  h.start_server(ServerSettings().lease(3));
  auto pool = h.start_pool(2, {"--max-jobs", "2"});
  const auto running = h.submit_text(channel(6));
  const auto queued = h.submit_text(channel(0.5));
  ASSERT_TRUE(h.wait_for_job(running.id(), 60s, has_progress)) << h.logs();

  h.server().kill_all();            // kill -9
  std::this_thread::sleep_for(2s);  // the pool computes on, unable to report
  h.start_server();
  ASSERT_TRUE(h.wait_for_state(running.id(), v1::JOB_STATE_SUCCEEDED, 120s)) << h.logs();
  ASSERT_TRUE(h.wait_for_state(queued.id(), v1::JOB_STATE_SUCCEEDED, 60s)) << h.logs();

  const auto done = h.get_job(running.id());
  EXPECT_EQ(done.attempts_size(), 1) << "the restart cost the running attempt";
  const auto events = h.history(running.id());
  ASSERT_FALSE(events.empty());
  int running_changes = 0, progress = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].sequence(), static_cast<std::int64_t>(i + 1)) << "a gap in the history";
    running_changes +=
        events[i].has_state_change() && events[i].state_change().state() == v1::JOB_STATE_RUNNING;
    progress += events[i].has_progress();
  }
  EXPECT_EQ(events.front().state_change().state(), v1::JOB_STATE_QUEUED);
  EXPECT_EQ(running_changes, 1);
  EXPECT_GE(progress, 2);
  EXPECT_TRUE(events[events.size() - 2].has_result_ready());
  EXPECT_EQ(events.back().state_change().state(), v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

std::vector<fs::path> checkpoint_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".h5") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// A pool cut off from the server computes on and writes checkpoints the server never hears
// of; once its lease expires the server hands the newest checkpoint it knows to the job's
// next attempt. That file must stay: the pool deletes a checkpoint only after the server has
// acknowledged two newer ones (worker/pool/checkpoint_pruner.h). Before, the solver kept the
// two newest files, and the known one was gone two checkpoints after the cut.
TEST(ServiceEndToEnd, ACutOffPoolKeepsTheCheckpointTheServerKnowsOf) {
  ServiceHarness h;
  h.start_server(ServerSettings().lease(3));
  auto pool = h.start_pool(2, {"--checkpoint-interval", "0.2", "--max-jobs", "1"});
  // Long enough to be still running when the server is back: on an idle machine a 12 s
  // channel finished (2.8 s of wall time) before that, and its pool never pruned.
  const auto job = h.submit_text(channel(40));
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, [](const v1::Job& j) {
    return j.has_checkpoint() && j.checkpoint().step() > 0;
  })) << h.logs();
  const fs::path known = h.get_job(job.id()).checkpoint().path();
  h.server().kill_all();  // kill -9: the pool computes on, unable to report
  const fs::path dir = known.parent_path();
  auto newer = [&] {
    const auto all = checkpoint_files(dir);
    return std::count_if(all.begin(), all.end(), [&](const fs::path& p) { return p > known; });
  };
  // Two seconds cut off (about ten checkpoints), and at least two newer files on disk.
  std::this_thread::sleep_for(2s);
  const auto until = std::chrono::steady_clock::now() + scaled(30s);
  while (newer() < 2 && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(50ms);
  ASSERT_GE(newer(), 2) << "the pool wrote no checkpoints while cut off\n" << h.logs();
  EXPECT_TRUE(fs::exists(known)) << "the checkpoint the server knows of was deleted";

  // Back in touch, the server hears of the newer ones and the old ones go, while the job runs
  // on (waiting for it to finish would make the test as slow as the machine is loaded).
  h.start_server();
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, [&](const v1::Job& j) {
    return j.has_checkpoint() && fs::path(j.checkpoint().path()) > known;
  })) << h.logs();
  const auto pruned = std::chrono::steady_clock::now() + scaled(30s);
  while ((fs::exists(known) || checkpoint_files(dir).size() > 3) &&
         std::chrono::steady_clock::now() < pruned)
    std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(fs::exists(known));
  EXPECT_LE(checkpoint_files(dir).size(), 3u);
  const auto running = h.get_job(job.id());
  EXPECT_EQ(running.attempts_size(), 1);
  if (running.state() == v1::JOB_STATE_RUNNING) {
    EXPECT_EQ(h.sphctl({"cancel", job.id()}).exit_code, 0);
    EXPECT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_CANCELLED, 30s)) << h.logs();
  }
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

TEST(ServiceEndToEnd, SignalledPoolCheckpointsAndReleasesItsJob) {
  ServiceHarness h;
  h.start_server();
  const auto job = h.submit_text(channel(200));
  auto first = h.start_pool(2, {}, "pool1");
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, has_progress)) << h.logs();
  first.signal(SIGUSR1);  // mpirun forwards it to every rank at once
  ASSERT_EQ(first.wait(30s).value_or(-1), 0) << h.logs();
  const auto released = h.get_job(job.id());
  EXPECT_EQ(released.state(), v1::JOB_STATE_QUEUED) << released.reason();
  ASSERT_EQ(released.attempts_size(), 1);
  EXPECT_EQ(released.attempts(0).outcome(), v1::ATTEMPT_INTERRUPTED);
  ASSERT_TRUE(released.has_checkpoint());
  EXPECT_GT(released.checkpoint().step(), 0);

  auto second = h.start_pool(2, {}, "pool2");
  ASSERT_TRUE(h.wait_for_job(job.id(), 60s, [](const v1::Job& j) {
    return j.attempt() == 2 && j.state() == v1::JOB_STATE_RUNNING;
  })) << h.logs();
  EXPECT_EQ(h.get_job(job.id()).attempts(1).resumed_from(), released.checkpoint().path());
  EXPECT_EQ(h.sphctl({"cancel", job.id()}).exit_code, 0);
  EXPECT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_CANCELLED, 10s)) << h.logs();
}

TEST(ServiceEndToEnd, TwoPoolsShareOneQueue) {
  ServiceHarness h;
  h.start_server();
  auto a = h.start_pool(1, {"--idle-exit", "3"}, "pool-a");
  auto b = h.start_pool(1, {"--idle-exit", "3"}, "pool-b");
  std::vector<std::string> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(h.submit_text(channel(2)).id());
  std::set<std::string> pools;
  for (const auto& id : ids) {
    ASSERT_TRUE(h.wait_for_state(id, v1::JOB_STATE_SUCCEEDED, 120s)) << h.logs();
    const auto j = h.get_job(id);
    EXPECT_EQ(j.attempts_size(), 1) << id << " ran more than once";
    pools.insert(j.attempts(0).pool());
  }
  EXPECT_EQ(pools.size(), 2u) << "one pool did all the work";
  EXPECT_EQ(a.wait(30s).value_or(-1), 0);
  EXPECT_EQ(b.wait(30s).value_or(-1), 0);
}

TEST(ServiceEndToEnd, SphctlExitCodesAndOutputs) {
  ServiceHarness h;
  h.start_server();
  const auto dry = h.sphctl({"submit", test_case_path("tiny_dam_break_2d.textproto"), "--dry-run"});
  EXPECT_EQ(dry.exit_code, 0);
  EXPECT_NE(dry.out.find("150 fluid, 456 wall, 0 rigid, 0 elastic, 606 total"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("steps:"), std::string::npos);
  EXPECT_NE(dry.out.find("memory:"), std::string::npos);
  EXPECT_TRUE(h.sphctl({"list", "--json"}).out.find("\"jobs\":[]") != std::string::npos)
      << "--dry-run submitted something";

  const std::string bad =
      write_case(h, "bad.textproto",
                 std::regex_replace(read_test_case("channel_2d.textproto"),
                                    std::regex("material: \"fluid\""), "material: \"oil\""));
  const auto invalid = h.sphctl({"submit", bad});
  EXPECT_EQ(invalid.exit_code, 3);
  EXPECT_NE(invalid.err.find("fluids[0].material"), std::string::npos) << invalid.err;
  EXPECT_EQ(h.sphctl({"status", "job-42"}).exit_code, 4);
  EXPECT_EQ(h.sphctl({"frobnicate"}).exit_code, 2);

  const auto first = h.sphctl(
      {"submit", test_case_path("channel_2d.textproto"), "--request-id", "fixed-id", "--json"});
  EXPECT_EQ(first.exit_code, 0);
  EXPECT_NE(first.out.find("\"created\":true"), std::string::npos) << first.out;
  const auto again = h.sphctl(
      {"submit", test_case_path("channel_2d.textproto"), "--request-id", "fixed-id", "--json"});
  EXPECT_NE(again.out.find("\"created\":false"), std::string::npos) << again.out;
  const auto list = h.sphctl({"list", "--state", "queued"});
  EXPECT_NE(list.out.find("job-1"), std::string::npos) << list.out;
  EXPECT_EQ(h.sphctl({"list", "--state", "running"}).out.find("job-1"), std::string::npos);
  EXPECT_EQ(h.sphctl({"fetch", "job-1"}).exit_code, 8);  // no result yet

  h.server().kill_all();
  const auto down = h.sphctl({"status", "job-1", "--timeout", "2"});
  EXPECT_EQ(down.exit_code, 5) << down.err;
}

}  // namespace
}  // namespace sph::testing
