// sphctl logs: the worker pool's log lines for a job, kept by the server per attempt and
// followed like watch, with a real server, a real two-rank pool and sphctl.
#include <gtest/gtest.h>

#include <future>
#include <thread>
#include <string>

#include "harness/service_harness.h"

namespace sph::testing {
namespace {

int count_of(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ServiceLogs, FollowsARunToItsGuardDiagnosis) {
  ServiceHarness h;
  h.start_server();
  // The tiny dam break run past t = 0.54, where the wave pushes fluid into the right wall
  // and the solid-fraction guard stops it: the diagnosis must reach `sphctl logs`.
  const auto job = h.submit_text(with_end_time(read_test_case("tiny_dam_break_2d.textproto"), 0.6));
  // Followed from before the job runs (it is queued: no pool yet) to its end.
  auto follow = std::async(std::launch::async, [&] {
    return h.sphctl({"logs", job.id(), "--follow"}, 120s);
  });
  std::this_thread::sleep_for(500ms);
  auto pool = h.start_pool(2, {"--max-jobs", "1", "--idle-exit", "60"});
  const auto followed = follow.get();
  std::printf("sphctl logs --follow:\n%s%s", followed.out.c_str(), followed.err.c_str());
  EXPECT_EQ(followed.exit_code, 10) << "the job FAILED: watch's exit code" << h.logs();
  EXPECT_NE(followed.out.find("[attempt 1] tiny_dam_break_2d, output "), std::string::npos);
  EXPECT_GE(count_of(followed.out, "[attempt 1] progress step "), 1);
  EXPECT_NE(followed.out.find("solid fraction"), std::string::npos) << "no diagnosis";
  EXPECT_NE(followed.out.find("(guards.max_solid_fraction)"), std::string::npos);

  // Afterwards without --follow: the same lines, and the job's reason ends them.
  const auto after = h.sphctl({"logs", job.id()});
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_EQ(after.out, followed.out);
  const auto j = h.get_job(job.id());
  EXPECT_EQ(j.state(), v1::JOB_STATE_FAILED);
  EXPECT_NE(after.out.find(j.reason().substr(j.reason().find("solid fraction"))), std::string::npos)
      << j.reason();
  // One JSON object per line; other attempts have none; errors as sphctl's others.
  const auto json = h.sphctl({"--json", "logs", job.id()});
  EXPECT_EQ(count_of(json.out, "\n"), count_of(after.out, "\n"));
  EXPECT_NE(json.out.find("\"sequence\":\"1\""), std::string::npos) << json.out;
  EXPECT_EQ(h.sphctl({"logs", job.id(), "--attempt", "2"}).out, "");
  EXPECT_EQ(h.sphctl({"logs", "job-99"}).exit_code, 4);
  EXPECT_EQ(h.sphctl({"logs", job.id(), "--attempt", "x"}).exit_code, 2);
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

}  // namespace
}  // namespace sph::testing
