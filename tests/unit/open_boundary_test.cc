// Open-boundary building blocks: the buffer zone's lanes, profile and ramp
// (solver/boundaries/open_boundary_zone.h) and the particle ledger's ids
// (solver/boundaries/particle_ledger.h).
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "solver/boundaries/open_boundaries.h"
#include "solver/boundaries/open_boundary_zone.h"
#include "solver/boundaries/particle_ledger.h"
#include "solver/core/kernel.h"
#include "tests/support/body_scene.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

TEST(OpenBoundaryZone, ParabolicInflowCarriesExactlyTheMeanFlux) {
  const auto c = test::load_case("channel_inflow_outflow_2d");  // H = 1, dx = 0.05, U = 1
  const OpenBoundaryZone<2> in(c, 0, 0, 1.0);
  ASSERT_EQ(in.lane_count(), 20u);
  EXPECT_TRUE(in.inflow());
  EXPECT_TRUE(in.prescribed());
  EXPECT_DOUBLE_EQ(in.length(), 0.2);
  EXPECT_DOUBLE_EQ(in.inner_xi(), 0.0);   // enters the fluid at x = 0
  EXPECT_DOUBLE_EQ(in.outer_xi(), -0.2);  // refills at x = -0.2
  // Discrete flux sum_lanes u dx equals U H (the plain midpoint sum would be 0.125% high).
  double flux = 0, umax = 0;
  for (std::size_t l = 0; l < in.lane_count(); ++l) {
    flux += in.speed(l, 100.0) * c.dx();
    umax = std::max(umax, in.speed(l, 100.0));
  }
  EXPECT_NEAR(flux, 1.0, 1e-12);
  EXPECT_NEAR(umax, 1.5 * 0.9975 / (1 + 1.0 / 800), 1e-3);  // parabola at the middle lanes
  // Lanes are the lattice rows; the sample points lie r_c = 0.15 inside the fluid.
  Vec<2> x(-0.1, 0.025);
  EXPECT_EQ(in.lane_of(x), 0u);
  x[1] = 0.975;
  EXPECT_EQ(in.lane_of(x), 19u);
  x[1] = 5.0;  // clamped
  EXPECT_EQ(in.lane_of(x), 19u);
  EXPECT_NEAR(in.sample_point(3)[0], 0.15, 1e-12);
  EXPECT_NEAR(in.sample_point(3)[1], 0.175, 1e-12);
  // Smooth ramp over 2 from t = 0.
  EXPECT_EQ(in.ramp(0.0), 0.0);
  EXPECT_NEAR(in.ramp(1.0), 0.5, 1e-15);
  EXPECT_EQ(in.ramp(2.5), 1.0);

  const OpenBoundaryZone<2> out(c, 1, 0, 1.0);
  EXPECT_FALSE(out.inflow());
  EXPECT_FALSE(out.prescribed());  // a pressure outlet
  EXPECT_DOUBLE_EQ(out.inner_xi(), 2.0);
  EXPECT_DOUBLE_EQ(out.outer_xi(), 2.2);
  EXPECT_NEAR(out.sample_point(0)[0], 1.85, 1e-12);
}

TEST(OpenBoundaryZone, SamplePointsLieOneKernelSupportInsideTheFluid) {
  // r_c = 3 h with h = smoothing_length_ratio dx: the sample's support reaches the face but
  // not the buffer (at 3 dx with h = 1.3 dx it would reach 0.9 dx into the buffer).
  auto c = test::load_case("channel_inflow_outflow_2d");  // dx = 0.05, quintic spline
  c.set_smoothing_length_ratio(1.3);
  const OpenBoundaryZone<2> in(c, 0, 0, 1.0);
  EXPECT_NEAR(in.sample_point(3)[0], 3 * 1.3 * 0.05, 1e-12);
  const OpenBoundaryZone<2> out(c, 1, 0, 1.0);
  EXPECT_NEAR(out.sample_point(0)[0], 2.0 - 3 * 1.3 * 0.05, 1e-12);
}

