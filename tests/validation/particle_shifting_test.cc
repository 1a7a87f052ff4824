// Particle shifting (solver/physics/particle_shifting.h; docs/particle_shifting.md) at CI size:
// the Taylor-Green vortex's velocity field over three resolutions with shifting instead of
// the transport velocity, the tank at rest, and the Koshizuka-Oka surge front with density
// diffusion and shifting against the run without shifting.
// tests/validation/particle_shifting/run.sh runs the full-size comparisons and writes
// tests/validation/reports/particle_shifting.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/evaluate_reference.h"
#include "analysis/series_data.h"
#include "case/load.h"
#include "solver/core/kernel.h"
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

// The Taylor-Green vortex (cases/taylor_green_2d, Re = 100, t = 2) with summation density and
// shifting in place of the transport velocity; the error is the case's: mean |u - u_exact|
// relative to the exact amplitude at the end time.
double taylor_green_error(double dx) {
  auto c = test::load_case("taylor_green_2d");
  c.set_dx(dx);
  c.mutable_fluid_model()->set_transport_velocity(false);
  // The largest speed (as Sun et al. 2017) with A = 6, the top of Skillen et al.'s range: the
  // local speed leaves the stagnation points, where the particles cluster, nearly unshifted
  // (docs/particle_shifting.md: 40% / 28% / 23% with the default LOCAL, A = 2).
  auto* ps = c.mutable_fluid_model()->mutable_particle_shifting();
  ps->set_speed(v1::ParticleShifting::MAXIMUM);
  ps->set_coefficient(6);
  c.mutable_output()->set_interval(0);
  char name[64];
  std::snprintf(name, sizeof name, "shifting_tgv_%.4f", dx);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const analysis::Measurement m = analysis::evaluate_reference(c, out + "/result.h5");
  std::printf("Taylor-Green dx = %.4f with particle shifting: %s\n", dx, m.detail.c_str());
  return m.error;
}

// The study's first three levels (docs/accuracy.md: with the transport velocity 21.1%, 14.8%,
// 10.3%, order 0.98 over five levels), printing the observed order.
TEST(ParticleShifting, TaylorGreenVelocityFieldOrder) {
  const double dx[3] = {0.05, 1.0 / 28, 0.025};
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = taylor_green_error(dx[k]);
  // Least-squares slope of log e against log dx.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < 3; ++k) {
    const double x = std::log(dx[k]), y = std::log(e[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double order = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
  std::printf(
      "Taylor-Green with particle shifting: velocity field error %.2f%% / %.2f%% / %.2f%% at "
      "dx = 0.05 / 0.0357 / 0.025, observed order %.2f (transport velocity: 21.1%% / 14.8%% / "
      "10.3%%, order 0.98)\n",
      100 * e[0], 100 * e[1], 100 * e[2], order);
  // Issue #43 asked for an order above 1.5: not reached (0.8-0.9 at every setting tried,
  // docs/particle_shifting.md). What holds: the field is closer than the transport velocity's
  // at each level.
  EXPECT_LT(e[0], 0.211);
  EXPECT_LT(e[1], 0.148);
  EXPECT_LT(e[2], 0.103);
}

// The tank at rest (cases/studies/hydrostatic_tank_2d, dx = 0.05, h = 2 dx, t = 10) with
// shifting at the largest speed of the step (the stronger form): the bottom pressure stays
// at rho g (H + dx/2) within 0.5% and no particle leaves the surface.
TEST(ParticleShifting, TankAtRestStaysAtRest) {
  auto c = test::load_case("studies/hydrostatic_tank_2d");
  c.mutable_fluid_model()->mutable_particle_shifting()->set_speed(v1::ParticleShifting::MAXIMUM);
  const std::string out = test::output_dir("shifting_tank");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const analysis::Measurement p = analysis::evaluate_reference(c, out + "/result.h5");
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot s = rr.last();
  double top = -1e300, speed = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    top = std::max(top, s.position[3 * i + 1]);
    speed = std::max(speed, std::hypot(s.velocity[3 * i], s.velocity[3 * i + 1]));
  }
  const auto shift = rr.series("particle_shifting/max_shift");
  const double largest_shift = *std::max_element(shift.begin(), shift.end());
  std::printf(
      "Tank at rest with particle shifting (MAXIMUM), dx = 0.05, t = 10: %s; highest particle "
      "y = %.4f (surface 0.9, top row 0.875), largest speed %.2e, largest shift in a step "
      "%.2e h\n",
      p.detail.c_str(), top, speed, largest_shift);
  EXPECT_LT(p.error, 0.005);
  EXPECT_LT(top, 0.9);
}

// The fraction of fluid particles whose kernel support (over fluid and wall particles, each
// of volume dx^2) is less than 95% complete: the free surface, and every void or splash
// inside the fluid adds to it.
double incomplete_support_fraction(const test::Snapshot& s, double dx) {
  const QuinticSpline<2> k(dx);
  const double rc = 3 * dx;
  std::size_t fluid = 0, open = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    ++fluid;
    double sum = 0;
    for (std::size_t j = 0; j < s.size(); ++j) {
      const double r = std::hypot(s.position[3 * i] - s.position[3 * j],
                                  s.position[3 * i + 1] - s.position[3 * j + 1]);
      if (r < rc) sum += dx * dx * k.W(r);
    }
    if (sum < 0.95) ++open;
  }
  return static_cast<double>(open) / static_cast<double>(fluid);
}

