// The Magnus effect benchmark of Reder et al. 2021 sec. 3.2 at CI size: the cylinder of
// cases/magnus_cylinder_2d.textproto (motion_type PRESCRIBED: held in place, turned clockwise
// at gamma = omega D / (2 U) = 1) in a stream at Re 200, at D/dx = 5 (dx = 0.2) to t = 10 D/U.
// Mittal & Kumar 2003 give a mean lift c_l = 2.532 at gamma = 1 (Reder Table 3). The case
// sets the fluid's pressure level (EOS background pressure and outlet pressure) to
// 0.1 rho0 c^2; at a zero level the suction on the fast side is negative pressure and the lift
// came out 45-75% short. At this coarse spacing the lift is about 9% short, and a change of
// the time steps alone moves it by some 10% (at D/dx = 10 it is within the digest's 5%:
// tests/validation/reports/magnus.md), so the test asks for c_l / 2.532 in [0.7, 1.05] and
// that the fluid's torque opposes the spin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

TEST(Magnus, RotatingCylinderLiftsTowardsItsFasterSide) {
  std::string s = test::case_text("magnus_cylinder_2d");
  const auto replace_all = [&](std::string& t, const std::string& from, const std::string& to) {
    ASSERT_GT(test::replace_all(t, from, to), 0) << "the case no longer holds '" << from << "'";
  };
  // Twice the spacing: walls and buffers grow to the kernel support (3 dx = 0.6).
  replace_all(s, "dx: 0.1\n", "dx: 0.2\n");
  replace_all(s, "-4.4", "-4.6");
  replace_all(s, "10.4", "10.6");
  replace_all(s, "y: 4.4 ", "y: 4.6 ");
  replace_all(s, "end_time: 40 }", "end_time: 10 }");
  replace_all(s, "output { interval: 10 ", "output { interval: 0 ");
  ASSERT_FALSE(::testing::Test::HasFatalFailure());  // an edit found nothing to replace
  const std::string out = test::output_dir("magnus");
  const RunOutcome r = test::run(parse_case_text(s), out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const auto t = rr.series("bodies/time"), f = rr.series("bodies/fluid_force");
  const auto torque = rr.series("bodies/fluid_torque"), w = rr.series("bodies/angular_velocity");
  const auto pos = rr.series("bodies/position");
  // rho = U = D = 1: c = F / (rho U^2 D / 2) = 2 F (Reder's rho U^2 R).
  double cl = 0, cd = 0, tq = 0, moved = 0;
  int n = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    moved = std::max({moved, std::abs(pos[2 * k] - pos[0]), std::abs(pos[2 * k + 1] - pos[1])});
    if (t[k] < 5) continue;
    cd += 2 * f[2 * k];
    cl += 2 * f[2 * k + 1];
    tq += torque[k] * (w[k] < 0 ? -1.0 : 1.0);  // along the spin
    ++n;
  }
  ASSERT_GT(n, 50);
  cl /= n;
  cd /= n;
  tq /= n;
  const double cl_ref = 2.532;
  std::printf(
      "Magnus cylinder, gamma = 1, Re = 200, D/dx = 5, 5 <= t <= 10: mean c_l %.3f (Mittal & "
      "Kumar %.3f, %.1f%%), mean c_d %.3f (M&K 1.088, Reder 1.295), torque along the spin "
      "%.4f, centre moved %.1e\n",
      cl, cl_ref, 100 * (cl / cl_ref - 1), cd, tq, moved);
  EXPECT_EQ(moved, 0.0);
  EXPECT_GT(cl / cl_ref, 0.7);
  EXPECT_LT(cl / cl_ref, 1.05);
  EXPECT_LT(tq, 0.0);  // the fluid brakes the spinning cylinder
}

}  // namespace
}  // namespace sph
