// Poiseuille and Couette flow against the transient analytic solutions (Adami 2012
// sec. 5.1), measured with the cases' references (analysis/channel_flow.h). Adami reports a mean
// error at t = 10 of 0.16% (Poiseuille) and 0.16% (Couette) at 30 particles across; we require <
// 0.5%.
#include <gtest/gtest.h>

#include <cstdio>

#include "analysis/evaluate_reference.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

// The error the case's reference defines (analysis/channel_flow.h), as a study measures it.
double reference_error(const v1::Case& c, const std::string& out) {
  const analysis::Measurement m = analysis::evaluate_reference(c, out + "/result.h5");
  std::printf("  %s\n", m.detail.c_str());
  return m.error;
}

TEST(ChannelFlow, PoiseuilleMatchesAnalyticAtT10) {
  const auto c = test::load_case("poiseuille_2d");
  const std::string out = test::output_dir("poiseuille");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const test::Snapshot s = test::ResultReader(out + "/result.h5").last();
  ASSERT_NEAR(s.time, 10.0, 1e-12);
  const double err = reference_error(c, out);
  std::printf(
      "Poiseuille, 30 particles across, t = 10: mean error %.3f%% of u_max (Adami 2012: 0.16%%)\n",
      100 * err);
  EXPECT_LT(err, 0.005);
}

TEST(ChannelFlow, CouetteMatchesAnalyticAtT10) {
  const auto c = test::load_case("couette_2d");
  const std::string out = test::output_dir("couette");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const double err = reference_error(c, out);
  std::printf(
      "Couette, 30 particles across, t = 10: mean error %.3f%% of v_wall (Adami 2012: 0.16%%)\n",
      100 * err);
  EXPECT_LT(err, 0.005);
}

}  // namespace
}  // namespace sph
