// Energy of elastic solids (total Lagrangian SPH, solver/elastic/; X. Tang's thesis sec. 3;
// issue #36): a hyperelastic body set oscillating keeps kinetic + strain energy (the series
// elastic/<body>/kinetic_energy and strain_energy) over ten periods of its motion without
// damping, for Saint Venant-Kirchhoff and neo-Hookean, and with Kelvin-Voigt damping loses it
// at the rate that the damping sets for the mode excited. The bodies start in their reference
// shape with a velocity field (the case format has no initial deformation); a quarter period
// later they are in the stretched state from which the issue releases them. At larger strains the
// scheme's zero-energy (checkerboard) mode grows until a particle inverts; the hourglass control
// (Material.hourglass_control, solver/elastic/hourglass_control.h) holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "case/load.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

struct EnergyRun {
  std::vector<double> t, energy;  // kinetic + strain energy of the body
  std::vector<double> u;          // the chosen displacement component of observation point 0
  std::vector<double> crossings;  // times at which u changes sign (u starts at 0 and grows)
  long long steps = 0;
  RunStatus status = RunStatus::kError;
  std::string message;
  double end = 0, wall = 0;  // time reached, wall seconds
};

EnergyRun run_body(const v1::Case& c, const std::string& body, std::size_t component,
                   const std::string& out_name, bool must_complete = true) {
  const std::string out = test::output_dir(out_name);
  const RunOutcome r = test::run(c, out);
  if (must_complete) {
    EXPECT_EQ(r.status, RunStatus::kCompleted) << out_name << ": " << r.message;
  }
  EnergyRun e;
  e.steps = r.steps;
  e.status = r.status;
  e.message = r.message;
  e.end = r.time;
  e.wall = r.wall_seconds;
  if (r.status != RunStatus::kCompleted) return e;
  test::ResultReader rr(out + "/result.h5");
  e.t = rr.series("diagnostics/time");  // every series is sampled together
  const std::vector<double> ek = rr.series("elastic/" + body + "/kinetic_energy");
  const std::vector<double> es = rr.series("elastic/" + body + "/strain_energy");
  const std::vector<double> d = rr.series("elastic/" + body + "/displacement");
  const std::size_t row = d.size() / e.t.size();  // points x D
  for (std::size_t k = 0; k < e.t.size(); ++k) {
    e.energy.push_back(ek[k] + es[k]);
    e.u.push_back(d[k * row + component]);
  }
  // Linear interpolation between samples; the sample at t = 0 is exactly 0 and counts as not
  // above, so the first crossing is the end of the first half period.
  for (std::size_t k = 1; k < e.t.size(); ++k)
    if ((e.u[k - 1] > 0) != (e.u[k] > 0) && e.u[k - 1] != 0)
      e.crossings.push_back(e.t[k - 1] +
                            (e.t[k] - e.t[k - 1]) * e.u[k - 1] / (e.u[k - 1] - e.u[k]));
  return e;
}

// The mean period from t = 0 to the last whole period the crossings show (crossing 2m + 1 ends
// period m + 1); 0 without one.
double mean_period(const EnergyRun& e) {
  const std::size_t n = e.crossings.size();
  if (n < 2) return 0;
  const std::size_t last = n % 2 == 0 ? n - 1 : n - 2;
  return e.crossings[last] / static_cast<double>((last + 1) / 2);
}

// Largest |W / W(0) - 1| over t <= until.
double energy_error(const EnergyRun& e, double until) {
  double worst = 0;
  for (std::size_t k = 0; k < e.t.size() && e.t[k] <= until; ++k)
    worst = std::max(worst, std::abs(e.energy[k] / e.energy[0] - 1));
  return worst;
}

const char* law_name(v1::ElasticLaw law) {
  return law == v1::NEO_HOOKEAN ? "neo-Hookean" : "Saint Venant-Kirchhoff";
}

// cases/elastic_bar_longitudinal_2d (clamped at x = 0, free at x = L, v_x = G x at t = 0).
constexpr double kBarLength = 0.2, kBarE = 1e6, kBarRho = 1000;

