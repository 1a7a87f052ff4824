// A rigid disk settling in a closed box (Fuchs et al. 2021, the Glowinski et al. 2001
// benchmark): velocity history against the FEM reference, no wall penetration, at rest on
// the bottom at the end. CI-sized: D/dx = 6.25 (the paper uses 12.5 and 25; see
// tests/validation/bodies/ for the finer runs).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/evaluate_reference.h"
#include "tests/support/reference_table.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

TEST(RigidBodies, FallingDiskVelocityHistoryAndRest) {
  auto c = test::load_case("falling_disk_2d");
  c.set_dx(0.0004);
  c.mutable_time()->set_end_time(1.0);
  const std::string out = test::output_dir("falling_disk");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const auto t = rr.series("bodies/time");
  const auto vel = rr.series("bodies/velocity");  // [samples][1][2]
  std::vector<double> vy;
  for (std::size_t k = 0; k < t.size(); ++k) vy.push_back(vel[2 * k + 1]);
  const auto ref = test::read_reference(
      std::string(SPHD_SOURCE_DIR) +
      "/tests/validation/data/sedimentation_disk_glowinski2001_vy_history.csv");
  // Settling speed: the mean over the terminal phase 0.3 s <= t <= 0.65 s against the same
  // mean of the data, as the case's reference defines it (analysis/series_data.h).
  const analysis::Measurement settling = analysis::evaluate_reference(c, out + "/result.h5");
  const double sim = settling.quantity;
  double refm = 0;
  int nr = 0;
  for (const auto& row : ref.rows)
    if (row[0] >= 0.3 && row[0] <= 0.65) refm += row[1], ++nr;
  refm /= nr;
  // Acceleration phase: the history up to t = 0.3 s.
  double worst_early = 0;
  for (const auto& row : ref.rows)
    if (row[0] <= 0.3)
      worst_early = std::max(worst_early,
                             std::abs(test::interpolate(t, vy, row[0]) - row[1]) / std::abs(refm));
  // Rest and penetration at the end.
  const test::Snapshot s = rr.last();
  double lowest_rigid = 1e9, top_wall = -1e9;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    if (s.kind[i] == 2) lowest_rigid = std::min(lowest_rigid, y);
    if (s.kind[i] == 1 && y < 0 && x > 0 && x < 0.02) top_wall = std::max(top_wall, y);
  }
  const double v_end = std::hypot(vel[vel.size() - 2], vel[vel.size() - 1]);
  std::printf(
      "Falling disk D/dx = 6.25: settling speed %.4f m/s vs Glowinski 2001 %.4f (%+.1f%%), history "
      "to "
      "t = 0.3 s within %.1f%% of it; at t = 1 s: speed %.1f%% of settling, lowest disk particle "
      "%.2f dx "
      "above the wall's first layer\n",
      -sim, -refm, 100 * (sim / refm - 1), 100 * worst_early, 100 * v_end / std::abs(refm),
      (lowest_rigid - top_wall) / c.dx());
  EXPECT_LT(settling.error, 0.05) << settling.detail;
  EXPECT_LT(worst_early, 0.08);
  EXPECT_LT(v_end, 0.02 * std::abs(refm));
  EXPECT_GT(lowest_rigid - top_wall, 0.5 * c.dx());  // no penetration of the bottom wall
}

}  // namespace
}  // namespace sph
