// Reversible phase transitions on the particle level (Fuchs 2021 eq. 29): what a melting or
// solidifying particle does to its body, with no fluid solver around it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "case/load.h"
#include "solver/bodies/phase_transitions.h"
#include "solver/core/neighbor_list.h"
#include "solver/parallel/halo.h"
#include "tests/support/body_scene.h"

namespace sph {
namespace {

// 2D scene: the given bodies (material "solid") and fluid regions (material "liquid").
v1::Case scene(const std::string& parts) {
  return parse_case_text(R"(dimension: 2 dx: 0.1
    domain { lo { x: -3 y: -3 } hi { x: 3 y: 3 } }
    materials { name: "solid" phase: SOLID density: 1000 }
    materials { name: "liquid" density: 1000 eos { sound_speed: 10 } }
    time { end_time: 1 fixed_dt: 1e-3 })" +
                         parts);
}

struct Fixture {
  ParticleStore<2> s;
  std::unique_ptr<RigidBodies<2>> bodies;
  Column<double>* T = nullptr;
  NeighborList<2> nl;
  Comm comm{MPI_COMM_WORLD};

  Fixture(const v1::Case& c, const Vec<2>& u0, double w0) {
    T = &s.add<double>("temperature", "heat_conduction", true);
    AngVec<2> w;
    w[0] = w0;
    bodies = bodies_of<2>(c, s, u0, w);
    // Fluid particles of the scene move with u0 too (what matters is that they carry momentum).
    for (std::size_t i = 0; i < s.owned(); ++i)
      if (s.kind[i] == Kind::kFluid) s.v[i] = Vec<2>(0.3, -0.2);
    const CellGrid<2> grid(Vec<2>(-3, -3), Vec<2>(3, 3), 0.3, {false, false});
    Halo<2> halo(grid, comm);
    std::vector<std::int64_t> counts(static_cast<size_t>(grid.total()), 1);
    halo.set_decomposition(Decomposition<2>(grid, 1, counts));
    nl.build(s, grid, halo.ghost_box(), 0.3, nullptr, true);
  }
  void set_temperature(double t) {
    for (std::size_t i = 0; i < s.owned(); ++i) (*T)[i] = t;
  }
  std::int64_t step = 0;  // each run() is the end of the next step
  PhaseTransitions<2>::Outcome run(PhaseTransitions<2>& pt) {
    return pt.run(s, nl, *bodies, T, nullptr, nullptr, Vec<2>::Zero(), ++step, comm);
  }
  Vec<2> momentum() const {  // bodies plus fluid
    Vec<2> p = Vec<2>::Zero();
    for (const auto& b : bodies->bodies())
      if (b.active()) p += b.mass * b.velocity;
    for (std::size_t i = 0; i < s.owned(); ++i)
      if (s.kind[i] == Kind::kFluid) p += s.m[i] * s.v[i];
    return p;
  }
  double mass() const {
    double m = 0;
    for (std::size_t i = 0; i < s.owned(); ++i) m += s.m[i];
    return m;
  }
};

PhaseRule rule(double t, double hysteresis, bool reversible) {
  PhaseRule r;
  r.solid = 0;
  r.fluid = 1;
  r.melt_above = t + 0.5 * hysteresis;
  r.freeze_below = t - 0.5 * hysteresis;
  r.reversible = reversible;
  r.join_radius = 0.15;
  return r;
}

TEST(PhaseTransition, HalfMeltedBodyMovesAsEq29Says) {
  Fixture f(scene(R"(bodies { name: "b" material: "solid"
                       shape { box { lo { x: -1 y: -0.5 } hi { x: 1 y: 0.5 } } } })"),
            Vec<2>(0.5, 0.1), 2.0);
  const RigidBody<2> before = f.bodies->bodies()[0];
  const Vec<2> p0 = f.momentum();
  const double m0 = f.mass();
  for (std::size_t i = 0; i < f.s.owned(); ++i) (*f.T)[i] = f.s.x[i][0] > 0.3 ? 100 : 0;
  PhaseTransitions<2> pt(f.s, {rule(50, 0, false)}, 8, 0.1);
  const auto out = f.run(pt);
  ASSERT_TRUE(out.error.empty()) << out.error;
  const RigidBody<2>& b = f.bodies->bodies()[0];
  std::int64_t melted = 0;
  for (std::size_t i = 0; i < f.s.owned(); ++i) melted += f.s.kind[i] == Kind::kFluid;
  EXPECT_EQ(out.melted, melted);
  EXPECT_EQ(b.particles + melted, before.particles);
  // Eq. 29: same angular velocity, u = u' + omega x (r - r').
  const Vec<2> expect = before.velocity + cross<2>(before.omega, b.com - before.com);
  EXPECT_EQ(b.omega[0], before.omega[0]);
  EXPECT_NEAR((b.velocity - expect).norm(), 0.0, 1e-14);
  EXPECT_LT(b.com[0], before.com[0] - 0.2);  // the centre moved towards the solid part
  // Melted particles carry the momentum they had: the total is unchanged.
  EXPECT_NEAR((f.momentum() - p0).norm(), 0.0, 1e-12 * p0.norm());
  EXPECT_EQ(f.mass(), m0);
  // The remaining particles sit where the body says (offsets in the body frame).
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    if (f.s.kind[i] != Kind::kRigid) continue;
    EXPECT_NEAR((b.com + b.orientation.matrix() * f.bodies->offset()[i] - f.s.x[i]).norm(), 0,
                1e-13);
  }
}

