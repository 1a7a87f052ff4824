// Every stability guard trips in a real run (issue: a run that goes unstable stops with a clear
// diagnosis instead of writing garbage). Each case is unstable by construction; the run must
// end unstable with a diagnosis that names the guard's field, the particle, the step and the
// time; what it wrote must be finite (the state that tripped the guard is not written), and
// the result file must say so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "case/load.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

// A 2D column of water (1 x 1, dx 0.05) in a tank 4 wide, g = 1, c = 10, plus `extra`.
std::string column(const std::string& extra, bool walls = true) {
  return std::string(R"(
    dimension: 2 dx: 0.05
    domain { lo { x: -0.2 y: -0.2 } hi { x: 4.2 y: 2.2 } }
    materials { name: "water" density: 1 eos { kind: TAIT sound_speed: 10 } }
    fluids { name: "column" material: "water" shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } }
    fluid_model { density: CONTINUITY artificial_viscosity: 0.1 }
    gravity { acceleration { y: -1 } }
    output { interval: 0.05 series_interval: 0.01 }
  )") +
         (walls
              ? R"(walls { name: "tank" shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 4 y: 2 } } } } } })"
              : "") +
         extra;
}

struct Tripped {
  RunOutcome outcome;
  std::string out;
};

// Runs the case; expects it to end unstable with `field` in the diagnosis and the written
// snapshots finite.
Tripped expect_trip(const std::string& name, const std::string& text, const std::string& field) {
  const std::string out = test::output_dir("guard_" + name);
  const RunOutcome r = test::run(parse_case_text(text), out);
  std::printf("%s: %s\n", name.c_str(), r.message.c_str());
  EXPECT_EQ(r.status, RunStatus::kUnstable) << r.message;
  EXPECT_NE(r.message.find(field), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("step "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("t = "), std::string::npos) << r.message;
  test::ResultReader rr(out + "/result.h5");
  EXPECT_EQ(rr.meta("status"), "unstable");
  EXPECT_EQ(rr.meta("message"), r.message);
  // The last state written is a good one: finite, and earlier than the failure.
  const test::Snapshot last = rr.last();
  for (double v : last.position) EXPECT_TRUE(std::isfinite(v));
  for (double v : last.velocity) EXPECT_TRUE(std::isfinite(v));
  for (double v : last.pressure) EXPECT_TRUE(std::isfinite(v));
  EXPECT_LE(last.time, r.time);
  return {r, out};
}

TEST(GuardsTrip, TimeStepForcedPastItsLimit) {
  // dt fixed at 20 times the acoustic bound 0.25 dx / c: the first wall contact flings the
  // column's corner faster than sound within four steps.
  expect_trip("forced_dt", column("time { end_time: 5 fixed_dt: 0.025 }"), "guards.max_mach");
}

TEST(GuardsTrip, DensityDeviation) {
  // The same with the speed guard out of the way: the compression runs away.
  expect_trip("density", column("time { end_time: 5 fixed_dt: 0.025 } guards { max_mach: 1e300 }"),
              "guards.max_density_deviation");
}

TEST(GuardsTrip, FasterThanSoundStopsOnMach) {
  expect_trip("mach", column(R"(time { end_time: 1 }
                        fluids { name: "jet" material: "water" initial_velocity { x: 25 }
                                 shape { box { lo { x: 2 y: 1 } hi { x: 2.2 y: 1.2 } } } })"),
              "guards.max_mach");
}

TEST(GuardsTrip, NonFiniteTemperatureStopsTheRun) {
  // Conduction in a strip with dt forced to ten times its bound 0.1 rho c_p h^2 / kappa
  // (Fuchs 2021 eq. 41): the explicit update amplifies the shortest wave by about 40 per step
  // and the temperature overflows, while the fluid itself stays at rest.
  expect_trip("non_finite", R"(dimension: 2 dx: 0.05 periodic_y: true
    domain { lo { x: -0.2 y: 0 } hi { x: 1.2 y: 0.4 } }
    materials { name: "f" density: 1 eos { sound_speed: 10 } heat_capacity: 1 thermal_conductivity: 1 }
    fluids { material: "f" shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } initial_temperature: 0 }
    walls { name: "hot" shape { box { lo { x: -1 y: 0 } hi { x: 0 y: 1 } } } temperature { value { constant: 1 } } }
    walls { name: "far" shape { box { lo { x: 1 y: 0 } hi { x: 2 y: 1 } } } }
    thermal { }
    time { end_time: 10 fixed_dt: 0.0025 }
    output { interval: 1 })",
              "non-finite temperature");
}

