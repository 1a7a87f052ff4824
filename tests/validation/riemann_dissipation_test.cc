// Riemann dissipation (solver/physics/riemann_dissipation.h; docs/riemann_dissipation.md) at
// CI size: the Colagrossi dam break's wall pressure against Buchner 2002 with and without it,
// and the hydrostatic tank at rest with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/evaluate_reference.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"
#include "tests/validation/impact_pressure.h"

namespace sph {
namespace {

std::string data(const char* file) {
  return std::string(SPHD_SOURCE_DIR) + "/tests/validation/data/" + file;
}

enum class Dissipation { kNone, kContinuity, kMomentum };

void add_riemann(v1::Case& c, Dissipation d) {
  if (d == Dissipation::kNone) return;
  auto* rd = c.mutable_fluid_model()->mutable_riemann_dissipation();
  if (d == Dissipation::kMomentum) {
    // The limited momentum term stands in for the artificial viscosity (validation refuses
    // both at once).
    rd->set_scope(v1::RiemannDissipation::CONTINUITY_AND_MOMENTUM);
    c.mutable_fluid_model()->set_artificial_viscosity(0);
  } else {
    rd->set_scope(v1::RiemannDissipation::CONTINUITY);
  }
}

// The probe on the far wall (y = 0.2 H), in t sqrt(g/H) and p / (rho g H) (H = 1, g = 1, rho = 1).
test::ImpactFigures colagrossi(const char* name, double dx, double end_time, Dissipation d) {
  auto c = test::load_case("colagrossi_dambreak_2d");
  c.set_dx(dx);
  c.mutable_time()->set_end_time(end_time);
  c.mutable_output()->set_interval(0);
  add_riemann(c, d);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  if (r.status != RunStatus::kCompleted) {
    // The caller's comparisons then fail on zero figures; a partial result is not read.
    ADD_FAILURE() << name << " did not complete: " << r.message;
    return {};
  }
  test::ResultReader rr(out + "/result.h5");
  return test::impact_figures(
      test::probe_signal(rr.series("probes/wall_p1/time"), rr.series("probes/wall_p1/pressure")));
}

void print(const char* what, const test::ImpactFigures& f, const test::ImpactFigures& ref) {
  std::printf(
      "%s: first impact peak %.2f (running mean over 0.05: %.2f; Buchner %.2f, ratio %.2f), "
      "plateau t = 3.2-5.2 %.3f (Buchner %.3f, %+.1f%%), noise %.4f rho g H\n",
      what, f.peak, f.smoothed_peak, ref.peak, f.peak / ref.peak, f.plateau, ref.plateau,
      100 * (f.plateau / ref.plateau - 1), f.noise);
}

test::ImpactFigures buchner() {
  return test::impact_figures(test::buchner_p1(data("dambreak_buchner2002_P1_pysph.csv")));
}

// The Colagrossi dam break at dx = H/20 through the plateau after the first impact
// (t sqrt(g/H) <= 5.2) without and with the Riemann dissipation, against Buchner's P1: the
// probe's noise about its running mean over 0.05 sqrt(H/g) reduced at least threefold and the
// plateau within 10% of the measured one, with either scope.
TEST(RiemannDissipation, ColagrossiProbeNoiseAndPlateau) {
  const test::ImpactFigures ref = buchner();
  const test::ImpactFigures plain =
      colagrossi("colagrossi_rd_plain", 0.05, 5.2, Dissipation::kNone);
  print("Colagrossi dam break dx = H/20 without", plain, ref);
  for (const Dissipation d : {Dissipation::kContinuity, Dissipation::kMomentum}) {
    const bool m = d == Dissipation::kMomentum;
    const test::ImpactFigures rd = colagrossi(m ? "colagrossi_rdm" : "colagrossi_rd", 0.05, 5.2, d);
    print(m ? "  with Riemann dissipation, continuity and momentum"
            : "  with Riemann dissipation, continuity",
          rd, ref);
    std::printf("  probe noise t = 3.2-5.2: %.1fx less\n", plain.noise / rd.noise);
    EXPECT_GT(plain.noise / rd.noise, 3.0);
    EXPECT_LT(std::abs(rd.plateau / ref.plateau - 1), 0.10);
  }
}

// The first impact on the far wall (t sqrt(g/H) = 2.3-3.2) at dx = H/25 with the continuity
// term: the largest raw probe sample within a factor 1.5 of Buchner's peak. (At H/20 the raw
// peak is a single-sample spike of 3.9 times the measured one, 16 times without; with the
// momentum term too it is 1.6x at H/20 and 2.3x at H/25: docs/riemann_dissipation.md.)
TEST(RiemannDissipation, ColagrossiFirstImpactAgainstBuchner) {
  const test::ImpactFigures ref = buchner();
  const test::ImpactFigures rd =
      colagrossi("colagrossi_rd_impact", 0.04, 3.2, Dissipation::kContinuity);
  std::printf(
      "Colagrossi dam break dx = H/25, Riemann dissipation in the continuity equation: first "
      "impact peak %.2f (running mean over 0.05: %.2f; Buchner %.2f, ratio %.2f)\n",
      rd.peak, rd.smoothed_peak, ref.peak, rd.peak / ref.peak);
  EXPECT_LT(rd.peak, 1.5 * ref.peak);
  EXPECT_GT(rd.peak, ref.peak / 1.5);
}

// The tank at rest (cases/studies/hydrostatic_tank_2d: dx = 0.05, h = 2 dx, its acoustic mode
// damped by viscosity) keeps the bottom pressure at rho g (H + dx/2) with the continuity
// term and its hydrostatic correction (the default): the walls complete the kernel support at
// the bottom with the hydrostatic pressure the wall condition extrapolates into them, and the
// correction keeps the free surface from diffusing the hydrostatic gradient (2.0% without it).
TEST(RiemannDissipation, HydrostaticTankKeepsRhoGH) {
  auto c = test::load_case("studies/hydrostatic_tank_2d");
  add_riemann(c, Dissipation::kContinuity);
  const std::string out = test::output_dir("hydrostatic_rd");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const analysis::Measurement p = analysis::evaluate_reference(c, out + "/result.h5");
  std::printf("Tank at rest, dx = 0.05, t = 10, Riemann dissipation (continuity): %s\n",
              p.detail.c_str());
  EXPECT_LT(p.error, 0.005);
}

}  // namespace
}  // namespace sph