// Two blocks joined by a bar: melting the bar (|x| < 0.45) breaks the body in two.
const char* const kDumbbell = R"(bodies { name: "dumbbell" material: "solid"
  shape { union {
    shapes { box { lo { x: -1.5 y: -0.5 } hi { x: -0.5 y: 0.5 } } }
    shapes { box { lo { x: 0.5 y: -0.5 } hi { x: 1.5 y: 0.5 } } }
    shapes { box { lo { x: -0.6 y: -0.1 } hi { x: 0.6 y: 0.1 } } } } } })";

TEST(PhaseTransition, BodyMeltedThroughBecomesTwoBodies) {
  // Two blocks joined by a bar; melting the bar leaves two bodies that keep rotating.
  Fixture f(scene(kDumbbell), Vec<2>(0.2, 0), 1.0);
  const RigidBody<2> before = f.bodies->bodies()[0];
  const Vec<2> p0 = f.momentum();
  for (std::size_t i = 0; i < f.s.owned(); ++i) (*f.T)[i] = std::abs(f.s.x[i][0]) < 0.45 ? 100 : 0;
  PhaseTransitions<2> pt(f.s, {rule(50, 0, false)}, 8, 0.1);
  ASSERT_TRUE(f.run(pt).error.empty());
  const auto& bs = f.bodies->bodies();
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_TRUE(bs[0].active() && bs[1].active());
  EXPECT_EQ(bs[0].particles, bs[1].particles);  // symmetric pieces
  EXPECT_NEAR(bs[0].com[0], -bs[1].com[0], 1e-12);
  for (const auto& b : bs) {
    EXPECT_EQ(b.omega[0], before.omega[0]);
    EXPECT_NEAR(
        (b.velocity - (before.velocity + cross<2>(before.omega, b.com - before.com))).norm(), 0.0,
        1e-14);
  }
  EXPECT_NEAR((f.momentum() - p0).norm(), 0.0, 1e-12 * p0.norm());
}

