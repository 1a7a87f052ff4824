// Melting with latent heat against the Neumann solution of the one-phase Stefan problem
// (Carslaw & Jaeger 1959, sec. 11.2; e.g. Alexiades & Solomon 1993, sec. 2.1). A solid
// (a fixed rigid body) at the melting temperature T_m = 0 fills x > 0; the wall x < 0 is held
// at T_w = 1 from t = 0. Rigid particles above T_m become fluid (Fuchs 2021 "Reversible phase
// transition") and the latent heat L is absorbed by the apparent-capacity scheme (Remark 3)
// over [T_m - dT/2, T_m + dT/2]. With c = k = rho = 1 (alpha = 1) and Stefan number
// St = c (T_w - T_m)/L:
//   front X(t) = 2 lambda sqrt(alpha t),  lambda exp(lambda^2) erf(lambda) = St / sqrt(pi),
//   liquid T(x, t) = T_w - (T_w - T_m) erf(x / (2 sqrt(alpha t))) / erf(lambda).
// The solid starts at the bottom of the melting interval, so it holds no sensible heat below
// the band and the problem is the one-phase one as dT -> 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "case/load.h"
#include "case/number_text.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

std::string num(double v) {
  return number_text(v, 10);
}

// lambda exp(lambda^2) erf(lambda) = St/sqrt(pi) by bisection (the left side increases).
double neumann_lambda(double stefan) {
  double lo = 0, hi = 3;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid * std::exp(mid * mid) * std::erf(mid) < stefan / std::sqrt(M_PI) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct StefanRun {
  double front = 0;  // liquid mass per unit strip height / rho
  double front_exact = 0;
  double max_liquid_error = 0;  // max |T - exact| over liquid particles away from the front
  double t_min = 0, t_max = 0;
};

StefanRun run_stefan(double dx, double latent, double interval, double t_end) {
  const double strip_height = 8 * dx, pad = 3 * dx;
  const std::string text = "dimension: 2 dx: " + num(dx) + " domain { lo { x: " + num(-pad) +
                           " y: 0 } hi { x: " + num(1 + pad) + " y: " + num(strip_height) +
                           R"( } } periodic_y: true
      materials { name: "liquid" density: 1 eos { sound_speed: 10 } kinematic_viscosity: 0.1
                  heat_capacity: 1 thermal_conductivity: 1 }
      materials { name: "solid" phase: SOLID density: 1 heat_capacity: 1 thermal_conductivity: 1 }
      bodies { name: "slab" material: "solid" motion_type: FIXED
               shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } initial_temperature: )" +
                           num(-0.5 * interval) + R"( }
      walls { name: "hot" shape { box { lo { x: -1 y: 0 } hi { x: 0 y: 1 } } }
              temperature { value { constant: 1 } } }
      walls { name: "far" shape { box { lo { x: 1 y: 0 } hi { x: 2 y: 1 } } } }
      thermal { }
      phase_transitions { solid_material: "solid" fluid_material: "liquid" driver: TEMPERATURE
                          transition_value: 0 latent_heat: )" +
                           num(latent) + " latent_heat_interval: " + num(interval) + R"( }
      output { interval: )" +
                           num(t_end) + R"( }
      time { end_time: )" + num(t_end) +
                           " }";
  // One folder per run: ctest -j runs the tests using this at once.
  const std::string out = test::output_dir("stefan_dx" + num(dx) + "_L" + num(latent));
  const RunOutcome r = test::run(parse_case_text(text), out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const int last = rr.snapshot_count() - 1;
  const test::Snapshot s = rr.snapshot(last);
  const std::vector<double> T = rr.snapshot_field(last, "temperature");
  const double lambda = neumann_lambda(1.0 / latent), t = s.time;
  StefanRun out_run;
  out_run.front_exact = 2 * lambda * std::sqrt(t);
  out_run.t_min = 1e300;
  out_run.t_max = -1e300;
  double liquid_volume = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] == 1) continue;  // walls
    out_run.t_min = std::min(out_run.t_min, T[i]);
    out_run.t_max = std::max(out_run.t_max, T[i]);
    if (s.kind[i] != 0) continue;  // rigid: still solid
    liquid_volume += s.mass[i];    // rho = 1
    const double x = s.position[3 * i];
    // The apparent-capacity band smears the front over about interval/|dT/dx| plus a
    // particle: compare the profile where it is liquid in the exact solution by a margin.
    if (x < out_run.front_exact - 3 * dx) {
      const double exact = 1 - std::erf(x / (2 * std::sqrt(t))) / std::erf(lambda);
      out_run.max_liquid_error = std::max(out_run.max_liquid_error, std::abs(T[i] - exact));
    }
  }
  out_run.front = liquid_volume / strip_height;
  return out_run;
}

