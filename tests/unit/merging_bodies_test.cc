// Bodies that merge on touching (PhaseTransition.merge_bodies): two bodies, one of them
// solidified, drift and turn towards each other with no fluid around them; when a particle of
// one comes within the join radius of the other they become one body with their total mass,
// linear momentum and angular momentum (Fuchs 2021 eq. 29's regrouping). Bodies the case
// placed (none of their particles solidified), bodies of another material and rules without
// merge_bodies keep two bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "case/load.h"
#include "solver/bodies/phase_transitions.h"
#include "solver/core/neighbor_list.h"
#include "solver/parallel/halo.h"
#include "tests/support/body_scene.h"

namespace sph {
namespace {

constexpr double kJoin = 0.15;  // 1.5 dx

template <int D>
v1::Case scene(const std::string& second_material) {
  const std::string lo = D == 2 ? "lo { x: -3 y: -3 }" : "lo { x: -1.5 y: -1.5 z: -1.5 }";
  const std::string hi = D == 2 ? "hi { x: 3 y: 3 }" : "hi { x: 1.5 y: 1.5 z: 1.5 }";
  // Disks of radius 0.4 (2D) or balls of 0.3 (3D), 0.3 and 0.2 apart at their closest.
  const std::string a = D == 2 ? "center { x: -0.55 y: 0.05 } radius: 0.4"
                               : "center { x: -0.45 y: 0.05 z: 0 } radius: 0.3";
  const std::string b = D == 2 ? "center { x: 0.55 y: -0.05 } radius: 0.4"
                               : "center { x: 0.45 y: -0.05 z: 0.02 } radius: 0.3";
  return parse_case_text("dimension: " + std::to_string(D) + " dx: 0.1 domain { " + lo + " " + hi +
                         R"( }
    materials { name: "solid" phase: SOLID density: 1000 }
    materials { name: "liquid" density: 1000 eos { sound_speed: 10 } }
    materials { name: "glass" phase: SOLID density: 2500 }
    time { end_time: 1 fixed_dt: 1e-3 }
    bodies { name: "a" material: "solid" shape { ball { )" +
                         a + R"( } } }
    bodies { name: "b" material: ")" +
                         second_material + R"(" shape { ball { )" + b + " } } }");
}

template <int D>
struct Totals {
  double mass = 0;
  Vec<D> p = Vec<D>::Zero();        // linear momentum
  AngVec<D> l = AngVec<D>::Zero();  // angular momentum about the origin
  int bodies = 0;
};

template <int D>
struct TwoBodies {
  ParticleStore<D> s;
  std::unique_ptr<RigidBodies<D>> bodies;
  Column<double>* T = nullptr;
  Comm comm{MPI_COMM_WORLD};
  CellGrid<D> grid;
  std::unique_ptr<Halo<D>> halo;
  NeighborList<D> nl;
  std::int64_t step = 0;

  explicit TwoBodies(const v1::Case& c) {
    T = &s.template add<double>("temperature", "heat_conduction", true);
    bodies = bodies_of<D>(c, s);
    auto& bs = bodies->bodies();
    // Towards each other, off-centre, turning both ways.
    if constexpr (D == 2) {
      bs[0].velocity = Vec<D>(0.6, 0.1);
      bs[1].velocity = Vec<D>(-0.4, 0.3);
      bs[0].omega[0] = 2.0;
      bs[1].omega[0] = -3.0;
    } else {
      bs[0].velocity = Vec<D>(0.6, 0.1, -0.05);
      bs[1].velocity = Vec<D>(-0.4, 0.3, 0.1);
      bs[0].omega = AngVec<D>(1.0, -0.5, 2.0);
      bs[1].omega = AngVec<D>(-0.3, 2.5, -3.0);
    }
    for (auto& b : bs) b.angular_momentum = b.world_inertia_times(b.omega);
    bodies->update_owned_velocities();
    Vec<D> lo, hi;
    lo.setConstant(D == 2 ? -3.0 : -1.5);
    hi.setConstant(D == 2 ? 3.0 : 1.5);
    std::array<bool, D> periodic{};
    grid = CellGrid<D>(lo, hi, 0.3, periodic);
    halo = std::make_unique<Halo<D>>(grid, comm);
    std::vector<std::int64_t> counts(static_cast<std::size_t>(grid.total()), 1);
    halo->set_decomposition(Decomposition<D>(grid, 1, counts));
    search();
  }
  void search() { nl.build(s, grid, halo->ghost_box(), 0.3, nullptr, true); }
  // Drift by dt (torque-free), place the particles, search: the state at the end of a step.
  void drift(double dt) {
    bodies->drift(dt, 0.0);
    for (auto& b : bodies->bodies()) b.update_omega();
    bodies->place_owned_particles();
    search();
  }
  typename PhaseTransitions<D>::Outcome run(PhaseTransitions<D>& pt) {
    return pt.run(s, nl, *bodies, T, nullptr, nullptr, Vec<D>::Zero(), ++step, comm);
  }
  // Marks the particles of body k solidified (as if they had frozen in an earlier step).
  void solidify(std::int32_t k) {
    auto& changed = s.template get<std::int64_t>("phase_changed_at");
    for (std::size_t i = 0; i < s.owned(); ++i)
      if (bodies->body_index()[i] == k) changed[i] = 1;
  }
  Totals<D> totals() const {
    Totals<D> t;
    for (const auto& b : bodies->bodies()) {
      if (!b.active()) continue;
      ++t.bodies;
      t.mass += b.mass;
      t.p += b.mass * b.velocity;
      t.l += moment<D>(b.com, b.mass * b.velocity) + b.world_inertia_times(b.omega);
    }
    return t;
  }
  double particle_mass() const {
    double m = 0;
    for (std::size_t i = 0; i < s.owned(); ++i) m += s.m[i];
    return m;
  }
  // The smallest distance between rigid particles of different bodies.
  double gap() const {
    double g = std::numeric_limits<double>::infinity();
    const auto& body = bodies->body_index();
    for (std::size_t i = 0; i < s.owned(); ++i)
      for (std::size_t j = i + 1; j < s.owned(); ++j)
        if (s.kind[i] == Kind::kRigid && s.kind[j] == Kind::kRigid && body[i] != body[j])
          g = std::min(g, (s.x[i] - s.x[j]).norm());
    return g;
  }
};

PhaseRule rule(bool merge) {
  PhaseRule r;
  r.solid = 0;  // "solid"
  r.fluid = 1;  // "liquid"
  r.melt_above = 50;
  r.freeze_below = 50;
  r.reversible = true;
  r.join_radius = kJoin;
  r.merge_bodies = merge;
  return r;
}

template <int D>
void merge_and_check_conservation() {
  TwoBodies<D> f(scene<D>("solid"));
  PhaseTransitions<D> pt(f.s, {rule(true)}, 8, 0.1);
  f.solidify(1);  // b froze earlier; a is the case's
  const Totals<D> before = f.totals();
  const double particle_mass = f.particle_mass();
  ASSERT_EQ(before.bodies, 2);
  int merged_at = -1;
  double gap_before = 0;
  for (int n = 0; n < 100 && merged_at < 0; ++n) {
    const double gap = f.gap();
    f.drift(0.005);
    const double now = f.gap();
    const auto out = f.run(pt);
    ASSERT_TRUE(out.error.empty()) << out.error;
    if (f.totals().bodies == 1) {
      merged_at = n;
      gap_before = gap;
      EXPECT_LT(now, kJoin);
      EXPECT_GT(out.touching, 0);
      EXPECT_EQ(out.merged, 1);
      EXPECT_EQ(pt.merged_total(), 1);
    } else {
      EXPECT_GE(now, kJoin) << "step " << n;  // apart: no merge
      EXPECT_EQ(out.touching, 0);
    }
  }
  ASSERT_GE(merged_at, 1) << "the bodies never merged";
  EXPECT_GE(gap_before, kJoin);
  const Totals<D> after = f.totals();
  const double dp = (after.p - before.p).norm() / before.p.norm();
  const double dl = (after.l - before.l).norm() / before.l.norm();
  const double dm = std::abs(after.mass / before.mass - 1);
  std::printf(
      "%dD bodies merging on touching at step %d: body mass %.17g -> %.17g (relative %.1e, the "
      "particles' masses summed in another order), relative change of linear momentum %.2e, "
      "of angular momentum about the origin %.2e\n",
      D, merged_at, before.mass, after.mass, dm, dp, dl);
  EXPECT_EQ(particle_mass, f.particle_mass());  // no particle gains or loses mass
  EXPECT_LT(dm, 1e-15);
  EXPECT_LT(dp, 1e-14);
  EXPECT_LT(dl, 1e-13);
  // Every particle is now in the merged body and sits where it says.
  const auto& bs = f.bodies->bodies();
  std::int64_t particles = 0;
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    if (f.s.kind[i] != Kind::kRigid) continue;
    const RigidBody<D>& b = bs[static_cast<std::size_t>(f.bodies->body_index()[i])];
    EXPECT_TRUE(b.active());
    EXPECT_NEAR((b.com + b.orientation.matrix() * f.bodies->offset()[i] - f.s.x[i]).norm(), 0,
                1e-13);
    ++particles;
  }
  for (const auto& b : bs)
    if (b.active()) {
      EXPECT_EQ(b.particles, particles);
    }
  // It moves on as one body: the next step finds nothing more to merge.
  f.drift(0.005);
  const auto next = f.run(pt);
  EXPECT_EQ(next.touching, 0);
  EXPECT_EQ(next.merged, 0);
}

TEST(MergingBodies, TouchingBodiesMergeKeepingMassAndMomentum2D) {
  merge_and_check_conservation<2>();
}

TEST(MergingBodies, TouchingBodiesMergeKeepingMassAndMomentum3D) {
  merge_and_check_conservation<3>();
}

// Drifts the bodies through each other's join radius and counts the bodies.
int bodies_after_passing(const std::string& second_material, bool merge, bool solidified) {
  TwoBodies<2> f(scene<2>(second_material));
  PhaseTransitions<2> pt(f.s, {rule(merge)}, 8, 0.1);
  if (solidified) f.solidify(1);
  bool touched = false;
  for (int n = 0; n < 100; ++n) {
    f.drift(0.005);
    touched = touched || f.gap() < kJoin;
    const auto out = f.run(pt);
    EXPECT_TRUE(out.error.empty()) << out.error;
  }
  EXPECT_TRUE(touched);
  return f.totals().bodies;
}

TEST(MergingBodies, OnlySolidifiedBodiesOfTheTransitionsSolidMerge) {
  // The case's bodies as placed (none of them froze) keep colliding.
  EXPECT_EQ(bodies_after_passing("solid", true, false), 2);
  // A solidified body next to a body of another material.
  EXPECT_EQ(bodies_after_passing("glass", true, true), 2);
  // merge_bodies off: bodies that come together later stay apart (Fuchs 2021 as written).
  EXPECT_EQ(bodies_after_passing("solid", false, true), 2);
  // The same with merging on: one body.
  EXPECT_EQ(bodies_after_passing("solid", true, true), 1);
}

}  // namespace
}  // namespace sph
