// Density diffusion (solver/physics/density_diffusion.h; docs/density_diffusion.md) at CI size:
// the Colagrossi dam break's wall pressure against Buchner 2002 with and without it, the
// Koshizuka-Oka surge front with and without it, and the hydrostatic tank at rest with each
// form. tests/validation/density_diffusion/run.sh runs the dam break at full size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/evaluate_reference.h"
#include "analysis/series_data.h"
#include "tests/support/reference_table.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"
#include "tests/validation/impact_pressure.h"
#include "tests/validation/surge_front.h"

namespace sph {
namespace {

std::string data(const char* file) {
  return std::string(SPHD_SOURCE_DIR) + "/tests/validation/data/" + file;
}

void add_density_diffusion(v1::Case& c, v1::DensityDiffusion::Form form, double delta = 0.1) {
  auto* dd = c.mutable_fluid_model()->mutable_density_diffusion();
  dd->set_form(form);
  dd->set_delta(delta);
}

// The probe on the far wall (y = 0.2 H), in t sqrt(g/H) and p / (rho g H) (H = 1, g = 1, rho = 1).
test::Signal wall_probe(const std::string& out) {
  test::ResultReader rr(out + "/result.h5");
  return test::probe_signal(rr.series("probes/wall_p1/time"), rr.series("probes/wall_p1/pressure"));
}

test::ImpactFigures colagrossi(const char* name, double dx, double end_time, bool with) {
  auto c = test::load_case("colagrossi_dambreak_2d");
  c.set_dx(dx);
  c.mutable_time()->set_end_time(end_time);
  c.mutable_output()->set_interval(0);
  if (with) add_density_diffusion(c, v1::DensityDiffusion::FOURTAKAS);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  return test::impact_figures(wall_probe(out));
}

// The Colagrossi dam break with density diffusion (Fourtakas, delta 0.1) at dx = H/25 to
// t sqrt(g/H) = 6.5, after the second impact, against Buchner's P1.
TEST(DensityDiffusion, ColagrossiWallPressureAgainstBuchner) {
  const test::ImpactFigures ref =
      test::impact_figures(test::buchner_p1(data("dambreak_buchner2002_P1_pysph.csv")));
  const test::ImpactFigures f = colagrossi("colagrossi_dd", 0.04, 6.5, true);
  std::printf(
      "Colagrossi dam break dx = H/25 with density diffusion: first impact peak %.2f (running "
      "mean over 0.05: %.2f; Buchner %.2f, ratio %.2f), plateau t = 3.2-5.2 %.3f (Buchner %.3f, "
      "%+.1f%%), second impact t = 5.5-6.2 %.3f (%.3f, %+.1f%%), noise %.4f rho g H\n",
      f.peak, f.smoothed_peak, ref.peak, f.peak / ref.peak, f.plateau, ref.plateau,
      100 * (f.plateau / ref.plateau - 1), f.second, ref.second, 100 * (f.second / ref.second - 1),
      f.noise);
  EXPECT_LT(f.peak, 1.5 * ref.peak);
  EXPECT_GT(f.peak, ref.peak / 1.5);
  EXPECT_LT(std::abs(f.plateau / ref.plateau - 1), 0.10);
  // 9.9% measured (7.7% without, snapshots every 0.1): the 5-10% excess of both plateaus is
  // there with and without the term at every resolution (docs/density_diffusion.md).
  EXPECT_LT(std::abs(f.second / ref.second - 1), 0.10);
}

// The noise of the probe about its running mean over 0.05 sqrt(H/g), without and with
// density diffusion, at dx = H/20 through the plateau after the first impact.
TEST(DensityDiffusion, ColagrossiProbeNoiseReducedThreefold) {
  const test::ImpactFigures plain = colagrossi("colagrossi_noise_plain", 0.05, 5.2, false);
  const test::ImpactFigures dd = colagrossi("colagrossi_noise_dd", 0.05, 5.2, true);
  std::printf(
      "Colagrossi dam break dx = H/20, t sqrt(g/H) = 3.2-5.2: probe noise %.4f rho g H without, "
      "%.4f with density diffusion (%.1fx less); first impact peak %.2f without, %.2f with\n",
      plain.noise, dd.noise, plain.noise / dd.noise, plain.peak, dd.peak);
  EXPECT_GT(plain.noise / dd.noise, 3.0);
}

// The surge front of the 1 x 2 column (cases/dambreak_martin_moyce_2d, as
// FreeSurface.DamBreakFrontAgainstExperimentAndMPS) against Koshizuka & Oka's experiment:
// the diffusion of density must not change how the front runs.
TEST(DensityDiffusion, SurgeFrontAsWithout) {
  double err[2];
  for (int with = 0; with < 2; ++with) {
    auto c = test::load_case("dambreak_martin_moyce_2d");
    c.set_dx(0.04);
    c.mutable_time()->set_end_time(2.1);  // T = t sqrt(2 g / a) up to 3
    c.mutable_output()->set_interval(0);
    if (with) add_density_diffusion(c, v1::DensityDiffusion::FOURTAKAS);
    const std::string out = test::output_dir(with ? "front_dd" : "front_plain");
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    err[with] = test::surge_front_error(c, out);
    std::printf("Surge front dx = a/25, T <= 3, %s: mean deviation from Koshizuka-Oka %.2f%%\n",
                with ? "with density diffusion" : "without", 100 * err[with]);
  }
  EXPECT_LT(std::abs(err[1] - err[0]), 0.01);
}

// The tank at rest (cases/studies/hydrostatic_tank_2d: dx = 0.05, h = 2 dx, its acoustic mode
// damped by viscosity) keeps the bottom pressure at rho g (H + dx/2) with either form: the
// walls complete the kernel support at the bottom, and the free surface's share of the
// Molteni-Colagrossi term is too small to move this tank in t = 10.
TEST(DensityDiffusion, HydrostaticTankKeepsRhoGH) {
  double err[2];
  for (int form = 0; form < 2; ++form) {
    auto c = test::load_case("studies/hydrostatic_tank_2d");
    add_density_diffusion(
        c, form ? v1::DensityDiffusion::MOLTENI_COLAGROSSI : v1::DensityDiffusion::FOURTAKAS);
    const std::string out = test::output_dir(form ? "hydrostatic_dd_mc" : "hydrostatic_dd_f");
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    const analysis::Measurement p = analysis::evaluate_reference(c, out + "/result.h5");
    std::printf("Tank at rest, dx = 0.05, t = 10, density diffusion %s: %s\n",
                form ? "Molteni-Colagrossi" : "Fourtakas", p.detail.c_str());
    err[form] = p.error;
  }
  EXPECT_LT(err[0], 0.005);
  EXPECT_LT(err[1], 0.005);
}

}  // namespace
}  // namespace sph