TEST(OpenBoundaries, BufferParticlesMoveWithTheirPrescribedVelocityAsTransportVelocity) {
  // An inflow buffer particle during the ramp, and a fluid particle crossing the inflow's
  // inner face (it becomes fluid and a copy refills its lane upstream). After the exchange at
  // the new time every buffer particle's transport velocity is its new prescribed velocity,
  // so the transport-velocity stress rho u (u~ - u) of the buffers is zero.
  auto c = test::load_case("channel_inflow_outflow_2d");  // inflow at x in [-0.2, 0], along +x
  c.mutable_open_boundaries(0)->set_start_time(0.0);
  const Comm comm(MPI_COMM_SELF);
  ParticleStore<2> s;
  auto& transport = s.add<Vec<2>>("transport_velocity", "test", true);
  std::vector<OpenBoundaryZone<2>> zones;
  zones.emplace_back(c, 0, 0, 1.0);
  const QuinticSpline<2> kernel(c.dx());
  const std::vector<FluidConstants> fluids(1);
  OpenBoundaries<2, QuinticSpline<2>> open(s, kernel, std::move(zones), fluids, 0.0025);
  s.resize(2, 2);
  for (std::size_t i = 0; i < 2; ++i) {
    s.kind[i] = Kind::kFluid;
    s.id[i] = static_cast<ParticleId>(i);
    open.zone()[i] = 1;
    s.v[i] = transport[i] = Vec<2>(0.3, 0.0);  // the prescribed velocity of an earlier time
  }
  s.x[0] = Vec<2>(-0.1, 0.525);  // stays in the buffer
  s.x[1] = Vec<2>(0.01, 0.475);  // has crossed x = 0 into the fluid
  open.ledger().set_next_id(2);
  const double t = 0.5;  // inside the ramp (over 2 from t = 0)
  EXPECT_EQ(open.exchange_particles(t, &transport, comm), 1);
  ASSERT_EQ(s.owned(), 3u);
  EXPECT_EQ(open.zone()[1], 0);  // the crossing particle is fluid now
  for (const std::size_t i : {std::size_t{0}, std::size_t{2}}) {
    const auto& zone = open.zones()[0];
    const Vec<2> u = zone.speed(zone.lane_of(s.x[i]), t) * zone.normal();
    EXPECT_GT(u[0], 0.0);
    EXPECT_NE(u[0], 0.3);
    EXPECT_EQ(s.v[i], u) << "particle " << i;
    EXPECT_EQ(transport[i], u) << "particle " << i << ": stale transport velocity";
  }
  EXPECT_NEAR(s.x[2][0], 0.01 - 0.2, 1e-15);  // the copy refills the lane upstream
}

TEST(OpenBoundaries, AFreeBodyLeavesOnlyThroughTheOutletsBuffer) {
  // Rigid particles of free bodies follow the fluid's rule at an outflow: taken in at the
  // inner face (x = 2), deleted at the far face (x = 2.2). Body "through" straddles the inner
  // face and moves on by 0.1; body "beyond" lies past the far face (the domain goes on there)
  // and never came through the buffer: it is not the outflow's.
  auto c = test::load_case("channel_body_outflow_2d");
  c.mutable_domain()->mutable_hi()->set_x(3.0);
  v1::Case scene = c;  // only the bodies' particles
  scene.clear_fluids();
  scene.clear_walls();
  scene.clear_open_boundaries();
  scene.clear_bodies();
  for (const auto& [name, lo, hi] : {std::tuple{"through", 1.9, 2.15}, {"beyond", 2.5, 2.7}}) {
    auto* b = scene.add_bodies();
    b->set_name(name);
    b->set_material("solid");
    auto* box = b->mutable_shape()->mutable_box();
    box->mutable_lo()->set_x(lo);
    box->mutable_lo()->set_y(0.4);
    box->mutable_hi()->set_x(hi);
    box->mutable_hi()->set_y(0.6);
  }
  ParticleStore<2> s;
  auto bodies = bodies_of<2>(scene, s);
  std::vector<OpenBoundaryZone<2>> zones;
  zones.emplace_back(c, 1, 0, 1.0);  // the pressure outlet
  const QuinticSpline<2> kernel(c.dx());
  const std::vector<FluidConstants> fluids(1);
  OpenBoundaries<2, QuinticSpline<2>> open(s, kernel, std::move(zones), fluids, 0.0025);
  open.zone().resize(s.owned());
  open.ledger().set_next_id(static_cast<ParticleId>(s.owned()));
  const Comm comm(MPI_COMM_SELF);
  auto count = [&](std::int32_t k) {
    std::int64_t n = 0;
    for (std::size_t i = 0; i < s.owned(); ++i) n += bodies->body_index()[i] == k;
    return n;
  };
  const auto n_through = count(0), n_beyond = count(1);
  std::vector<std::int64_t> lost(2, 0);
  EXPECT_EQ(open.exchange_particles(0.0, nullptr, comm, bodies.get(), &lost), 0);
  EXPECT_EQ(lost, (std::vector<std::int64_t>{0, 0}));
  for (std::size_t i = 0; i < s.owned(); ++i) s.x[i][0] += 0.1;
  lost.assign(2, 0);
  // x in (2.1, 2.15] before: in the buffer, now past x = 2.2 (one column of dx = 0.05).
  const std::int64_t gone = open.exchange_particles(0.0, nullptr, comm, bodies.get(), &lost);
  EXPECT_EQ(lost[0], n_through / 5);
  EXPECT_EQ(lost[1], 0);
  EXPECT_EQ(gone, -lost[0]);
  EXPECT_EQ(count(1), n_beyond);
  EXPECT_EQ(open.through()[0], lost[0]);
}

