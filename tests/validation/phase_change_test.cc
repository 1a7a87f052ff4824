// Reversible phase transitions end to end, on two of Fuchs 2021's seed scenes at coarse
// resolution:
//  - "Gastric disintegration of food boluses": 60 boluses dissolve into chyme as the
//    concentration diffusing in from the gastric juice passes C_t, while a moving constriction
//    drives a jet. The paper's result is qualitative (boluses shrink, some disappear by
//    t = 0.875); the invariants are exact.
//  - "Powder grains exposed to a highly dynamic gas flow", a short start: grains melt at the
//    hot lower walls while the gas jet (started early here) flows in and out through the
//    open boundaries. Mass is exact: the metal's (rigid + melt) does not change, the total
//    changes by the gas particles that crossed the open boundaries.
// and on a moving, spinning disk in a periodic box, melting and freezing, whose total
// momentum (fluid plus bodies) must not change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "case/load.h"
#include "solver/core/types.h"
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

TEST(PhaseChange, ABodyThatMeltsLeavesNoContactBehind) {
  // Grain B moves into grain A. Solid, A holds B off through the contact in every step. Above
  // its melting point, A turns to liquid at the end of the first step, and from then on B has
  // no body to touch: the contact must not push it off the particles that were A's (liquid
  // now), as it would with the contact candidates of the search made before the transition.
  // Gas and metal of the 2D powder scene; the grains' facing rows are one dx apart.
  auto scene = [](double temperature_a) {
    return parse_case_text(R"(dimension: 2 dx: 0.25
      domain { lo { x: -1 y: -1 } hi { x: 7 y: 5 } }
      materials { name: "gas" density: 0.1 eos { reference_pressure: 16e6 }
                  kinematic_viscosity: 100 transport_background_pressure: 16e6
                  heat_capacity: 0.01 thermal_conductivity: 0.1 }
      materials { name: "liquid_metal" density: 1 eos { reference_pressure: 16e6 }
                  kinematic_viscosity: 100 transport_background_pressure: 16e6 heat_capacity: 1
                  thermal_conductivity: 10 }
      materials { name: "solid_metal" phase: SOLID density: 1 heat_capacity: 1
                  thermal_conductivity: 10 }
      fluids { name: "gas" material: "gas" initial_temperature: 50
               shape { box { lo { x: 0 y: 0 } hi { x: 6 y: 4 } } } }
      walls { name: "box" shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 6 y: 4 } } } } } }
      bodies { name: "A" material: "solid_metal" initial_temperature: )" +
                           std::to_string(temperature_a) + R"(
               shape { ball { center { x: 2.125 y: 2 } radius: 0.8 } } }
      bodies { name: "B" material: "solid_metal" initial_temperature: 25
               initial_velocity { x: -1 } shape { ball { center { x: 3.9 y: 2 } radius: 0.8 } } }
      contact { stiffness: 1e8 damping: 1e2 }
      thermal { initial_temperature: 50 }
      phase_transitions { solid_material: "solid_metal" fluid_material: "liquid_metal"
                          driver: TEMPERATURE transition_value: 50 hysteresis: 2 reversible: true }
      fluid_model { transport_velocity: true }
      time { end_time: 1 max_steps: 6 }
      output { interval: 0 series_interval: 1e-12 })");
  };
  // B's touching pairs at t = 0 and after each of the six steps, and the melted count.
  auto run = [&](double temperature_a, const std::string& name) {
    const std::string out = test::output_dir(name);
    const RunOutcome r = test::run(scene(temperature_a), out);
    EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
    test::ResultReader rr(out + "/result.h5");
    const auto contacts = rr.series("bodies/contacts");
    const auto melted = rr.series("phase/melted");
    const std::size_t samples = melted.size(), slots = contacts.size() / samples;
    std::vector<double> b;
    for (std::size_t k = 0; k < samples; ++k) b.push_back(contacts[k * slots + 1]);
    std::printf("A at %g: grain B's touching pairs per step:", temperature_a);
    for (const double n : b) std::printf(" %g", n);
    std::printf("; melted %g\n", melted.back());
    return std::make_pair(b, melted);
  };
  const auto [solid, none] = run(25, "phase_contact_solid");
  const auto [melting, melted] = run(60, "phase_contact_melting");
  ASSERT_EQ(solid.size(), 7u);
  ASSERT_EQ(melting.size(), 7u);
  EXPECT_EQ(none.back(), 0.0);
  for (std::size_t k = 1; k < solid.size(); ++k) EXPECT_GT(solid[k], 0.0) << "step " << k;
  EXPECT_GT(melted[1], 20.0);  // all of A (about 32 particles) melted at the end of step 1
  EXPECT_EQ(melted.back(), melted[1]);
  for (std::size_t k = 1; k < melting.size(); ++k) EXPECT_EQ(melting[k], 0.0) << "step " << k;
}