TEST(ElasticEnergy, UndampedBarKeepsItsEnergy) {
  // The bar of the case without damping, at nu = 0.3 (the Poisson contraction makes it 2D)
  // and released with G = 8 1/s: the tip moves by 2.5% of L and the strain at the clamp swings
  // between about -4% and +4%, where the two laws differ: Saint Venant-Kirchhoff is stiffer in
  // tension than in compression, neo-Hookean the other way round, and the half periods show
  // it (the one in tension the shorter for the first). At larger strains, and at this one after
  // about 40 periods, the particles drift into a growing checkerboard (the hourglass mode of
  // collocated total Lagrangian SPH, which the thesis does not control) until one inverts,
  // unless hourglass control holds it (HourglassControlOutlivesTheCheckerboardMode below).
  for (const v1::ElasticLaw law : {v1::SAINT_VENANT_KIRCHHOFF, v1::NEO_HOOKEAN}) {
    v1::Case c = test::load_case("elastic_bar_longitudinal_2d");
    v1::Material& m = *c.mutable_materials(0);
    m.set_elastic_law(law);
    m.set_poisson_ratio(0.3);
    m.set_elastic_damping(0);
    c.mutable_elastic_bodies(0)
        ->mutable_initial_velocity_field()
        ->mutable_linear()
        ->mutable_gradient_x()
        ->set_x(8);
    const EnergyRun e = run_body(
        c, "bar", 0, std::string("elastic_energy_bar_") + (law == v1::NEO_HOOKEAN ? "nh" : "svk"));
    const double T = mean_period(e);
    ASSERT_GT(T, 0) << law_name(law);
    const double error = energy_error(e, 10 * T);
    double amplitude = 0;
    for (double u : e.u) amplitude = std::max(amplitude, std::abs(u));
    // Plane strain, nu = 0.3: a thin bar's modulus E / (1 - nu^2); this bar is 5 times longer
    // than high, so its period lies a little above 4 L / c of that modulus.
    const double thin_bar = 4 * kBarLength / std::sqrt(kBarE / (1 - 0.09) / kBarRho);
    std::printf(
        "Bar, %s, nu = 0.3, %lld steps to t = %.3f: period %.5f s (thin-bar theory %.5f s), "
        "half periods in tension %.5f s and compression %.5f s, tip amplitude %.3g m "
        "(%.2f%% of L); largest |W/W0 - 1| over ten periods %.3g%%\n",
        law_name(law), e.steps, e.t.back(), T, thin_bar, e.crossings[0],
        e.crossings[1] - e.crossings[0], amplitude, 100 * amplitude / kBarLength, 100 * error);
    EXPECT_GE(e.t.back(), 10 * T) << law_name(law);
    EXPECT_LT(error, 0.01) << law_name(law);
    EXPECT_NEAR(T, thin_bar, 0.05 * thin_bar) << law_name(law);
  }
}

TEST(ElasticEnergy, UndampedBlockInShearKeepsItsEnergy) {
  // cases/elastic_block_shear_2d: a square block held only at its centre particle, set
  // shearing by v = G (y, x) (pure shear, no spin), G = 30 1/s: a shear strain of about 4%.
  // The shear mode's period is read from the x displacement of the middle of the top face.
  for (const v1::ElasticLaw law : {v1::SAINT_VENANT_KIRCHHOFF, v1::NEO_HOOKEAN}) {
    v1::Case c = test::load_case("elastic_block_shear_2d");
    c.mutable_materials(0)->set_elastic_law(law);
    const EnergyRun e =
        run_body(c, "block", 0,
                 std::string("elastic_energy_block_") + (law == v1::NEO_HOOKEAN ? "nh" : "svk"));
    const double T = mean_period(e);
    ASSERT_GT(T, 0) << law_name(law);
    const double error = energy_error(e, 10 * T);
    std::printf(
        "Block in shear, %s, %lld steps to t = %.3f: period %.5f s, largest |W/W0 - 1| over "
        "ten periods %.3g%%\n",
        law_name(law), e.steps, e.t.back(), T, 100 * error);
    EXPECT_GE(e.t.back(), 10 * T) << law_name(law);
    EXPECT_LT(error, 0.01) << law_name(law);
  }
}