// The surge front of the 1 x 2 column (cases/dambreak_martin_moyce_2d at dx = a/25, T <= 3)
// against Koshizuka & Oka's experiment, with density diffusion, without and with shifting:
// shifting must not change how the front runs.
TEST(ParticleShifting, SurgeFrontWithDensityDiffusion) {
  double err[2], open[2];
  for (int with = 0; with < 2; ++with) {
    auto c = test::load_case("dambreak_martin_moyce_2d");
    c.set_dx(0.04);
    c.mutable_time()->set_end_time(2.1);  // T = t sqrt(2 g / a) up to 3
    c.mutable_output()->set_interval(0);
    c.mutable_fluid_model()->mutable_density_diffusion()->set_form(v1::DensityDiffusion::FOURTAKAS);
    if (with) c.mutable_fluid_model()->mutable_particle_shifting();
    const std::string out = test::output_dir(with ? "shifting_front" : "shifting_front_plain");
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    err[with] = test::surge_front_error(c, out);
    test::ResultReader rr(out + "/result.h5");
    open[with] = incomplete_support_fraction(rr.last(), c.dx());
    std::printf(
        "Surge front dx = a/25, T <= 3, density diffusion %s particle shifting: mean deviation "
        "from Koshizuka-Oka %.2f%%; fluid particles with less than 95%% of a kernel support at "
        "T = 3: %.1f%%\n",
        with ? "with" : "without", 100 * err[with], 100 * open[with]);
  }
  EXPECT_LT(std::abs(err[1] - err[0]), 0.01);
  // Shifting leaves more of the fluid with an incomplete support at T = 3 (7.2% against
  // 5.9% measured): docs/particle_shifting.md. Bounded here so that it cannot grow unnoticed.
  EXPECT_LT(open[1], 1.5 * open[0]);
}

// ---- Full size (tests/validation/particle_shifting/run.sh runs these; each prints Markdown
// table rows for tests/validation/reports/particle_shifting.md) ----

// The Taylor-Green study's five levels (docs/accuracy.md) with shifting, LOCAL and MAXIMUM.
TEST(ParticleShifting, DISABLED_TaylorGreenFiveLevels) {
  const double dx[5] = {0.05, 1.0 / 28, 0.025, 1.0 / 56, 0.0125};
  const struct {
    v1::ParticleShifting::Speed speed;
    double a;
    const char* label;
  } forms[] = {{v1::ParticleShifting::LOCAL, 2, "LOCAL, A = 2"},
               {v1::ParticleShifting::MAXIMUM, 2, "MAXIMUM, A = 2"},
               {v1::ParticleShifting::MAXIMUM, 6, "MAXIMUM, A = 6"}};
  for (const auto& form : forms) {
    double e[5];
    for (int k = 0; k < 5; ++k) {
      auto c = test::load_case("taylor_green_2d");
      c.set_dx(dx[k]);
      c.mutable_fluid_model()->set_transport_velocity(false);
      c.mutable_fluid_model()->mutable_particle_shifting()->set_speed(form.speed);
      c.mutable_fluid_model()->mutable_particle_shifting()->set_coefficient(form.a);
      c.mutable_output()->set_interval(0);
      const std::string out = test::output_dir("shifting_tgv_full");
      const RunOutcome r = test::run(c, out);
      ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
      e[k] = analysis::evaluate_reference(c, out + "/result.h5").error;
      std::printf("| TGV | %s | %.4f | %.2f%% | %lld | %.1f s |\n", form.label, dx[k], 100 * e[k],
                  static_cast<long long>(r.steps), r.wall_seconds);
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < 5; ++k) {
      const double x = std::log(dx[k]), y = std::log(e[k]);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    std::printf("| TGV order | %s | five levels | %.2f | | |\n", form.label,
                (5 * sxy - sx * sy) / (5 * sxx - sx * sx));
  }
}

// The Colagrossi dam break (dx = H/25, to t sqrt(g/H) = 8) with density diffusion, without
// and with shifting: the wall probe against Buchner P1 and how much of the fluid has an
// incomplete kernel support (surface, voids, splashes) at t = 2, 4, 6, 8.
TEST(ParticleShifting, DISABLED_ColagrossiWithDensityDiffusion) {
  const test::ImpactFigures ref =
      test::impact_figures(test::buchner_p1(data("dambreak_buchner2002_P1_pysph.csv")));
  std::printf("| Buchner 2002 P1 | %.2f | %.3f | %.3f | | |\n", ref.peak, ref.plateau, ref.second);
  for (int with = 0; with < 2; ++with) {
    auto c = test::load_case("colagrossi_dambreak_2d");
    c.set_dx(0.04);
    c.mutable_time()->set_end_time(8);
    c.mutable_output()->set_interval(2);
    c.mutable_fluid_model()->mutable_density_diffusion()->set_form(v1::DensityDiffusion::FOURTAKAS);
    if (with) c.mutable_fluid_model()->mutable_particle_shifting();
    const std::string out =
        test::output_dir(with ? "shifting_colagrossi" : "shifting_colagrossi_dd");
    const RunOutcome r = test::run(c, out);
    ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
    test::ResultReader rr(out + "/result.h5");
    const test::ImpactFigures f = test::impact_figures(
        test::probe_signal(rr.series("probes/wall_p1/time"), rr.series("probes/wall_p1/pressure")));
    std::string open;
    for (int k = 1; k < rr.snapshot_count(); ++k) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%s%.1f%%", k > 1 ? " / " : "",
                    100 * incomplete_support_fraction(rr.snapshot(k), c.dx()));
      open += buf;
    }
    std::printf("| %s | %.2f (%.2fx) | %.3f (%+.1f%%) | %.3f (%+.1f%%) | %.4f | %s | %.0f s |\n",
                with ? "density diffusion + shifting" : "density diffusion", f.peak,
                f.peak / ref.peak, f.plateau, 100 * (f.plateau / ref.plateau - 1), f.second,
                100 * (f.second / ref.second - 1), f.noise, open.c_str(), r.wall_seconds);
  }
}

