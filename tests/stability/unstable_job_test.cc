// An unstable case submitted to the service ends as a FAILED job whose reason carries the
// diagnosis (criterion, particle, step, time), with its output up to the last good state kept
// and fetchable (issue: cases unstable by construction end as FAILED jobs).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/service_harness.h"

namespace sph::testing {
namespace {

TEST(UnstableJob, FailsWithTheDiagnosisAndKeepsTheLastGoodState) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--max-jobs", "1", "--idle-exit", "60"});
  // A dam break whose time step is forced to 20 times its acoustic bound.
  const std::string text = R"(name: "forced_dt_dam_break"
    dimension: 2 dx: 0.05
    domain { lo { x: -0.2 y: -0.2 } hi { x: 4.2 y: 2.2 } }
    materials { name: "water" density: 1 eos { kind: TAIT sound_speed: 10 } }
    fluids { name: "column" material: "water" shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } }
    walls { name: "tank" shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 4 y: 2 } } } } } }
    fluid_model { density: CONTINUITY artificial_viscosity: 0.1 }
    gravity { acceleration { y: -1 } }
    time { end_time: 5 fixed_dt: 0.025 }
    output { interval: 0.05 })";
  const auto job = h.submit_text(text);
  ASSERT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_FAILED, 120s)) << h.logs();
  const auto done = h.get_job(job.id());
  EXPECT_NE(done.reason().find("guards.max_mach"), std::string::npos) << done.reason();
  EXPECT_NE(done.reason().find("particle id"), std::string::npos) << done.reason();
  EXPECT_NE(done.reason().find("step "), std::string::npos) << done.reason();
  ASSERT_TRUE(done.has_result()) << "the output up to the failure is not in the manifest";
  const auto status = h.sphctl({"status", job.id()});
  EXPECT_NE(status.out.find("FAILED"), std::string::npos) << status.out;
  const auto fetched = h.sphctl({"fetch", job.id(), "-o", h.dir() + "/fetched"});
  ASSERT_EQ(fetched.exit_code, 0) << fetched.err;
  std::string out;
  EXPECT_EQ(h5check({"finite", h.dir() + "/fetched/result.h5"}, h.dir(), out), 0) << out;
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

}  // namespace
}  // namespace sph::testing