TEST(PhaseTransition, PiecesOfABodyGetTheirOwnForces) {
  // The dumbbell of the test above with a fluid force on every particle (uneven, so that it
  // has a moment) and a contact force on the body. After the bar melts, each piece's fluid
  // force and torque are those of its own particles about its own centre (eqs. 24-26): the
  // next step's first half kick must not push a piece with its parent's whole force. The
  // contact force is evaluated again by the simulation; the mean contact force the fluid's
  // wall condition sees is split by mass.
  Fixture f(scene(kDumbbell), Vec<2>(0.2, 0), 1.0);
  auto& force = f.bodies->fluid_force();
  RigidBody<2>& whole = f.bodies->bodies()[0];
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    force[i] = Vec<2>(1.0 + 0.3 * f.s.x[i][0], -0.5 + 0.2 * f.s.x[i][1] * f.s.x[i][0]);
    whole.fluid_force += force[i];
    whole.fluid_torque += moment<2>(f.s.x[i] - whole.com, force[i]);
  }
  whole.contact_force = Vec<2>(3, 4);
  whole.contacts = 7;
  whole.mean_contact_force = Vec<2>(0, 10);
  const RigidBody<2> before = whole;  // `whole` is slot 0, which the first piece takes
  for (std::size_t i = 0; i < f.s.owned(); ++i) (*f.T)[i] = std::abs(f.s.x[i][0]) < 0.45 ? 100 : 0;
  PhaseTransitions<2> pt(f.s, {rule(50, 0, false)}, 8, 0.1);
  ASSERT_TRUE(f.run(pt).error.empty());
  const auto& bs = f.bodies->bodies();
  ASSERT_EQ(bs.size(), 2u);
  for (std::size_t k = 0; k < bs.size(); ++k) {
    Vec<2> F = Vec<2>::Zero();
    AngVec<2> T = AngVec<2>::Zero();
    for (std::size_t i = 0; i < f.s.owned(); ++i)
      if (f.s.kind[i] == Kind::kRigid && f.bodies->body_index()[i] == static_cast<int>(k)) {
        F += force[i];
        T += moment<2>(f.s.x[i] - bs[k].com, force[i]);
      }
    EXPECT_NEAR((bs[k].fluid_force - F).norm(), 0.0, 1e-12 * F.norm()) << "body " << k;
    EXPECT_NEAR(bs[k].fluid_torque[0], T[0], 1e-12 * std::abs(T[0])) << "body " << k;
    EXPECT_LT(bs[k].fluid_force.norm(), 0.7 * before.fluid_force.norm()) << "body " << k;
    EXPECT_EQ(bs[k].contact_force.norm(), 0.0);
    EXPECT_EQ(bs[k].contacts, 0);
    EXPECT_NEAR(bs[k].mean_contact_force[1], 10 * bs[k].mass / before.mass, 1e-12);
  }
}

TEST(PhaseTransition, PrescribedRotatingBodyStaysOnItsPath) {
  // A body turning about the origin while it translates; half of it melts at t = 0.4 (turned
  // by 0.8 rad). The piece left must go on where the path takes its particles: com0 moves by
  // the centre's shift taken back into the path's frame at t = 0.
  Fixture f(scene(R"(bodies { name: "arm" material: "solid" motion_type: PRESCRIBED
                       motion { velocity_x { constant: 0.5 } angular_velocity { constant: 2 } }
                       shape { box { lo { x: 0.3 y: -0.3 } hi { x: 1.9 y: 0.3 } } } })"),
            Vec<2>(0, 0), 0.0);
  std::map<ParticleId, Vec<2>> x0;
  for (std::size_t i = 0; i < f.s.owned(); ++i) x0[f.s.id[i]] = f.s.x[i];
  const auto& path = f.bodies->bodies()[0].path;
  auto on_path = [&](const Vec<2>& x, double t) {
    const Point3 p = path.position(Point3(x[0], x[1], 0), t);
    return Vec<2>(p[0], p[1]);
  };
  f.bodies->drift(0.4, 0.4);
  f.bodies->place_owned_particles();
  for (std::size_t i = 0; i < f.s.owned(); ++i)
    ASSERT_NEAR((f.s.x[i] - on_path(x0[f.s.id[i]], 0.4)).norm(), 0.0, 1e-12);
  for (std::size_t i = 0; i < f.s.owned(); ++i) (*f.T)[i] = x0[f.s.id[i]][0] > 1.1 ? 100 : 0;
  PhaseTransitions<2> pt(f.s, {rule(50, 0, false)}, 8, 0.1);
  ASSERT_TRUE(f.run(pt).error.empty());
  const RigidBody<2>& b = f.bodies->bodies()[0];
  ASSERT_TRUE(b.active());
  EXPECT_NEAR((on_path(b.com0, 0.4) - b.com).norm(), 0.0, 1e-12);
  f.bodies->drift(0.3, 0.7);
  f.bodies->place_owned_particles();
  double worst = 0;
  for (std::size_t i = 0; i < f.s.owned(); ++i)
    if (f.s.kind[i] == Kind::kRigid)
      worst = std::max(worst, (f.s.x[i] - on_path(x0[f.s.id[i]], 0.7)).norm());
  EXPECT_LT(worst, 1e-12);
}