TEST(ElasticEnergy, KelvinVoigtDampingDecaysTheBarAtTheAnalyticRate) {
  // cases/elastic_bar_longitudinal_2d as it is: nu = 0, so the motion is 1D and
  // rho u_tt = E u_xx + eta u_xxt; the first mode's amplitude decays at
  // gamma = eta k^2 / (2 rho) = eta omega^2 / (2 E), its energy at 2 gamma. Measured: gamma from
  // a least-squares line through ln W at whole periods 2T, 3T, ... (the third mode, with 1.2% of
  // the energy, decays 9 times faster and is gone by 2T). Against eta omega^2 / (2 E) with the
  // measured omega the scheme's damping is checked alone; against eta k^2 / (2 rho),
  // k = pi / (2 L), the period's own discretisation error (+1.4% at L/dx = 80: the clamp holds
  // the bar a little behind x = 0) enters twice.
  const v1::Case c = test::load_case("elastic_bar_longitudinal_2d");
  const double eta = c.materials(0).elastic_damping();
  const EnergyRun e = run_body(c, "bar", 0, "elastic_energy_damped_bar");
  const double T = mean_period(e);
  ASSERT_GT(T, 0);
  const double omega = 2 * std::numbers::pi / T;
  std::vector<double> tt, lw;
  for (int n = 2; n * T <= e.t.back(); ++n) {
    const double tn = n * T;
    std::size_t k = 1;
    while (k + 1 < e.t.size() && e.t[k] < tn) ++k;
    const double f = (tn - e.t[k - 1]) / (e.t[k] - e.t[k - 1]);
    tt.push_back(tn);
    lw.push_back(std::log(e.energy[k - 1] + f * (e.energy[k] - e.energy[k - 1])));
  }
  ASSERT_GE(tt.size(), 6u);
  double st = 0, sl = 0, stt = 0, stl = 0;
  const double n = static_cast<double>(tt.size());
  for (std::size_t k = 0; k < tt.size(); ++k)
    st += tt[k], sl += lw[k], stt += tt[k] * tt[k], stl += tt[k] * lw[k];
  const double gamma = -0.5 * (n * stl - st * sl) / (n * stt - st * st);
  const double k_mode = std::numbers::pi / (2 * kBarLength);
  const double gamma_k = eta * k_mode * k_mode / (2 * kBarRho);
  const double gamma_omega = eta * omega * omega / (2 * kBarE);
  const double period_exact = 4 * kBarLength / std::sqrt(kBarE / kBarRho);
  std::printf(
      "Damped bar, eta = %g Pa s, %lld steps: period %.5f s (4 L / c = %.5f s, %+.2f%%); "
      "amplitude decay rate %.4f 1/s vs eta omega^2 / (2 E) = %.4f (%+.2f%%) and "
      "eta k^2 / (2 rho) = %.4f (%+.2f%%); energy after %.1f periods %.4f of the initial "
      "(exp(-2 gamma t) with the k rate %.4f)\n",
      eta, e.steps, T, period_exact, 100 * (T / period_exact - 1), gamma, gamma_omega,
      100 * (gamma / gamma_omega - 1), gamma_k, 100 * (gamma / gamma_k - 1), e.t.back() / T,
      e.energy.back() / e.energy[0], std::exp(-2 * gamma_k * e.t.back()));
  EXPECT_NEAR(gamma, gamma_omega, 0.02 * gamma_omega);
  EXPECT_NEAR(gamma, gamma_k, 0.05 * gamma_k);
  EXPECT_NEAR(T, period_exact, 0.03 * period_exact);
}

// The bar of UndampedBarKeepsItsEnergy at nu = 0.3 released with G = 16 1/s (strain at the clamp
// swinging between about -8% and +8%), Saint Venant-Kirchhoff, with hourglass control alpha
// (negative: Material.hourglass_control unset), to end_time.
v1::Case strained_bar(double G, double alpha, double end_time, v1::ElasticLaw law) {
  v1::Case c = test::load_case("elastic_bar_longitudinal_2d");
  v1::Material& m = *c.mutable_materials(0);
  m.set_elastic_law(law);
  m.set_poisson_ratio(0.3);
  m.set_elastic_damping(0);
  if (alpha >= 0) m.set_hourglass_control(alpha);
  c.mutable_elastic_bodies(0)
      ->mutable_initial_velocity_field()
      ->mutable_linear()
      ->mutable_gradient_x()
      ->set_x(G);
  c.mutable_time()->set_end_time(end_time);
  // Energy and displacement every 0.5 ms (about 50 samples a period).
  c.mutable_output()->set_series_interval(0.0005);
  c.mutable_output()->set_interval(end_time);
  return c;
}

// The hourglass alpha of the tests below (TrixiParticles' examples use it too): five times the
// smallest that held the 8% bar for 60 periods, 0.02 (docs/elastic_solids.md).
constexpr double kHourglassAlpha = 0.1;