TEST(OpenBoundaryZone, LanesInsideWallsCarryNoFlux) {
  // An inflow whose region reaches into the bottom wall: the covered lanes get no
  // particles, and the others carry the whole flux U * (open lanes) * dx.
  auto c = test::load_case("channel_inflow_outflow_2d");
  auto* o = c.mutable_open_boundaries(0);
  o->mutable_region()->mutable_lo()->set_y(-0.15);
  o->set_profile(v1::UNIFORM);
  o->set_start_time(1.0);
  const OpenBoundaryZone<2> in(c, 0, 0, 1.0);
  ASSERT_EQ(in.lane_count(), 23u);
  double flux = 0;
  for (std::size_t l = 0; l < in.lane_count(); ++l) {
    if (l < 3) {
      EXPECT_EQ(in.speed(l, 10.0), 0.0) << "lane " << l << " lies in the bottom wall";
    }
    flux += in.speed(l, 10.0) * c.dx();
  }
  EXPECT_NEAR(flux, 1.0, 1e-12);
  EXPECT_EQ(in.speed(10, 0.5), 0.0);  // before start_time
}

TEST(ParticleLedger, CopiesGetIdsInTheOrderOfTheirParentsIds) {
  const Comm comm(MPI_COMM_SELF);
  ParticleStore<2> s;
  auto& extra = s.add<double>("extra", "test", true);
  s.resize(5, 5);
  const ParticleId ids[5] = {40, 10, 30, 20, 0};
  for (std::size_t i = 0; i < 5; ++i) {
    s.id[i] = ids[i];
    s.x[i] = Vec<2>(static_cast<double>(i), 0.0);
    extra[i] = 100.0 + static_cast<double>(i);
  }
  ParticleLedger<2> ledger;
  ledger.set_next_id(50);
  std::vector<std::int64_t> tallies = {1, 2};
  // Copy rows 0 (id 40) and 3 (id 20), delete row 1 (id 10).
  const auto t = ledger.apply(s, {0, 3}, {1}, tallies, comm);
  EXPECT_EQ(t.created, 2);
  EXPECT_EQ(t.deleted, 1);
  EXPECT_EQ(tallies, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(ledger.next_id(), 52);
  ASSERT_EQ(s.owned(), 6u);
  ASSERT_EQ(t.first_new, 4u);
  // Survivors in order, then the copies with every column of their parent.
  EXPECT_EQ(s.id[0], 40);
  EXPECT_EQ(s.id[1], 30);
  EXPECT_EQ(s.id[3], 0);
  EXPECT_EQ(s.id[4], 51);  // copy of id 40: the second parent by id
  EXPECT_EQ(s.id[5], 50);  // copy of id 20: the first
  EXPECT_EQ(s.x[4][0], 0.0);
  EXPECT_EQ(extra[5], 103.0);
  // The counter survives a checkpoint.
  std::map<std::string, double> state;
  ledger.save(state, "next");
  ParticleLedger<2> again;
  again.load(state, "next");
  EXPECT_EQ(again.next_id(), 52);
}

}  // namespace
}  // namespace sph