TEST(PhaseTransition, LiquidFreezesOntoABodyOrIntoANewOne) {
  // A body, liquid around it, and a liquid drop far away; all liquid cools below T_t.
  Fixture f(scene(R"(bodies { name: "b" material: "solid"
                       shape { box { lo { x: -0.5 y: -0.5 } hi { x: 0.5 y: 0.5 } } } }
                     fluids { name: "film" material: "liquid"
                       shape { box { lo { x: 0.5 y: -0.5 } hi { x: 0.7 y: 0.5 } } } }
                     fluids { name: "drop" material: "liquid"
                       shape { ball { center { x: -2 y: 2 } radius: 0.3 } } })"),
            Vec<2>(0, 0), 0.0);
  const Vec<2> p0 = f.momentum();
  const double m0 = f.mass();
  const std::int64_t n_body = f.bodies->bodies()[0].particles;
  std::int64_t n_film = 0, n_drop = 0;
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    (*f.T)[i] = 0;
    if (f.s.kind[i] == Kind::kFluid) (f.s.x[i][1] > 1 ? n_drop : n_film) += 1;
  }
  PhaseTransitions<2> pt(f.s, {rule(50, 0, true)}, 8, 0.1);
  const auto out = f.run(pt);
  ASSERT_TRUE(out.error.empty()) << out.error;
  EXPECT_EQ(out.solidified, n_film + n_drop);
  const auto& bs = f.bodies->bodies();
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_EQ(bs[0].particles, n_body + n_film);  // the film joined the body
  EXPECT_EQ(bs[1].particles, n_drop);           // the drop is a body of its own
  EXPECT_NEAR(bs[1].com[0], -2, 1e-12);
  // The liquid's momentum went into the bodies.
  EXPECT_NEAR((f.momentum() - p0).norm(), 0.0, 1e-12 * p0.norm());
  EXPECT_GT(bs[1].velocity.norm(), 0.0);
  EXPECT_EQ(f.mass(), m0);
}

TEST(PhaseTransition, LiquidFreezingBetweenTwoBodiesMergesThemWithTheirMomentum) {
  // Two blocks moving and spinning differently with a liquid film between them. The film
  // freezes onto both at once (it lies within the join radius of each), so the two bodies
  // and the film become one body: its mass is theirs, and it takes the total linear momentum
  // and the total angular momentum about its new centre (eq. 29 for a merge).
  Fixture f(scene(R"(bodies { name: "left" material: "solid"
                       shape { box { lo { x: -1.1 y: -0.5 } hi { x: -0.1 y: 0.5 } } } }
                     bodies { name: "right" material: "solid"
                       shape { box { lo { x: 0.1 y: -0.3 } hi { x: 0.7 y: 0.3 } } } }
                     fluids { name: "film" material: "liquid"
                       shape { box { lo { x: -0.1 y: -0.3 } hi { x: 0.1 y: 0.3 } } } })"),
            Vec<2>(0, 0), 0.0);
  auto& bs = f.bodies->bodies();
  ASSERT_EQ(bs.size(), 2u);
  bs[0].velocity = Vec<2>(0.4, 0.1);
  bs[0].omega[0] = 0.5;
  bs[1].velocity = Vec<2>(-0.2, 0.3);
  bs[1].omega[0] = -1.5;
  f.bodies->update_owned_velocities();
  // Linear and angular momentum (about the origin, z) of bodies and fluid.
  auto angular = [&] {
    double L = 0;
    for (const auto& b : f.bodies->bodies())
      if (b.active())
        L += b.inertia_body(0, 0) * b.omega[0] +
             b.mass * (b.com[0] * b.velocity[1] - b.com[1] * b.velocity[0]);
    for (std::size_t i = 0; i < f.s.owned(); ++i)
      if (f.s.kind[i] == Kind::kFluid)
        L += f.s.m[i] * (f.s.x[i][0] * f.s.v[i][1] - f.s.x[i][1] * f.s.v[i][0]);
    return L;
  };
  const Vec<2> p0 = f.momentum();
  const double L0 = angular(), m0 = f.mass();
  const double mass_bodies = bs[0].mass + bs[1].mass;
  const std::int64_t n_bodies = bs[0].particles + bs[1].particles;
  std::int64_t n_film = 0;
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    (*f.T)[i] = 0;
    n_film += f.s.kind[i] == Kind::kFluid;
  }
  ASSERT_GT(n_film, 0);
  PhaseTransitions<2> pt(f.s, {rule(50, 0, true)}, 8, 0.1);
  const auto out = f.run(pt);
  ASSERT_TRUE(out.error.empty()) << out.error;
  EXPECT_EQ(out.solidified, n_film);
  std::int64_t active = 0;
  const RigidBody<2>* merged = nullptr;
  for (const auto& b : f.bodies->bodies())
    if (b.active()) {
      ++active;
      merged = &b;
    }
  ASSERT_EQ(active, 1);
  EXPECT_EQ(merged->particles, n_bodies + n_film);
  const auto k = static_cast<std::int32_t>(merged - f.bodies->bodies().data());
  for (std::size_t i = 0; i < f.s.owned(); ++i) {
    EXPECT_EQ(f.s.kind[i], Kind::kRigid) << "particle " << i;
    EXPECT_EQ(f.bodies->body_index()[i], k) << "particle " << i;
  }
  EXPECT_GT(merged->mass, mass_bodies);  // the film's mass joined
  EXPECT_EQ(f.mass(), m0);
  EXPECT_NEAR((f.momentum() - p0).norm(), 0.0, 1e-12 * p0.norm());
  EXPECT_NEAR(angular(), L0, 1e-12 * std::abs(L0));
  // The merged body moves rigidly: every particle where the body puts it.
  for (std::size_t i = 0; i < f.s.owned(); ++i)
    EXPECT_NEAR(
        (merged->com + merged->orientation.matrix() * f.bodies->offset()[i] - f.s.x[i]).norm(), 0,
        1e-13);
}

