// Hydrostatic tanks and the free-falling tank (Adami 2012 secs. 6.1, 6.3, 7.1).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/evaluate_reference.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

// Water height from the fluid mass: rho0 H L = sum m (2D, rho0 = 1).
double water_height(const test::Snapshot& s, double width) {
  double m = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == 0) m += s.mass[i];
  return m / width;
}

TEST(Hydrostatics, TankBottomPressureAndRest) {
  auto c = test::load_case("hydrostatic_tank_2d");
  c.set_dx(0.04);  // 1100 fluid particles: a CI-sized version of the case
  c.mutable_time()->set_end_time(8);
  const std::string out = test::output_dir("hydrostatic_tank");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const test::Snapshot s = test::ResultReader(out + "/result.h5").last();
  const double H = water_height(s, 2.0), g = 1.0;
  // The bottom pressure as the case's reference defines it (analysis/hydrostatic.h).
  const analysis::Measurement p = analysis::evaluate_reference(c, out + "/result.h5");
  double vmax = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == 0) vmax = std::max(vmax, std::hypot(s.velocity[3 * i], s.velocity[3 * i + 1]));
  std::printf("Hydrostatic tank dx = %.2f, t = 8: %s; max |u| = %.2f%% of sqrt(gH)\n", c.dx(),
              p.detail.c_str(), 100 * vmax / std::sqrt(g * H));
  EXPECT_LT(p.error, 0.02);
  EXPECT_LT(vmax / std::sqrt(g * H), 0.01);
}

// The tank with its acoustic mode damped (cases/studies/hydrostatic_tank_2d) at dx = 0.05.
// At h = dx the bottom pressure is 0.071% high, an error no refinement removes: the quintic
// spline's discrete first moment on a square lattice is -1.00080 instead of -1 (plus an
// O(Ma^2) part at the wall; docs/accuracy.md). At h = 2 dx the moment is off by 7e-6 and the
// error is 0.026% (measured), falling with dx from there.
TEST(Hydrostatics, SteadyTankLargerSmoothingLengthLowersTheFloor) {
  double err[2];
  for (int k = 0; k < 2; ++k) {
    auto c = test::load_case("studies/hydrostatic_tank_2d");
    c.set_smoothing_length_ratio(k + 1);
    const std::string out = test::output_dir("hydrostatic_steady_h" + std::to_string(k + 1));
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    const analysis::Measurement p = analysis::evaluate_reference(c, out + "/result.h5");
    std::printf("Steady hydrostatic tank, dx = 0.05, h = %d dx: %s\n", k + 1, p.detail.c_str());
    err[k] = p.error;
  }
  EXPECT_GT(err[0], 0.0005);  // the lattice floor is there at h = dx ...
  EXPECT_LT(err[0], 0.0012);
  EXPECT_LT(err[1], 0.0004);  // ... and a third of it at h = 2 dx
}

TEST(Hydrostatics, FreeFallingTankStaysAtZeroPressure) {
  const auto c = test::load_case("free_fall_tank_2d");
  const std::string out = test::output_dir("free_fall");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  double worst = 0;
  for (int k = 1; k < rr.snapshot_count(); ++k) {
    const test::Snapshot s = rr.snapshot(k);
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == 0) worst = std::max(worst, std::abs(s.pressure[i]));
  }
  const double rho_g_H = 0.9;
  std::printf(
      "Free-falling tank to t = 1: max |p| = %.3f%% of rho g H (Adami 2012 Fig. 12b: zero)\n",
      100 * worst / rho_g_H);
  EXPECT_LT(worst / rho_g_H, 0.01);
}

TEST(Hydrostatics, Cylinder3DAxisProfile) {
  auto c = test::load_case("hydrostatic_cylinder_3d");
  c.set_dx(0.08);  // coarse: ~1500 fluid particles
  c.mutable_time()->set_end_time(3);
  const std::string out = test::output_dir("hydrostatic_cylinder");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot s = rr.last();
  double m = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == 0) m += s.mass[i];
  const double H = m / (std::numbers::pi * 0.25);
  // Probe line along the axis, z = 0.02 ... 0.98 (25 points); compare away from the ends,
  // where the fluid-only interpolation is truncated (Adami 2012 sec. 6.3).
  const auto p = rr.series("probes/axis/pressure");
  const std::size_t n = 25, last = p.size() - n;
  double worst = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double z = 0.02 + 0.96 * static_cast<double>(k) / (n - 1);
    if (z < 0.2 || z > H - 0.2) continue;
    worst = std::max(worst, std::abs(p[last + k] - (H - z)) / H);
  }
  std::printf("3D cylinder dx = 0.08, t = 3: axis pressure within %.2f%% of rho g (H - z)\n",
              100 * worst);
  EXPECT_LT(worst, 0.03);
}

}  // namespace
}  // namespace sph