TEST(Stefan, MeltingFrontWithLatentHeatFollowsNeumann) {
  // St = 1 (L = 1): lambda = 0.6201; the front reaches x = 0.4 at t = 0.104.
  const double latent = 1, t_end = 0.1;
  std::vector<double> dxs = {0.02, 0.01}, front_err, liquid_err;
  for (double dx : dxs) {
    // The interval shrinks with dx so that the band stays about one particle wide.
    const StefanRun r = run_stefan(dx, latent, 0.05 * dx / 0.01, t_end);
    const double rel = std::abs(r.front - r.front_exact) / r.front_exact;
    front_err.push_back(rel);
    std::printf(
        "Stefan St = 1, t = %.3g, dx = %.3g: front %.4f vs Neumann %.4f (%.2f%%), liquid max |T - "
        "exact| %.2e, T in [%.4f, %.4f]\n",
        t_end, dx, r.front, r.front_exact, 100 * rel, r.max_liquid_error, r.t_min, r.t_max);
    // Maximum principle: no temperature outside [initial, wall].
    EXPECT_GE(r.t_min, -0.5 * 0.05 * dx / 0.01 - 1e-12);
    EXPECT_LE(r.t_max, 1 + 1e-12);
    liquid_err.push_back(r.max_liquid_error);
  }
  // At 40 particles across the melt: front within 2%, liquid temperatures within 0.02 of
  // T_w - T_m; both improve with resolution (first order in the profile: the mirror wall
  // value and the smeared band).
  EXPECT_LT(front_err.back(), 0.02);
  EXPECT_LT(front_err.back(), front_err.front());
  EXPECT_LT(liquid_err.back(), 0.02);
  EXPECT_LT(liquid_err.back(), 0.7 * liquid_err.front());
}

TEST(Stefan, WithoutLatentHeatTheFrontIsTheMeltingIsotherm) {
  // The same slab with a negligible latent heat: the front is then the T = T_m isotherm of
  // pure conduction from T_0 = -dT/2 with the wall at 1, T_0 + (1 - T_0) erfc(X / 2 sqrt(t)) = 0,
  // far ahead of the Neumann front: the latent heat, not conduction, sets the front above.
  const double t_end = 0.05, dx = 0.02, interval = 0.1, t0 = -0.5 * interval;
  const StefanRun r = run_stefan(dx, 1e-6, interval, t_end);
  double lo = 0, hi = 5;  // erfc(z) = -t0 / (1 - t0), erfc decreasing
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid) > -t0 / (1 - t0) ? lo : hi) = mid;
  }
  const double isotherm = 2 * 0.5 * (lo + hi) * std::sqrt(t_end);
  std::printf("no latent heat, t = %.3g: front %.4f, conduction isotherm %.4f, Neumann %.4f\n",
              t_end, r.front, isotherm, 2 * neumann_lambda(1.0) * std::sqrt(t_end));
  EXPECT_NEAR(r.front, isotherm, 2 * dx);
}