// One square body at rest, every particle at the same temperature.
v1::Case square_body() {
  return scene(R"(bodies { name: "b" material: "solid"
                    shape { box { lo { x: -0.5 y: -0.5 } hi { x: 0.5 y: 0.5 } } } })");
}

TEST(PhaseTransition, HysteresisBandStopsFlicker) {
  Fixture f(square_body(), Vec<2>(0, 0), 0.0);
  PhaseTransitions<2> pt(f.s, {rule(50, 10, true)}, 8, 0.1);  // melts above 55, freezes below 45
  f.set_temperature(54);                                      // inside the band: stays solid
  EXPECT_EQ(f.run(pt).melted, 0);
  f.set_temperature(56);
  const auto melted = f.run(pt).melted;
  EXPECT_EQ(melted, f.s.owned());
  EXPECT_FALSE(f.bodies->bodies()[0].active());
  for (double t : {54.0, 50.0, 46.0}) {  // cooling inside the band: stays liquid
    f.set_temperature(t);
    EXPECT_EQ(f.run(pt).solidified, 0) << "at T = " << t;
  }
  f.set_temperature(44);
  EXPECT_EQ(f.run(pt).solidified, melted);
  EXPECT_EQ(pt.melted_total(), melted);
  EXPECT_EQ(pt.solidified_total(), melted);
}

// Flicker shows as reversals a few steps apart: each particle's last transition is kept, and
// the unit counts the transitions of particles that had changed phase before and the fewest
// steps between two of them.
TEST(PhaseTransition, ReversalsAreCountedWithTheFewestStepsBetweenThem) {
  Fixture f(square_body(), Vec<2>(0, 0), 0.0);
  PhaseTransitions<2> pt(f.s, {rule(50, 10, true)}, 8, 0.1);  // melts above 55, freezes below 45
  auto step_at = [&](double t) {
    f.set_temperature(t);
    return f.run(pt);
  };
  const auto n = static_cast<std::int64_t>(f.s.owned());
  EXPECT_EQ(step_at(56).melted, n);  // step 1: a first transition is no reversal
  EXPECT_EQ(pt.reversals_total(), 0);
  EXPECT_EQ(pt.shortest_reversal(), 0);
  step_at(50);
  step_at(50);
  EXPECT_EQ(step_at(44).solidified, n);  // step 4
  EXPECT_EQ(pt.reversals_total(), n);
  EXPECT_EQ(pt.shortest_reversal(), 3);
  EXPECT_EQ(step_at(56).melted, n);  // step 5: back after one step
  EXPECT_EQ(pt.reversals_total(), 2 * n);
  EXPECT_EQ(pt.shortest_reversal(), 1);
  step_at(50);  // no transition: the record stays
  EXPECT_EQ(pt.reversals_total(), 2 * n);
  const auto& changed = f.s.get<std::int64_t>("phase_changed_at");
  for (std::size_t i = 0; i < f.s.owned(); ++i) EXPECT_EQ(changed[i], 6) << "particle " << i;
  // A checkpoint carries the totals.
  CheckpointState state;
  pt.save(state);
  PhaseTransitions<2> resumed(f.s, {rule(50, 10, true)}, 8, 0.1);
  resumed.load(state);
  EXPECT_EQ(resumed.reversals_total(), 2 * n);
  EXPECT_EQ(resumed.shortest_reversal(), 1);
}