// A spinning disk moving through a periodic box (no walls, no gravity: nothing outside acts
// on fluid and bodies together, so their total momentum stays the disk's initial M U) of
// water, with `regions` for the fluid; the disk (at T = 50) melts into the fluid "melt" above
// 50.5, which freezes below 49.5.
v1::Case moving_disk_in_periodic_water(const std::string& regions) {
  return parse_case_text(R"(dimension: 2 dx: 0.02
    domain { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } periodic_x: true periodic_y: true
    materials { name: "water" density: 1 eos { sound_speed: 10 } kinematic_viscosity: 0.01
                heat_capacity: 1 thermal_conductivity: 0.1 }
    materials { name: "melt" density: 1 eos { sound_speed: 10 } kinematic_viscosity: 0.01
                heat_capacity: 1 thermal_conductivity: 0.1 }
    materials { name: "solid" phase: SOLID density: 1 heat_capacity: 1 thermal_conductivity: 0.1 }
    bodies { name: "disk" material: "solid" initial_temperature: 50
             initial_velocity { x: 1 y: 0.5 } initial_angular_velocity { z: 2 }
             shape { ball { center { x: 0.5 y: 0.5 } radius: 0.2 } } }
    thermal { }
    phase_transitions { solid_material: "solid" fluid_material: "melt" driver: TEMPERATURE
                        transition_value: 50 hysteresis: 1 reversible: true }
    fluid_model { density: SUMMATION transport_velocity: true }
    time { end_time: 1 max_steps: 300 }
    output { interval: 0 series_interval: 1e-12 })" +
                         regions);
}

// Over the series of a run: the largest change of fluid plus bodies' momentum relative to
// the initial one and of their total mass, and the bodies' total mass at the end.
struct Invariants {
  double momentum_change = 0, mass_change = 0, body_mass_start = 0, body_mass_end = 0;
  double melted = 0, solidified = 0;
};
// Runs the case into test-output/<name> and measures its invariants; a run that does not
// complete ends the test (gtest reports the exception with the run's message).
Invariants run_and_measure(const v1::Case& c, const std::string& name) {
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  if (r.status != RunStatus::kCompleted)
    throw std::runtime_error(name + ": the run did not complete: " + r.message);
  test::ResultReader rr(out + "/result.h5");
  const auto fluid_p = rr.series("diagnostics/momentum"), fluid_m = rr.series("diagnostics/mass");
  const auto body_m = rr.series("bodies/mass"), body_u = rr.series("bodies/velocity");
  const auto melted = rr.series("phase/melted");
  const std::size_t samples = melted.size(), slots = body_m.size() / samples;
  EXPECT_EQ(fluid_p.size(), 2 * samples);
  Invariants inv;
  Vec<2> p0 = Vec<2>::Zero();
  double m0 = 0;
  for (std::size_t k = 0; k < samples; ++k) {
    Vec<2> p(fluid_p[2 * k], fluid_p[2 * k + 1]);
    double m_bodies = 0;
    for (std::size_t b = 0; b < slots; ++b) {
      const double m = body_m[k * slots + b];
      if (std::isnan(m)) continue;  // a slot without a body
      p += m * Vec<2>(body_u[2 * (k * slots + b)], body_u[2 * (k * slots + b) + 1]);
      m_bodies += m;
    }
    if (k == 0) {
      p0 = p;
      m0 = fluid_m[0] + m_bodies;
      inv.body_mass_start = m_bodies;
    }
    inv.momentum_change = std::max(inv.momentum_change, (p - p0).norm() / p0.norm());
    inv.mass_change = std::max(inv.mass_change, std::abs(fluid_m[k] + m_bodies - m0) / m0);
    inv.body_mass_end = m_bodies;
  }
  inv.melted = melted.back();
  inv.solidified = rr.series("phase/solidified").back();
  return inv;
}