TEST(ElasticEnergy, HourglassControlOutlivesTheCheckerboardMode) {
  // CI-sized: without hourglass control the checkerboard of the bar at 12% strain (G = 24 1/s)
  // inverts a particle after about 30 periods (0.74 s, docs/elastic_solids.md) and the guard
  // stops the run; with it the bar runs to 0.8 s (32 periods) and keeps its energy over the
  // first ten. (At 8% the bare bar now lasts 54 periods, too long for the suite.)
  const double end = 0.8;
  const EnergyRun bare = run_body(strained_bar(24, 0, end, v1::SAINT_VENANT_KIRCHHOFF), "bar", 0,
                                  "elastic_energy_bar_12pct_bare", false);
  const EnergyRun held =
      run_body(strained_bar(24, kHourglassAlpha, end, v1::SAINT_VENANT_KIRCHHOFF), "bar", 0,
               "elastic_energy_bar_12pct_held");
  ASSERT_EQ(held.status, RunStatus::kCompleted) << held.message;
  const double T = mean_period(held);
  ASSERT_GT(T, 0);
  const double error = energy_error(held, 10 * T);
  std::printf(
      "Bar at 12%% strain, Saint Venant-Kirchhoff: without hourglass control %s at t = %.4f s "
      "(%.1f periods, %.1f s wall): %s\n  with alpha = %g: t = %.3f s reached (%.1f periods, "
      "%lld steps, %.1f s wall), period %.5f s, largest |W/W0 - 1| over ten periods %.3g%%\n",
      to_string(bare.status), bare.end, bare.end / T, bare.wall, bare.message.c_str(),
      kHourglassAlpha, held.end, held.end / T, held.steps, held.wall, T, 100 * error);
  EXPECT_EQ(bare.status, RunStatus::kUnstable);
  EXPECT_NE(bare.message.find("inverted particle"), std::string::npos) << bare.message;
  EXPECT_LT(bare.end, end);
  EXPECT_LT(error, 0.01);
}

TEST(ElasticEnergy, HourglassControlLeavesTheCantileverPeriod) {
  // cases/oscillating_plate_2d (H/dx = 10) with alpha = kHourglassAlpha: bending is not affine,
  // F X_ab misses x_ab at second order and the pairs feel a little of the penalty's stiffness.
  // Without control the first period is 0.269455 s (ElasticSolid.CantileverPlateFirstPeriod,
  // docs/elastic_solids.md); with it the period may move by less than 0.5% and the energy
  // series (which leave the penalty's own energy out) by less than 1%.
  const double without = 0.269455;
  v1::Case c = test::load_case("oscillating_plate_2d");
  c.mutable_time()->set_end_time(0.3);
  c.mutable_materials(0)->set_hourglass_control(kHourglassAlpha);
  const EnergyRun e = run_body(c, "plate", 1, "elastic_energy_plate_hourglass");
  ASSERT_GE(e.crossings.size(), 2u);
  const double T = e.crossings[1];  // the tip starts at 0 moving up: T/2, then T
  const double error = energy_error(e, e.t.back());
  std::printf(
      "Cantilever plate, H/dx = 10, alpha = %g, %lld steps (%.1f s wall): first period %.6f s, "
      "without control %.6f s (%+.3f%%); largest |W/W0 - 1| %.3g%%\n",
      kHourglassAlpha, e.steps, e.wall, T, without, 100 * (T / without - 1), 100 * error);
  EXPECT_NEAR(T, without, 0.005 * without);
  EXPECT_LT(error, 0.01);
}

// The long runs behind docs/elastic_solids.md (minutes each; SPHD_ELASTIC_LONG=1): the bar at 8%
// and 4% strain, both laws, with hourglass control for 60 periods (1.5 s), the energy over
// the first ten and over all of them.
TEST(ElasticEnergy, HourglassControlLongRuns) {
  const char* v = std::getenv("SPHD_ELASTIC_LONG");
  if (!v || std::string(v) != "1") GTEST_SKIP() << "set SPHD_ELASTIC_LONG=1 (several minutes)";
  const double end = 1.5;
  for (const double G : {16.0, 8.0})
    for (const v1::ElasticLaw law : {v1::SAINT_VENANT_KIRCHHOFF, v1::NEO_HOOKEAN}) {
      const std::string name = std::string("elastic_energy_long_") +
                               (law == v1::NEO_HOOKEAN ? "nh_" : "svk_") +
                               std::to_string(static_cast<int>(G));
      const EnergyRun e = run_body(strained_bar(G, kHourglassAlpha, end, law), "bar", 0, name);
      ASSERT_EQ(e.status, RunStatus::kCompleted) << e.message;
      const double T = mean_period(e);
      ASSERT_GT(T, 0);
      double amplitude = 0;
      for (double u : e.u) amplitude = std::max(amplitude, std::abs(u));
      std::printf(
          "Bar, %s, G = %g 1/s (strain about %.0f%%), alpha = %g: t = %.3f s (%.1f periods, %lld "
          "steps, %.0f s wall), period %.5f s, tip amplitude %.3g m; largest |W/W0 - 1| over ten "
          "periods %.3g%%, over all %.3g%%\n",
          law_name(law), G, G / 2, kHourglassAlpha, e.end, e.end / T, e.steps, e.wall, T, amplitude,
          100 * energy_error(e, 10 * T), 100 * energy_error(e, e.end));
      EXPECT_GE(e.end / T, 50);
      EXPECT_LT(energy_error(e, 10 * T), 0.01);
    }
}

}  // namespace
}  // namespace sph