TEST(PhaseTransition, BodyTableCapacityIsEnforced) {
  Fixture f(scene(R"(fluids { name: "a" material: "liquid"
                       shape { ball { center { x: -2 y: 0 } radius: 0.3 } } }
                     fluids { name: "b" material: "liquid"
                       shape { ball { center { x: 2 y: 0 } radius: 0.3 } } })"),
            Vec<2>(0, 0), 0.0);
  f.set_temperature(0);
  PhaseTransitions<2> pt(f.s, {rule(50, 0, true)}, 1, 0.1);
  const auto out = f.run(pt);
  EXPECT_NE(out.error.find("max_bodies"), std::string::npos) << out.error;
}

// Melting and freezing again and again needs slots for the bodies that exist at once: a slot
// that melting emptied goes to the next body made, under a new serial number and name, and a
// checkpoint keeps both.
TEST(PhaseTransition, AnEmptiedSlotGoesToTheNextBodyMade) {
  const v1::Case c = scene(R"(fluids { name: "a" material: "liquid"
                                shape { ball { center { x: -2 y: 0 } radius: 0.3 } } }
                              fluids { name: "b" material: "liquid"
                                shape { ball { center { x: 2 y: 0 } radius: 0.3 } } })");
  Fixture f(c, Vec<2>(0, 0), 0.0);
  PhaseTransitions<2> pt(f.s, {rule(50, 0, true)}, 2, 0.1);  // room for two bodies
  auto set = [&](double left, double right) {
    for (std::size_t i = 0; i < f.s.owned(); ++i) (*f.T)[i] = f.s.x[i][0] < 0 ? left : right;
  };
  auto& bs = f.bodies->bodies();
  set(0, 0);  // both blobs freeze: two bodies
  ASSERT_TRUE(f.run(pt).error.empty());
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_EQ(bs[0].serial, 0);
  EXPECT_EQ(bs[1].serial, 1);
  set(100, 0);  // the left one melts: slot 0 is empty
  ASSERT_TRUE(f.run(pt).error.empty());
  EXPECT_FALSE(bs[0].active());
  set(0, 0);  // and freezes again: a third body, in slot 0
  const auto out = f.run(pt);
  ASSERT_TRUE(out.error.empty()) << out.error;
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_TRUE(bs[0].active());
  EXPECT_EQ(bs[0].serial, 2);
  EXPECT_EQ(bs[0].name, "body_2");
  EXPECT_EQ(bs[1].serial, 1);
  for (std::size_t i = 0; i < f.s.owned(); ++i)
    EXPECT_EQ(f.bodies->body_index()[i], f.s.x[i][0] < 0 ? 0 : 1);

  std::map<std::string, double> st;
  f.bodies->save(st);
  Fixture g(c, Vec<2>(0, 0), 0.0);
  g.bodies->load(st);
  ASSERT_EQ(g.bodies->bodies().size(), 2u);
  EXPECT_EQ(g.bodies->bodies()[0].serial, 2);
  EXPECT_EQ(g.bodies->bodies()[0].name, "body_2");
  EXPECT_EQ(g.bodies->bodies()[1].name, "body_1");
  EXPECT_EQ(g.bodies->next_serial(), 3);
}

}  // namespace
}  // namespace sph
