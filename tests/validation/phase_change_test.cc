// Reversible phase transitions end to end (Fuchs 2021, "Gastric disintegration of food
// boluses", coarse): 60 boluses dissolve into chyme as the concentration diffusing in from the
// gastric juice passes C_t, while a moving constriction drives a jet. The paper's result is
// qualitative (boluses shrink, some disappear by t = 0.875); the invariants are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

TEST(PhaseChange, GastricBolusesDissolveConservingMass) {
  auto c = test::load_case("gastric_boluses_2d");
  c.set_dx(0.4);  // 4.8k particles, 10.8k steps; the case file uses 0.2, the paper 0.1
  const std::string out = test::output_dir("phase_gastric");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  // Total mass (fluid + rigid) after every snapshot: exact, particles only change phase.
  const test::Snapshot s0 = rr.snapshot(0);
  auto total = [](const test::Snapshot& s, int kind) {
    double m = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (kind < 0 ? s.kind[i] != 1 : s.kind[i] == kind) m += s.mass[i];
    return m;
  };
  const double m0 = total(s0, -1), rigid0 = total(s0, 2);
  double worst = 0;
  for (int k = 0; k < rr.snapshot_count(); ++k)
    worst = std::max(worst, std::abs(total(rr.snapshot(k), -1) / m0 - 1));
  const test::Snapshot end = rr.last();
  const double rigid_end = total(end, 2);
  // Concentration stays within its initial/boundary bounds [0, 1] (maximum principle).
  const auto cmin = rr.series("diagnostics/concentration_min");
  const auto cmax = rr.series("diagnostics/concentration_max");
  const auto active = rr.series("phase/active_bodies");
  const auto melted = rr.series("phase/melted");
  const auto solidified = rr.series("phase/solidified");
  std::printf(
      "gastric boluses (dx 0.4): total mass error %.1e over %d snapshots; bolus mass %.1f -> "
      "%.1f (%.0f%% dissolved), bodies %g -> %g, C in [%.3g, %.3g], %.1f s wall\n",
      worst, rr.snapshot_count(), rigid0, rigid_end, 100 * (1 - rigid_end / rigid0), active.front(),
      active.back(), *std::min_element(cmin.begin(), cmin.end()),
      *std::max_element(cmax.begin(), cmax.end()), r.wall_seconds);
  EXPECT_LE(worst, 1e-12);
  EXPECT_GE(*std::min_element(cmin.begin(), cmin.end()), 0.0);
  EXPECT_LE(*std::max_element(cmax.begin(), cmax.end()), 1.0 + 1e-12);
  // Melting only (the transition is not reversible), boluses shrink and some disappear.
  EXPECT_EQ(solidified.back(), 0.0);
  EXPECT_GT(melted.back(), 0.3 * rigid0 / s0.mass[0]);
  EXPECT_LT(rigid_end, 0.7 * rigid0);
  EXPECT_EQ(active.front(), 60.0);
  EXPECT_LT(active.back(), 60.0);
  // Mass is counted per body too: the body series sum to the rigid mass.
  const auto body_mass = rr.series("bodies/mass");
  double sum = 0;
  const std::size_t slots = body_mass.size() / active.size();
  for (std::size_t k = body_mass.size() - slots; k < body_mass.size(); ++k)
    if (std::isfinite(body_mass[k])) sum += body_mass[k];
  EXPECT_NEAR(sum, rigid_end, 1e-9 * rigid0);
}

}  // namespace
}  // namespace sph