// The free drop of docs/surface_tension.md "Not done at free surfaces": R/dx = 20, sigma = 1,
// rho = 1, c = 10, started in the Laplace state (background pressure sigma / R), mu = 0.01,
// to t = 3: without shifting it stops on the density guard at t = 1.15.
v1::Case free_drop(double mu, const std::string& shifting) {
  return parse_case_text(
      "name: \"free_drop\"\ndimension: 2\ndx: 0.05\n"
      "domain { lo { x: -3 y: -3 } hi { x: 3 y: 3 } }\n"
      "materials { name: \"drop\" density: 1 eos { kind: LINEAR sound_speed: 10 "
      "background_pressure: 1 } dynamic_viscosity: " +
      std::to_string(mu) +
      " }\n"
      "fluids { name: \"drop\" material: \"drop\" shape { ball { radius: 1 } } }\n"
      "surface_tension { pairs { material_a: \"drop\" sigma: 1 } }\n"
      "fluid_model { density: CONTINUITY " +
      shifting +
      " }\n"
      "time { end_time: 3 }\n"
      "output { interval: 0.05 series_interval: 0.005 }\n");
}

TEST(ParticleShifting, DISABLED_FreeDropLowViscosity) {
  const double dx = 0.05;
  for (const char* shifting : {"", "particle_shifting { }", "particle_shifting { speed: MAXIMUM }",
                               "particle_shifting { coefficient: 6 speed: MAXIMUM }"}) {
    const v1::Case c = free_drop(0.01, shifting);
    const std::string out = test::output_dir("shifting_free_drop");
    const RunOutcome r = test::run(c, out);
    test::ResultReader rr(out + "/result.h5");
    const test::Snapshot first = rr.snapshot(0);
    const auto fluid = std::count(first.kind.begin(), first.kind.end(), std::uint8_t{0});
    const double Rn = std::sqrt(static_cast<double>(fluid) * dx * dx / 3.141592653589793);
    // The mean pressure more than 4 h inside, over the snapshots of t >= 1.5 (as
    // SurfaceTension.FreeDropSpuriousCurrents), and the largest speed of t >= 2.
    double inside = 0;
    int n = 0;
    for (int k = 0; k < rr.snapshot_count(); ++k) {
      const test::Snapshot s = rr.snapshot(k);
      if (s.time < 1.5) continue;
      double sum = 0;
      int count = 0;
      for (std::size_t i = 0; i < s.size(); ++i)
        if (std::hypot(s.position[3 * i], s.position[3 * i + 1]) < Rn - 4 * dx) {
          sum += s.pressure[i];
          ++count;
        }
      inside += sum / count;
      ++n;
    }
    const auto t = rr.series("diagnostics/time");
    const auto vmax = rr.series("diagnostics/max_speed");
    double spurious = 0, early = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k] >= 2) spurious = std::max(spurious, vmax[k]);
      if (t[k] <= 1) early = std::max(early, vmax[k]);
    }
    char jump[32] = "-", late[32] = "-";
    if (n > 0) std::snprintf(jump, sizeof jump, "%+.2f%%", 100 * (inside / n * Rn - 1));
    if (t.back() >= 2) std::snprintf(late, sizeof late, "%.3g", spurious);
    const std::string message =
        r.status == RunStatus::kCompleted ? "completed" : "stopped: " + r.message;
    std::string outcome;  // a Markdown table cell: its bars escaped
    for (const char ch : message) {
      if (ch == '|') outcome += '\\';
      outcome += ch;
    }
    std::printf("| %s | %s (t = %.3f) | %s | %.3g | %s |\n", *shifting ? shifting : "without",
                outcome.c_str(), r.time, jump, early, late);
  }
}

}  // namespace
}  // namespace sph