// An insulated strip: liquid at T_l on [-1, 0] against a fixed solid at T_s on [0, 1], T_m = 0,
// L = 0.5 over [-0.1, 0.1], reversible with a hysteresis of 0.05. The enthalpy sum m h(T) is
// conserved to round-off by the symmetric pair fluxes (both phases have c_p = 1, so h does not
// jump when a particle changes phase), and no temperature leaves [min, max] of the initial
// values. Returns the melted and solidified particle counts.
std::pair<double, double> closed_strip(double t_liquid, double t_solid, const std::string& name) {
  const double dx = 0.02, pad = 3 * dx;
  const std::string text = "dimension: 2 dx: " + num(dx) + " domain { lo { x: " + num(-1 - pad) +
                           " y: 0 } hi { x: " + num(1 + pad) + " y: " + num(8 * dx) +
                           R"( } } periodic_y: true
      materials { name: "liquid" density: 1 eos { sound_speed: 10 } kinematic_viscosity: 0.1
                  heat_capacity: 1 thermal_conductivity: 1 }
      materials { name: "solid" phase: SOLID density: 1 heat_capacity: 1 thermal_conductivity: 1 }
      fluids { material: "liquid" shape { box { lo { x: -1 y: 0 } hi { x: 0 y: 1 } } }
               initial_temperature: )" +
                           num(t_liquid) + R"( }
      bodies { name: "slab" material: "solid" motion_type: FIXED
               shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } initial_temperature: )" +
                           num(t_solid) + R"( }
      walls { shape { box { lo { x: -2 y: 0 } hi { x: -1 y: 1 } } } }
      walls { shape { box { lo { x: 1 y: 0 } hi { x: 2 y: 1 } } } }
      thermal { }
      phase_transitions { solid_material: "solid" fluid_material: "liquid" driver: TEMPERATURE
                          transition_value: 0 hysteresis: 0.05 reversible: true
                          latent_heat: 0.5 latent_heat_interval: 0.2 }
      output { interval: 0.2 series_interval: 0.01 }
      time { end_time: 0.2 })";
  // Its own folder per test: ctest -j runs the two at once.
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(parse_case_text(text), out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const auto energy = rr.series("diagnostics/thermal_energy");
  const auto tmin = rr.series("diagnostics/temperature_min");
  const auto tmax = rr.series("diagnostics/temperature_max");
  double drift = 0;
  for (double e : energy) drift = std::max(drift, std::abs(e - energy.front()));
  const double scale = std::abs(energy.front());
  const std::pair<double, double> changed = {rr.series("phase/melted").back(),
                                             rr.series("phase/solidified").back()};
  std::printf(
      "closed strip, liquid at %g | solid at %g: enthalpy %.6g -> %.6g (max drift %.2e "
      "relative), T in [%.4f, %.4f] at t = 0.2, %g melted, %g solidified\n",
      t_liquid, t_solid, energy.front(), energy.back(), drift / scale, tmin.back(), tmax.back(),
      changed.first, changed.second);
  EXPECT_LT(drift / scale, 1e-10);
  for (std::size_t k = 0; k < tmin.size(); ++k) {
    EXPECT_GE(tmin[k], t_solid - 1e-12);
    EXPECT_LE(tmax[k], t_liquid + 1e-12);
  }
  return changed;
}

TEST(Stefan, LatentHeatIsConservedThroughMelting) {
  // Contact temperature 0.4 (equal effusivities): the solid melts from the interface.
  const auto [melted, frozen] = closed_strip(1.0, -0.2, "stefan_closed_melting");
  EXPECT_GT(melted, 0);
  EXPECT_EQ(frozen, 0);
}

TEST(Stefan, LatentHeatIsConservedThroughFreezing) {
  // Contact temperature -0.4: the liquid freezes onto the body.
  const auto [melted, frozen] = closed_strip(0.2, -1.0, "stefan_closed_freezing");
  EXPECT_EQ(melted, 0);
  EXPECT_GT(frozen, 0);
}

}  // namespace
}  // namespace sph