TEST(GuardsTrip, ParticleLeavingTheDomain) {
  // No walls: the column falls out of the domain.
  expect_trip("domain", column("time { end_time: 5 }", false), "left the domain");
}

TEST(GuardsTrip, TimeStepCollapse) {
  // The collapsing column accelerates; demanding dt >= 0.999 dt0 trips as soon as it does.
  expect_trip("dt_collapse", column("time { end_time: 2 } guards { min_dt_fraction: 0.999 }"),
              "guards.min_dt_fraction");
}

TEST(GuardsTrip, FluidDrivenIntoAWall) {
  // A plate moved down through the column at twice the sound speed, with the density and
  // speed guards out of the way: the fluid cannot get out of its way and ends up inside it.
  expect_trip("solid_fraction", column(R"(time { end_time: 1 }
                        walls { name: "plate" shape { box { lo { x: 0.2 y: 1.3 } hi { x: 0.8 y: 1.45 } } }
                                motion { velocity_y { constant: -20 } } }
                        guards { max_density_deviation: 1e300 max_mach: 1e300 })"),
              "guards.max_solid_fraction");
}

TEST(GuardsTrip, AbsurdContactStiffness) {
  // A disk resting on the floor with k_c = 1e16: the contact time step is millions of times
  // below the fluid's; the run stops before the step instead of taking forever.
  const auto t = expect_trip("contact_stiffness",
                             R"(dimension: 2 dx: 0.0002
    domain { lo { x: -0.001 y: -0.001 } hi { x: 0.011 y: 0.011 } }
    materials { name: "fluid" density: 1000 eos { kind: LINEAR sound_speed: 0.5 } kinematic_viscosity: 1e-5 }
    materials { name: "disk" phase: SOLID density: 1250 }
    fluids { name: "fluid" material: "fluid" shape { box { lo { x: 0 y: 0 } hi { x: 0.01 y: 0.01 } } } }
    walls { name: "box" shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 0.01 y: 0.01 } } } } } }
    bodies { name: "disk" material: "disk" shape { ball { center { x: 0.005 y: 0.0013 } radius: 0.00125 } }
             body_force: BUOYANCY_REDUCED buoyancy_fluid: "fluid" }
    contact { stiffness: 1e16 damping: 1 }
    fluid_model { density: SUMMATION }
    gravity { acceleration { y: -9.81 } apply_to_fluid: false }
    time { end_time: 0.1 }
    output { interval: 0.01 })",
                             "guards.max_contact_substeps");
  EXPECT_LT(t.outcome.wall_seconds, 30);
}