// Prints the invariants of a run in which `count` particles `changed` (melted, solidified)
// and requires fluid plus bodies to keep their momentum and mass to round-off.
void expect_momentum_and_mass_kept(const char* what, double count, const char* changed,
                                   const Invariants& inv) {
  std::printf(
      "%s: %g particles %s, body mass %.4f -> %.4f; "
      "largest relative change of the total momentum %.2e, of the mass %.2e\n",
      what, count, changed, inv.body_mass_start, inv.body_mass_end, inv.momentum_change,
      inv.mass_change);
  EXPECT_LT(inv.momentum_change, 1e-12) << what;
  EXPECT_LT(inv.mass_change, 1e-14) << what;
}

// A half-melted body keeps moving with the momentum eq. 29 gives it, over a run: the disk
// melts from its side in the hot half of the box while it moves; the melt carries away the
// momentum the rigid motion gave it and the remaining body keeps the rest.
TEST(PhaseChange, AHalfMeltedBodyKeepsTheMomentumOfItsRemainingPart) {
  const auto c = moving_disk_in_periodic_water(R"(
    fluids { material: "water" initial_temperature: 0 shape { box { lo { x: 0 y: 0 } hi { x: 0.5 y: 1 } } } }
    fluids { material: "water" initial_temperature: 100 shape { box { lo { x: 0.5 y: 0 } hi { x: 1 y: 1 } } } })");
  const Invariants inv = run_and_measure(c, "phase_half_melted_momentum");
  // Momentum: 7e-15; 3e-3 when a melted particle took the body's acceleration at its place
  // (with the pull of the rest of the body) instead of its own share of the body's fluid force.
  expect_momentum_and_mass_kept("half-melted disk", inv.melted, "melted in 300 steps", inv);
  EXPECT_GT(inv.melted, 20.0);                               // melting went on ...
  EXPECT_GT(inv.body_mass_end, 0.25 * inv.body_mass_start);  // ... with a body left (0.45)
}

// The reverse: a ring of cold melt around the moving disk (the disk's lattice points are the
// body's, and earlier regions win over later ones) freezes onto it in the first step and the
// grown body moves on, now with the fluid forces of the frozen particles too.
TEST(PhaseChange, LiquidFreezingOntoAMovingBodyKeepsTheTotalMomentum) {
  const auto c = moving_disk_in_periodic_water(R"(
    fluids { material: "melt" initial_temperature: 40
             shape { ball { center { x: 0.5 y: 0.5 } radius: 0.24 } } }
    fluids { material: "water" initial_temperature: 50 shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } })");
  const Invariants inv = run_and_measure(c, "phase_frozen_on_momentum");
  // Momentum: 4e-15; 2.6e-3 when the frozen particles brought no force into their body's sum.
  expect_momentum_and_mass_kept("disk with a frozen ring", inv.solidified, "solidified", inv);
  EXPECT_GT(inv.solidified, 50.0);
  EXPECT_GT(inv.body_mass_end, inv.body_mass_start);
}

