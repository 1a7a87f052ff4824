// Rebuilding a body that lost particles at an outlet (BodyRegrouping::whole_bodies), with no
// fluid solver around it: what remains keeps the rigid motion its particles had, and a body
// is not split however little of it is connected.
#include <gtest/gtest.h>

#include <map>

#include "case/load.h"
#include "solver/bodies/body_regrouping.h"
#include "tests/support/body_scene.h"

namespace sph {
namespace {

// One body of two separate blocks (a union of shapes that do not touch), spinning.
v1::Case two_blocks() {
  return parse_case_text(R"(dimension: 2 dx: 0.1
    domain { lo { x: -3 y: -3 } hi { x: 3 y: 3 } }
    materials { name: "solid" phase: SOLID density: 1000 }
    time { end_time: 1 fixed_dt: 1e-3 }
    bodies { name: "pair" material: "solid"
      shape { union {
        shapes { box { lo { x: -1.5 y: -0.5 } hi { x: -0.5 y: 0.5 } } }
        shapes { box { lo { x: 0.5 y: -0.5 } hi { x: 1.5 y: 0.5 } } } } } })");
}

struct Motion {
  Vec<2> x, v, a;
};

// Places the body's particles with a given acceleration, deletes those right of x_cut (as an
// outlet would) and regroups with `regrouping`; returns the motion of the remaining particles
// before, by id.
std::map<ParticleId, Motion> cut(ParticleStore<2>& s, RigidBodies<2>& bodies, double x_cut,
                                 const BodyRegrouping<2>& regrouping) {
  RigidBody<2>& b = bodies.bodies()[0];
  b.acceleration = Vec<2>(1.0, -2.0);
  b.angular_acceleration[0] = 0.7;
  bodies.place_owned_particles();
  std::map<ParticleId, Motion> before;
  std::vector<std::uint32_t> keep;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.x[i][0] > x_cut) continue;
    keep.push_back(static_cast<std::uint32_t>(i));
    before[s.id[i]] = {s.x[i], s.v[i], bodies.particle_acceleration()[i]};
  }
  s.reorder_owned(keep);
  const std::string error = regrouping.run(s, bodies, {1}, Comm(MPI_COMM_WORLD));
  EXPECT_EQ(error, "");
  return before;
}

TEST(BodyRegrouping, ABodyCutAtAnOutletKeepsItsRigidMotionAndStaysOne) {
  const v1::Case c = two_blocks();
  ParticleStore<2> s;
  AngVec<2> w;
  w[0] = 2.0;
  auto bodies = bodies_of<2>(c, s, Vec<2>(0.5, 0.1), w);
  const RigidBody<2> old = bodies->bodies()[0];
  // Half of the right block leaves: what remains is two pieces, 1.05 apart.
  const auto before = cut(s, *bodies, 1.0, BodyRegrouping<2>::whole_bodies(0.1));
  ASSERT_EQ(bodies->bodies().size(), 1u);
  const RigidBody<2>& b = bodies->bodies()[0];
  EXPECT_EQ(b.particles, static_cast<std::int64_t>(s.owned()));
  EXPECT_LT(b.particles, old.particles);
  EXPECT_EQ(b.serial, old.serial);
  EXPECT_LT(b.com[0], old.com[0] - 0.1);
  EXPECT_EQ(b.omega[0], old.omega[0]);
  EXPECT_EQ(b.angular_acceleration[0], 0.7);
  // Every remaining particle moves and accelerates as before (rigid motion about the new
  // centre, centripetal term included: the wall condition reads these accelerations in the
  // step of the cut), and sits where the body frame says.
  double dv = 0, da = 0, dx = 0;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const Motion& m = before.at(s.id[i]);
    EXPECT_EQ(bodies->body_index()[i], 0);
    dv = std::max(dv, (s.v[i] - m.v).norm());
    da = std::max(da, (bodies->particle_acceleration()[i] - m.a).norm());
    dx = std::max(dx, (b.com + b.orientation.matrix() * bodies->offset()[i] - m.x).norm());
  }
  std::printf(
      "cut body: largest change of a particle's velocity %.2e, acceleration %.2e, "
      "position %.2e\n",
      dv, da, dx);
  EXPECT_LT(dv, 1e-12);
  EXPECT_LT(da, 1e-12);
  EXPECT_LT(dx, 1e-12);
}

TEST(BodyRegrouping, MeltingRulesWouldSplitTheSameCutBody) {
  // The contrast: eq. 29's connected pieces make two bodies of the same remainder.
  const v1::Case c = two_blocks();
  ParticleStore<2> s;
  auto bodies = bodies_of<2>(c, s);
  cut(s, *bodies, 1.0, BodyRegrouping<2>(0.15, 8, 0.1, "max_bodies"));
  int active = 0;
  for (const auto& b : bodies->bodies()) active += b.active();
  EXPECT_EQ(active, 2);
}

}  // namespace
}  // namespace sph