TEST(GuardsTrip, InvertedElasticParticle) {
  // A soft block (Saint Venant-Kirchhoff, nu = 0: lambda = 0, so its top and bottom faces stay
  // free of stress) hit hard along x: released with v_x = -G (x - x_c), its faces move inwards
  // at G W/2 = 3 times its wave speed c = sqrt(E / rho). The deformation is uniform, so inside
  // the block no force acts (the corrected operators are exact for it) until the release waves
  // from the free faces arrive at c: the middle is squeezed at F_xx = 1 - G t towards
  // F_xx = 0 at t = 1/G. Saint Venant-Kirchhoff does not stop it (its energy stays finite at
  // F = 0, and below F_xx = 1/sqrt(3) its stress falls as the squeeze grows, so the squeezed
  // material is unstable), and a particle of the middle inverts at about 1/G. The run must
  // stop there, naming the particle and a place inside the squeezed block.
  // G = 3 c / (W/2), c = sqrt(E / rho) = 31.62 m/s, W/2 = 0.05 m (the case text spells it).
  const double G = 1897.3665961010275, xc = 0.00125, yc = 0.00125, dx = 0.0025;
  const auto t = expect_trip("inverted_elastic", R"(dimension: 2 dx: 0.0025
    domain { lo { x: -0.1 y: -0.1 } hi { x: 0.1 y: 0.1 } }
    materials { name: "soft" phase: SOLID density: 1000 youngs_modulus: 1e6 poisson_ratio: 0 }
    elastic_bodies { name: "block" material: "soft"
      shape { box { lo { x: -0.05 y: -0.025 } hi { x: 0.0525 y: 0.0275 } } }
      constraints { region { ball { center { x: 0.00125 y: 0.00125 } radius: 0.001 } } }
      initial_velocity_field { linear { center { x: 0.00125 y: 0.00125 }
                                        gradient_x { x: -1897.3665961010275 } } } }
    time { end_time: 0.01 }
    output { interval: 0.0001 })",
                             "inverted particle (det F = ");
  const std::string& m = t.outcome.message;
  EXPECT_NE(m.find("elastic body block"), std::string::npos) << m;
  EXPECT_NE(m.find("particle id "), std::string::npos) << m;
  // The place and time: "... at (x, y), step N, t = T" after the particle's description.
  const std::size_t at = m.rfind(" at (");
  ASSERT_NE(at, std::string::npos) << m;
  double x = 0, y = 0, time = 0;
  long long step = 0;
  ASSERT_EQ(std::sscanf(m.c_str() + at, " at (%lf, %lf), step %lld, t = %lf", &x, &y, &step, &time),
            4)
      << m;
  std::printf(
      "inverted elastic: stopped at step %lld, t = %.6g = %.4f / G, the particle named "
      "at (%.6g, %.6g), %.3g m from the block's centre along x\n",
      step, time, G * time, x, y, x - xc);
  // Not before the middle is squeezed to half its width (F_xx = 0.5 is still stable ground),
  // not later than a tenth of 1/G past the collapse.
  EXPECT_GE(time, 0.5 / G);
  EXPECT_LE(time, 1.1 / G);
  EXPECT_LE(time, t.outcome.time + 1e-15);
  // Inside the block: its particles move along x only, the faces inwards.
  EXPECT_LE(std::abs(x - xc), 20 * dx);
  EXPECT_LE(std::abs(y - yc), 10 * dx + 1e-9);
}

TEST(GuardsTrip, WorkerExitsWithStatus3AndKeepsTheLastGoodState) {
  const std::string dir = test::output_dir("guard_worker");
  std::filesystem::create_directories(dir);
  const std::string case_path = dir + "/case.textproto";
  std::FILE* f = std::fopen(case_path.c_str(), "w");
  std::fputs(column("time { end_time: 5 fixed_dt: 0.025 }").c_str(), f);
  std::fclose(f);
  const std::string cmd = std::string(SPHD_WORKER_BIN) + " --quiet --case " + case_path +
                          " --out " + dir + "/out > " + dir + "/log.txt 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  std::FILE* log = std::fopen((dir + "/log.txt").c_str(), "r");
  std::string text(4096, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), log));
  std::fclose(log);
  EXPECT_NE(text.find("unstable"), std::string::npos) << text;
  EXPECT_NE(text.find("guards.max_mach"), std::string::npos) << text;
  test::ResultReader rr(dir + "/out/result.h5");
  EXPECT_GE(rr.snapshot_count(), 1);
  EXPECT_EQ(rr.meta("status"), "unstable");
}

}  // namespace
}  // namespace sph