// The first 0.008 of the 2D powder scene at its coarse dx = 0.25 (9.3k particles, 1.6k steps),
// with the gas jet started at t = 0.002 (ramped over 0.002) instead of 0.25 so that the short
// run sees it. The full coarse run to t = 0.75 is in tests/validation/reports/seed_scenes.md.
TEST(PhaseChange, PowderGrainsMeltWhileGasFlowsThrough) {
  auto c = test::load_case("powder_grains_2d_coarse");
  c.mutable_time()->set_end_time(0.008);
  c.mutable_output()->set_interval(0.002);
  c.mutable_output()->set_series_interval(0.0005);
  for (auto& o : *c.mutable_open_boundaries()) {
    o.set_start_time(0.002);
    o.set_ramp_time(0.002);
  }
  const std::string out = test::output_dir("phase_powder");
  const RunOutcome r = test::run(c, out);
  // No guard tripped (density, Mach, solid fraction, contact sub-steps, non-finite scalars).
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const int gas = 0;  // material order of the case: gas, liquid_metal, solid_metal
  const double m_gas = c.materials(gas).density() * c.dx() * c.dx();
  // Masses of snapshot k: all fluid + rigid particles (buffers included), and the metal's.
  auto masses = [&](int k) {
    const test::Snapshot s = rr.snapshot(k);
    const auto mat = rr.snapshot_field(k, "material");
    double total = 0, metal = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] == 1) continue;
      total += s.mass[i];
      if (mat[i] != gas) metal += s.mass[i];
    }
    return std::make_pair(total, metal);
  };
  const auto [total0, metal0] = masses(0);
  double metal_err = 0;
  for (int k = 0; k < rr.snapshot_count(); ++k)
    metal_err = std::max(metal_err, std::abs(masses(k).second / metal0 - 1));
  // Gas in and out: the last series sample and the last snapshot are both at the end time.
  const auto in = rr.series("open_boundaries/inlet");
  const auto out_ = rr.series("open_boundaries/outlet");
  const auto [total_end, metal_end] = masses(rr.snapshot_count() - 1);
  const double balance = total0 + m_gas * (in.back() - out_.back());
  // The inflow's volume: 3 wide at mean 420 from 0.002, ramped by (1 - cos)/2 over 0.002.
  const double expected_in = 3.0 * 420.0 * (0.008 - 0.002 - 0.001) / (c.dx() * c.dx());
  const auto tmin = rr.series("diagnostics/temperature_min");
  const auto tmax = rr.series("diagnostics/temperature_max");
  const auto melted = rr.series("phase/melted");
  const auto solidified = rr.series("phase/solidified");
  const auto active = rr.series("phase/active_bodies");
  const auto dev = rr.series("diagnostics/max_density_deviation");
  std::printf(
      "powder grains (dx 0.25, t <= 0.008): metal mass error %.1e, total %.6f = %.6f + m_gas "
      "(%g in - %g out) (expected in %.0f), T in [%.4g, %.4g], melted %g, solidified %g, bodies "
      "%g -> %g, max density deviation %.3f, %lld steps, %.1f s wall\n",
      metal_err, total_end, total0, in.back(), out_.back(), expected_in,
      *std::min_element(tmin.begin(), tmin.end()), *std::max_element(tmax.begin(), tmax.end()),
      melted.back(), solidified.back(), active.front(), active.back(),
      *std::max_element(dev.begin(), dev.end()), static_cast<long long>(r.steps), r.wall_seconds);
  EXPECT_LE(metal_err, 1e-12);
  EXPECT_NEAR(total_end, balance, 1e-12 * total0);
  // The gas flows in and out at the prescribed rate (within a row of the 12 lanes).
  EXPECT_NEAR(in.back(), expected_in, 12.0);
  EXPECT_NEAR(out_.back(), in.back(), 12.0);
  // Temperatures within the initial (25, 50) and wall (50, 100) values: maximum principle.
  EXPECT_GE(*std::min_element(tmin.begin(), tmin.end()), 25.0 - 1e-9);
  EXPECT_LE(*std::max_element(tmax.begin(), tmax.end()), 100.0 + 1e-9);
  // Grains touching the hot lower walls melt.
  EXPECT_GT(melted.back(), 20.0);
  EXPECT_GT(metal_end, 0.0);
  EXPECT_EQ(active.front(), 10.0);
}

}  // namespace
}  // namespace sph
