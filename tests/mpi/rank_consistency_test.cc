// One code path for any rank count: the same case run on 1, 2 and 4 ranks (sub-communicators
// of one mpirun -np 4) must give the same particle fields, and runs at a fixed rank count must
// be bitwise repeatable. Neighbour sums are evaluated in a canonical order (see
// solver/core/neighbor_list.h) and reductions are exact, so we require agreement to the last
// bit.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <map>
#include <thread>

#include "case/validate.h"
#include "tests/support/backflow_channel.h"
#include "tests/support/growing_floor.h"
#include "tests/support/plastic_bar.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Waits for every rank of MPI_COMM_WORLD, sleeping rather than polling: the ranks left out of
// a 1- or 2-rank run would otherwise spin in MPI_Barrier on the cores the run needs (the
// suite runs 4 ranks on 2 cores).
void wait_for_all_ranks() {
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  int done = 0;
  for (MPI_Test(&req, &done, MPI_STATUS_IGNORE); !done; MPI_Test(&req, &done, MPI_STATUS_IGNORE))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// Runs `c` on the first `ranks` ranks of MPI_COMM_WORLD (the others wait).
RunOutcome run_on(const v1::Case& c, int ranks, const std::string& out) {
  MPI_Comm sub;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &sub);
  RunOutcome r;
  if (sub != MPI_COMM_NULL) {
    r = test::run(c, out, sub);
    MPI_Comm_free(&sub);
  }
  wait_for_all_ranks();
  int status = static_cast<int>(r.status);
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  r.status = static_cast<RunStatus>(status);
  return r;
}

struct Fields {
  std::map<std::int64_t, std::array<double, 8>> by_id;  // x, y, z, u, v, w, rho, p
};

Fields read_last(const std::string& path) {
  const test::Snapshot s = test::ResultReader(path).last();
  Fields f;
  for (std::size_t i = 0; i < s.size(); ++i)
    f.by_id[s.id[i]] = {s.position[3 * i], s.position[3 * i + 1], s.position[3 * i + 2],
                        s.velocity[3 * i], s.velocity[3 * i + 1], s.velocity[3 * i + 2],
                        s.density[i],      s.pressure[i]};
  return f;
}

// Largest difference relative to the field's scale (positions: domain size, others: max |value|).
double max_relative_difference(const Fields& a, const Fields& b) {
  EXPECT_EQ(a.by_id.size(), b.by_id.size());
  std::array<double, 8> scale{}, diff{};
  for (const auto& [id, va] : a.by_id) {
    auto it = b.by_id.find(id);
    if (it == b.by_id.end()) {
      ADD_FAILURE() << "particle " << id << " missing";
      return 1e300;
    }
    for (int k = 0; k < 8; ++k) {
      scale[static_cast<size_t>(k)] =
          std::max(scale[static_cast<size_t>(k)], std::abs(va[static_cast<size_t>(k)]));
      diff[static_cast<size_t>(k)] =
          std::max(diff[static_cast<size_t>(k)],
                   std::abs(va[static_cast<size_t>(k)] - it->second[static_cast<size_t>(k)]));
    }
  }
  double worst = 0;
  for (int k = 0; k < 8; ++k)
    if (scale[static_cast<size_t>(k)] > 0)
      worst = std::max(worst, diff[static_cast<size_t>(k)] / scale[static_cast<size_t>(k)]);
  return worst;
}

// Where the last series sample puts the largest density deviation; checks that it is the
// fluid particle of the largest |rho/rho0 - 1| in the last snapshot (the same step).
std::vector<double> check_worst_density_location(const std::string& path, double rho0) {
  test::ResultReader rr(path);
  const test::Snapshot s = rr.last();
  const auto t = rr.series("diagnostics/time");
  const auto dev = rr.series("diagnostics/max_density_deviation");
  const auto at = rr.series("diagnostics/max_density_deviation_at");
  const std::size_t d = at.size() / t.size();
  EXPECT_EQ(t.back(), s.time) << path;
  std::size_t worst = s.size();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == 0 && (worst == s.size() || std::abs(s.density[i] / rho0 - 1) >
                                                    std::abs(s.density[worst] / rho0 - 1)))
      worst = i;
  EXPECT_LT(worst, s.size()) << path;
  if (worst == s.size()) return {};
  EXPECT_NEAR(dev.back(), std::abs(s.density[worst] / rho0 - 1), 1e-12) << path;
  std::vector<double> last(at.end() - static_cast<std::ptrdiff_t>(d), at.end());
  for (std::size_t a = 0; a < d; ++a)
    EXPECT_EQ(last[a], s.position[3 * worst + a]) << path << " axis " << a;
  return last;
}

// `one_fluid`: the largest density deviation is that of the first fluid's material (a
// multi-phase case measures each phase against its own reference density).
void check_rank_counts(const std::string& name, v1::Case c, std::int64_t steps,
                       bool one_fluid = true) {
  c.mutable_time()->set_max_steps(steps);
  c.mutable_output()->set_interval(0);  // snapshots at t = 0 and at the end only
  // Series every step, so that the last sample is the state of the last snapshot.
  c.mutable_output()->set_series_interval(1e-12);
  std::map<int, std::string> outs;
  for (int ranks : {1, 2, 4}) {
    outs[ranks] =
        std::string(SPHD_BINARY_DIR) + "/test-output/mpi_" + name + "_" + std::to_string(ranks);
    const RunOutcome r = run_on(c, ranks, outs[ranks]);
    ASSERT_EQ(r.status, RunStatus::kCompleted)
        << name << " on " << ranks << " ranks: " << r.message;
  }
  const std::string again = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_" + name + "_2_again";
  ASSERT_EQ(run_on(c, 2, again).status, RunStatus::kCompleted);
  if (world_rank() != 0) return;
  const Fields one = read_last(outs[1] + "/result.h5");
  const double d2 = max_relative_difference(one, read_last(outs[2] + "/result.h5"));
  const double d4 = max_relative_difference(one, read_last(outs[4] + "/result.h5"));
  const double rep =
      max_relative_difference(read_last(outs[2] + "/result.h5"), read_last(again + "/result.h5"));
  std::printf(
      "%s after %lld steps: max relative difference 1 vs 2 ranks %.3g, 1 vs 4 ranks %.3g, "
      "2-rank repeat %.3g\n",
      name.c_str(), static_cast<long long>(steps), d2, d4, rep);
  EXPECT_EQ(d2, 0.0);
  EXPECT_EQ(d4, 0.0);
  EXPECT_EQ(rep, 0.0);
  if (!one_fluid) return;
  double rho0 = 0;
  for (const auto& m : c.materials())
    if (m.name() == c.fluids(0).material()) rho0 = m.density();
  const auto at1 = check_worst_density_location(outs[1] + "/result.h5", rho0);
  const auto at4 = check_worst_density_location(outs[4] + "/result.h5", rho0);
  ASSERT_EQ(at1.size(), at4.size());
  for (std::size_t a = 0; a < at1.size(); ++a) EXPECT_NEAR(at1[a], at4[a], 1e-9) << name;
}

// Body series of two runs agree to the bit (NaN, a slot without a body, matches NaN).
void expect_same_series(const test::ResultReader& a, const test::ResultReader& b,
                        std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const auto x = a.series(name), y = b.series(name);
    ASSERT_EQ(x.size(), y.size()) << name;
    for (std::size_t k = 0; k < x.size(); ++k)
      ASSERT_TRUE(x[k] == y[k] || (std::isnan(x[k]) && std::isnan(y[k]))) << name << " entry " << k;
  }
}

TEST(RankConsistency, DamBreak2D) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.04);
  check_rank_counts("dambreak", c, 1500);
}

TEST(RankConsistency, PoiseuillePeriodic2D) {
  check_rank_counts("poiseuille", test::load_case("poiseuille_2d"), 1500);
}

TEST(RankConsistency, CouetteMovingWallsPeriodic2D) {
  // Walls moving through the periodic boundary and across rank boundaries.
  check_rank_counts("couette", test::load_case("couette_2d"), 1500);
}

TEST(RankConsistency, HydrostaticCylinder3D) {
  auto c = test::load_case("hydrostatic_cylinder_3d");
  c.set_dx(0.08);
  check_rank_counts("cylinder3d", c, 200);
}

TEST(RankConsistency, FallingDiskWithContact) {
  // A rigid disk released near the bottom: fluid coupling, body reductions across ranks and
  // wall contact with friction within 600 steps.
  auto c = test::load_case("falling_disk_2d");
  c.set_dx(0.0004);
  c.mutable_bodies(0)->mutable_shape()->mutable_ball()->mutable_center()->set_y(0.0016);
  // A quarter of the tank's height (30 particle rows above the disk): the disk meets the floor
  // the same way, with a quarter of the particles.
  const double top = 0.015;
  c.mutable_domain()->mutable_hi()->set_y(top + 0.001);
  c.mutable_fluids(0)->mutable_shape()->mutable_box()->mutable_hi()->set_y(top);
  c.mutable_walls(0)
      ->mutable_shape()
      ->mutable_shell()
      ->mutable_inner()
      ->mutable_box()
      ->mutable_hi()
      ->set_y(top);
  // Thrown at the floor so that it lands within the 600 steps (the acceleration limit on dt
  // keeps the steps short while fluid is squeezed out of the gap).
  c.mutable_bodies(0)->mutable_initial_velocity()->set_y(-0.12);
  // With friction: the contact history has to agree too.
  c.mutable_contact()->mutable_friction()->set_coefficient(0.3);
  c.mutable_contact()->mutable_friction()->set_tangential_stiffness(2.86e7);
  c.mutable_output()->set_series_interval(1e-6);  // every step: contacts are brief
  check_rank_counts("falling_disk", c, 600);
  if (world_rank() != 0) return;
  // Body trajectories agree bitwise too, and contact did happen.
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_falling_disk_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  EXPECT_EQ(r1.series("bodies/position"), r4.series("bodies/position"));
  EXPECT_EQ(r1.series("bodies/velocity"), r4.series("bodies/velocity"));
  const auto contacts = r1.series("bodies/contacts");
  EXPECT_GT(*std::max_element(contacts.begin(), contacts.end()), 0.0);
}

TEST(RankConsistency, StlFunnelWallAndMeshBodyAcrossRanks) {
  // Geometry from STL files (a funnel block as a wall, one sphere as a rigid body, both also cut
  // out of the fluid), as shipped (coarse): every rank compiles the same meshes and fills the same
  // lattice.
  auto c = test::load_case("funnel_spheres_3d");
  c.mutable_output()->set_series_interval(1e-6);
  check_rank_counts("funnel", c, 50);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_funnel_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  expect_same_series(r1, r4, {"bodies/position", "bodies/velocity", "bodies/mass"});
}

TEST(RankConsistency, DistanceGridWallAcrossRanks) {
  // A wall from a signed-distance grid read from HDF5 (the boulder of the shipped case), with
  // the water placed around it: a box minus the same grid, so that it flows off the boulder at
  // once. Every rank interpolates the same grid and fills the same lattice.
  auto c = test::load_case("dambreak_sdf_obstacle_2d");
  auto* water = c.mutable_fluids(0)->mutable_shape();
  v1::Shape box;
  box.mutable_box()->mutable_lo()->set_x(2.3);
  box.mutable_box()->mutable_hi()->set_x(3.7);
  box.mutable_box()->mutable_hi()->set_y(0.6);
  *water->mutable_difference()->mutable_base() = box;
  *water->mutable_difference()->add_subtract() = c.walls(1).shape();
  check_rank_counts("distance_grid", c, 300);
}

TEST(RankConsistency, BolusesMeltingAcrossRanks) {
  // Phase transitions regroup bodies from particles on several ranks (the gastric seed scene,
  // coarse, with boluses already near C_t so that they start to dissolve at once).
  auto c = test::load_case("gastric_boluses_2d");
  c.set_dx(0.4);
  for (auto& b : *c.mutable_bodies()) b.set_initial_concentration(0.79);
  c.mutable_output()->set_series_interval(1e-6);
  check_rank_counts("boluses", c, 400);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_boluses_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  const auto melted = r1.series("phase/melted");
  std::printf("boluses: %g particles melted in 400 steps, bodies %g -> %g\n", melted.back(),
              r1.series("phase/active_bodies").front(), r1.series("phase/active_bodies").back());
  EXPECT_GT(melted.back(), 0.0);
  EXPECT_EQ(melted, r4.series("phase/melted"));
  expect_same_series(r1, r4, {"bodies/mass", "bodies/position"});
}

TEST(RankConsistency, PowderGrainsMeltingInContactAcrossRanks) {
  // Grains resting on each other and on the hot floor, just below their melting point, melt
  // where they touch (the 2D powder seed scene, coarse): particles change kind and body while
  // they are in contact lists and ghosts on other ranks. The next step's contact must see
  // them as they are now on every rank count. (In these 300 steps the grains melt where they
  // touch the walls, not each other: this run agreed on 1, 2 and 4 ranks also before bf81e52.
  // The single-rank fault is caught by PhaseChange.ABodyThatMeltsLeavesNoContactBehind.)
  auto c = test::load_case("powder_grains_2d_coarse");
  for (auto& b : *c.mutable_bodies()) b.set_initial_temperature(50.9);
  check_rank_counts("powder", c, 300, false);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_powder_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  const auto melted = r1.series("phase/melted");
  const auto contacts = r1.series("bodies/contacts");
  std::printf("powder grains: %g particles melted in 300 steps, bodies %g -> %g\n", melted.back(),
              r1.series("phase/active_bodies").front(), r1.series("phase/active_bodies").back());
  EXPECT_GT(melted.back(), 0.0);
  EXPECT_GT(*std::max_element(contacts.begin(), contacts.end()), 0.0);
  EXPECT_EQ(melted, r4.series("phase/melted"));
  // The melt-gas interface is counted over ghosts as over owned neighbours.
  const auto interface = r1.series("diagnostics/interface_particles");
  EXPECT_GT(*std::max_element(interface.begin(), interface.end()), 0.0);
  expect_same_series(
      r1, r4,
      {"bodies/position", "diagnostics/interface_particles", "diagnostics/stray_phase_particles"});
}

// The stability suite's melt/freeze case, coarse, its disk next to the left wall and one short
// hot phase: the disk melts from the hot wall inwards while, once the walls turn cold, the melt
// freezes along them into new bodies that grow and merge (measured on one rank: 170 of 177
// disk particles melted, 618 solidified (all of it), up to 8 bodies at once, 1 at the end; the
// 170 melted froze again, 143 steps after melting at the soonest, 30 of them by step 250).
v1::Case melt_freeze_by_the_hot_wall() {
  auto c = test::load_case("melt_freeze_cycles_2d");
  c.set_dx(0.04);
  c.mutable_bodies(0)->mutable_shape()->mutable_ball()->mutable_center()->set_x(0.33);
  auto* schedule =
      c.mutable_walls(0)->mutable_temperature()->mutable_value()->mutable_piecewise_linear();
  schedule->clear_times();
  schedule->clear_values();
  for (const auto& [t, T] : {std::pair{0.0, 2.0}, {0.02, 2.0}, {0.025, -1.0}}) {
    schedule->add_times(t);
    schedule->add_values(T);
  }
  return c;
}

TEST(RankConsistency, MeltingAndFreezingWithNewAndMergingBodiesAcrossRanks) {
  // Both directions of the phase transition at once, on particles spread over ranks; all
  // frozen at the end, so no fluid density to compare.
  check_rank_counts("melt_freeze", melt_freeze_by_the_hot_wall(), 600, false);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_melt_freeze_";
  test::ResultReader r1(base + "1/result.h5"), r2(base + "2/result.h5"), r4(base + "4/result.h5");
  const auto melted = r1.series("phase/melted"), frozen = r1.series("phase/solidified");
  const auto bodies = r1.series("phase/active_bodies");
  const auto reversals = r1.series("phase/reversals");
  const double most = *std::max_element(bodies.begin(), bodies.end());
  std::printf(
      "melt/freeze: %g melted, %g solidified in 600 steps, up to %g bodies, %g at the end; %g "
      "reversals, the fewest steps between two transitions of a particle %g\n",
      melted.back(), frozen.back(), most, bodies.back(), reversals.back(),
      r1.series("phase/shortest_reversal_steps").back());
  EXPECT_GT(reversals.back(), 0.0);  // melted particles froze again
  EXPECT_GT(melted.back(), 100.0);
  EXPECT_GT(frozen.back(), 100.0);
  EXPECT_GE(most, 3.0);            // new bodies born apart from each other ...
  EXPECT_LT(bodies.back(), most);  // ... that merge
  for (const test::ResultReader* r : {&r2, &r4}) {
    EXPECT_EQ(melted, r->series("phase/melted"));
    EXPECT_EQ(frozen, r->series("phase/solidified"));
    EXPECT_EQ(bodies, r->series("phase/active_bodies"));
    // The reversal series too: the step of each particle's last transition migrates with it.
    expect_same_series(r1, *r,
                       {"bodies/mass", "bodies/position", "bodies/velocity", "phase/reversals",
                        "phase/shortest_reversal_steps"});
  }
}

// Two drops frozen into bodies at the first step, thrown at each other, merge where they touch
// (PhaseTransition.merge_bodies): the touching pairs are found on the owners of the
// solidified particles, some of them next to ghosts, and the merged body is rebuilt from
// particles on several ranks.
constexpr std::int64_t kDropsSteps = 100;

TEST(RankConsistency, FrozenDropsMergeAcrossRanks) {
  auto c = test::load_case("frozen_drops_merge_2d");
  check_rank_counts("drops_merge", c, kDropsSteps);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_drops_merge_";
  test::ResultReader r1(base + "1/result.h5"), r2(base + "2/result.h5"), r4(base + "4/result.h5");
  const auto merged = r1.series("phase/merged_bodies");
  const auto bodies = r1.series("phase/active_bodies");
  const auto step = r1.series("diagnostics/step");
  const auto at = static_cast<std::size_t>(
      std::find_if(merged.begin(), merged.end(), [](double m) { return m > 0; }) - merged.begin());
  std::printf("frozen drops: %g solidified, bodies %g -> %g, merged at step %g\n",
              r1.series("phase/solidified").back(), bodies[1], bodies.back(),
              at < step.size() ? step[at] : -1.0);
  EXPECT_EQ(bodies[1], 2.0);      // two drops frozen apart at the first step ...
  EXPECT_EQ(bodies.back(), 1.0);  // ... that merged
  EXPECT_EQ(merged.back(), 1.0);
  for (const test::ResultReader* r : {&r2, &r4}) {
    EXPECT_EQ(merged, r->series("phase/merged_bodies"));
    EXPECT_EQ(bodies, r->series("phase/active_bodies"));
    expect_same_series(r1, *r,
                       {"bodies/mass", "bodies/position", "bodies/velocity", "bodies/inertia"});
  }
}

TEST(RankConsistency, PowderMelting3DAcrossRanks) {
  // The 3D seed scene (coarse) with its grains started a thousandth of a kelvin below their
  // melting point: in 3D, particles leave bodies spread over ranks and the bodies (quaternion
  // orientation, 3D inertia) are rebuilt from them (measured on one rank: 638 of 1349
  // particles melted in the first 30 steps, where the grains touch the hot walls, 746 by
  // step 90).
  auto c = test::load_case("powder_melting_3d_coarse");
  for (auto& b : *c.mutable_bodies()) b.set_initial_temperature(1704.999);
  check_rank_counts("powder3d", c, 100, false);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_powder3d_";
  test::ResultReader r1(base + "1/result.h5"), r2(base + "2/result.h5"), r4(base + "4/result.h5");
  const auto melted = r1.series("phase/melted");
  std::printf("3D powder: %g particles melted in 100 steps\n", melted.back());
  EXPECT_GT(melted.back(), 600.0);
  for (const test::ResultReader* r : {&r2, &r4}) {
    EXPECT_EQ(melted, r->series("phase/melted"));
    expect_same_series(r1, *r,
                       {"bodies/mass", "bodies/position", "bodies/velocity", "bodies/orientation",
                        "bodies/inertia"});
  }
}

TEST(RankConsistency, PairKernelTableAndStreamAgreeToTheBit) {
  // The pair kernel kept as a table or evaluated by each pass (solver/core/pair_kernel.h)
  // must give the same bits: the coarse powder scene with the gas jet started at once has
  // every pass that reads it (density, wall condition, conduction with Dirichlet walls,
  // forces on fluid and bodies, solid fraction) and grains melting in contact, on 2 ranks.
  auto c = test::load_case("powder_grains_2d_coarse");
  for (auto& b : *c.mutable_bodies()) b.set_initial_temperature(50.9);
  for (auto& o : *c.mutable_open_boundaries()) {
    o.set_start_time(0.0002);
    o.set_ramp_time(0.0005);
  }
  c.mutable_time()->set_max_steps(300);
  c.mutable_output()->set_interval(0);
  c.mutable_output()->set_series_interval(1e-12);  // every step
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_pair_kernel_";
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_TABLE);
  ASSERT_EQ(run_on(c, 2, base + "table").status, RunStatus::kCompleted);
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_STREAM);
  ASSERT_EQ(run_on(c, 2, base + "stream").status, RunStatus::kCompleted);
  if (world_rank() != 0) return;
  const double d = max_relative_difference(read_last(base + "table/result.h5"),
                                           read_last(base + "stream/result.h5"));
  test::ResultReader table(base + "table/result.h5"), stream(base + "stream/result.h5");
  const auto melted = table.series("phase/melted");
  const auto through = table.series("open_boundaries/inlet");
  std::printf(
      "pair kernel table vs stream after 300 steps: max relative difference %.3g, "
      "%g particles melted, %g entered through the inlet\n",
      d, melted.back(), through.back());
  EXPECT_EQ(d, 0.0);
  EXPECT_GT(melted.back(), 0.0);
  EXPECT_GT(through.back(), 0.0);
  EXPECT_EQ(melted, stream.series("phase/melted"));
  EXPECT_EQ(table.series("diagnostics/kinetic_energy"),
            stream.series("diagnostics/kinetic_energy"));
}

// The single-precision pair kernel (PAIR_KERNEL_COMPACT) in the scene with every pass that
// reads it, grains melting in contact and the gas jet: the same bits on 1, 2 and 4 ranks
// (its rounding is a function of the pair, not of where the pair is computed), and within
// rounding of the double table.
TEST(RankConsistency, CompactPairKernelAcrossRanks) {
  auto c = test::load_case("powder_grains_2d_coarse");
  for (auto& b : *c.mutable_bodies()) b.set_initial_temperature(50.9);
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_COMPACT);
  check_rank_counts("compact", c, 300, false);
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_";
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_TABLE);
  c.mutable_time()->set_max_steps(300);
  c.mutable_output()->set_interval(0);
  c.mutable_output()->set_series_interval(1e-12);
  ASSERT_EQ(run_on(c, 1, base + "compact_vs_table").status, RunStatus::kCompleted);
  if (world_rank() != 0) return;
  const double d = max_relative_difference(read_last(base + "compact_1/result.h5"),
                                           read_last(base + "compact_vs_table/result.h5"));
  test::ResultReader compact(base + "compact_1/result.h5");
  std::printf(
      "compact pair kernel after 300 steps of the powder grains: %g particles melted, max "
      "relative difference from the double table %.3g\n",
      compact.series("phase/melted").back(), d);
  EXPECT_GT(compact.series("phase/melted").back(), 0.0);
}

TEST(RankConsistency, DamBreakWithADiskOnTheFloorRebalances) {
  // A heavy disk resting on the floor of the dam break's column, in contact with the floor,
  // while the collapsing water makes the decomposition move particles between ranks every
  // few dozen steps: the contact drift after a rebalance must read the neighbour list of the
  // particles as they are after the migration.
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.04);
  auto* m = c.add_materials();
  m->set_name("stone");
  m->set_phase(v1::SOLID);
  m->set_density(4);
  auto* b = c.add_bodies();
  b->set_name("disk");
  b->set_material("stone");
  b->mutable_shape()->mutable_ball()->mutable_center()->set_x(0.5);
  b->mutable_shape()->mutable_ball()->mutable_center()->set_y(
      0.14);  // lowest row one dx above the floor
  b->mutable_shape()->mutable_ball()->set_radius(0.16);
  // Stiff enough to hold it within a few percent of dx, soft enough for one sub-step.
  c.mutable_contact()->set_stiffness(400);
  c.mutable_contact()->set_damping(1);
  check_rank_counts("dambreak_disk", c, 1500);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_dambreak_disk_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  EXPECT_EQ(r1.series("bodies/position"), r4.series("bodies/position"));
  EXPECT_EQ(r1.series("bodies/velocity"), r4.series("bodies/velocity"));
  const auto contacts = r1.series("bodies/contacts");
  const auto touching =
      std::count_if(contacts.begin(), contacts.end(), [](double n) { return n > 0; });
  std::printf("disk touching the floor in %lld of %zu samples\n", static_cast<long long>(touching),
              contacts.size());
  EXPECT_GT(touching, static_cast<std::ptrdiff_t>(contacts.size() / 2));
}

// The inflow/outflow channel with a short ramp, so that within 1500 steps the inlet has
// refilled its lanes (new particles, new ids) and the outlet has deleted particles many times,
// across rank boundaries.
v1::Case open_channel() {
  auto c = test::load_case("channel_inflow_outflow_2d");
  c.mutable_open_boundaries(0)->set_ramp_time(0.5);
  c.mutable_output()->set_series_interval(1e-6);  // every step
  return c;
}

TEST(RankConsistency, OpenChannelCreatesAndDeletesIdentically) {
  check_rank_counts("open_channel", open_channel(), 1500);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_open_channel_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  const auto in = r1.series("open_boundaries/inlet"), out = r1.series("open_boundaries/outlet");
  std::printf(
      "open channel: %g particles entered, %g left in 1500 steps; %zu particles at the end\n",
      in.back(), out.back(), r1.last().size());
  EXPECT_GT(in.back(), 100.0);
  EXPECT_GT(out.back(), 100.0);
  EXPECT_EQ(in, r4.series("open_boundaries/inlet"));
  EXPECT_EQ(out, r4.series("open_boundaries/outlet"));
}

TEST(RankConsistency, ABodyLeavesThroughTheOutletIdentically) {
  // The disk's particles are deleted at the outlet on whichever rank owns them, and every
  // rank rebuilds what remains of the body from the same gathered particles.
  auto c = test::load_case("channel_body_outflow_2d");
  check_rank_counts("body_outflow", c, 900);  // t = 0.52: the disk is gone by 0.48
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_body_outflow_";
  test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
  // Bitwise, since the slot of a body that is gone holds NaN.
  const auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  const auto mass = r1.series("bodies/mass");
  EXPECT_TRUE(same_bits(mass, r4.series("bodies/mass")));
  EXPECT_TRUE(same_bits(r1.series("bodies/velocity"), r4.series("bodies/velocity")));
  EXPECT_TRUE(std::isnan(mass.back())) << "the disk did not leave within 900 steps";
}

TEST(RankConsistency, OpenDuct3D) {
  // A square duct with a parabolic (product-of-parabolas) inflow started at once and a
  // pressure outlet: lanes on a 2D grid, spawning and deleting on 1, 2 and 4 ranks.
  const auto c = parse_case_text(R"(
name: "open_duct_3d"
dimension: 3
dx: 0.1
domain { lo { x: -0.3 y: -0.3 z: -0.3 } hi { x: 1.3 y: 1.3 z: 1.3 } }
materials { name: "fluid" density: 1 eos { kind: LINEAR sound_speed: 20 } dynamic_viscosity: 0.1 }
fluids { name: "duct" material: "fluid" shape { box { lo { } hi { x: 1 y: 1 z: 1 } } } }
walls { name: "duct" shape { difference {
  base { box { lo { x: -0.3 y: -0.3 z: -0.3 } hi { x: 1.3 y: 1.3 z: 1.3 } } }
  subtract { box { lo { x: -0.3 } hi { x: 1.3 y: 1 z: 1 } } } } } }
open_boundaries { name: "inlet" kind: INFLOW material: "fluid" direction { x: 1 }
  region { lo { x: -0.3 } hi { y: 1 z: 1 } } profile: PARABOLIC mean_velocity: 1 }
open_boundaries { name: "outlet" kind: OUTFLOW material: "fluid" direction { x: 1 }
  region { lo { x: 1 } hi { x: 1.3 y: 1 z: 1 } } }
fluid_model { density: SUMMATION transport_velocity: true }
time { end_time: 1 }
output { series_interval: 1e-6 }
)");
  ASSERT_TRUE(validate_case(c).empty()) << join_errors(validate_case(c));
  check_rank_counts("open_duct3d", c, 300);
  if (world_rank() != 0) return;
  test::ResultReader r1(std::string(SPHD_BINARY_DIR) + "/test-output/mpi_open_duct3d_1/result.h5");
  const auto in = r1.series("open_boundaries/inlet"), out = r1.series("open_boundaries/outlet");
  std::printf("open duct 3D: %g particles entered, %g left in 300 steps\n", in.back(), out.back());
  EXPECT_GT(in.back(), 50.0);
  EXPECT_GT(out.back(), 50.0);
}

// Runs `c` with options `o` on the first `ranks` ranks of MPI_COMM_WORLD.
RunOutcome run_with(const v1::Case& c, int ranks, RunOptions o) {
  MPI_Comm sub;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &sub);
  RunOutcome r;
  if (sub != MPI_COMM_NULL) {
    o.quiet = true;
    r = run_case(c, sub, o);
    MPI_Comm_free(&sub);
  }
  wait_for_all_ranks();
  int status = static_cast<int>(r.status);
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  r.status = static_cast<RunStatus>(status);
  return r;
}

// A checkpoint written at step `at` of a 2-rank run continues on 4 and on 1 rank to the same
// particles, ids and fields as an uninterrupted 1-rank run of `steps` steps, carrying over
// the 2-rank run's series up to the checkpoint.
void check_resume(const std::string& name, v1::Case c, std::int64_t steps, int at) {
  c.mutable_time()->set_max_steps(steps);
  c.mutable_output()->set_interval(0);
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_" + name + "_resume_";
  RunOptions o;
  o.output_dir = dir + "reference";
  ASSERT_EQ(run_with(c, 1, o).status, RunStatus::kCompleted);
  o.output_dir = dir + "checkpointed";
  int polls = 0;
  o.checkpoint_requested = [&polls, at] { return ++polls == at; };  // once per step, rank 0
  ASSERT_EQ(run_with(c, 2, o).status, RunStatus::kCompleted);
  char ckpt[64];
  std::snprintf(ckpt, sizeof ckpt, "checkpointed/checkpoints/ckpt_%012d.h5", at);
  for (int ranks : {4, 1}) {
    RunOptions ro;
    ro.output_dir = dir + "resumed_" + std::to_string(ranks);
    ro.resume_from = dir + ckpt;
    // The 2-rank run went on past its checkpoint: its rows after the checkpoint must go.
    ro.previous_result = dir + "checkpointed/result.h5";
    ASSERT_EQ(run_with(c, ranks, ro).status, RunStatus::kCompleted) << ranks << " ranks";
  }
  if (world_rank() != 0) return;
  // The carried-over series line up with an uninterrupted run's, row for row.
  test::ResultReader rr(dir + "reference/result.h5");
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("diagnostics/time"), rr.series("diagnostics/time")) << ranks << " ranks";
    for (const char* n : {"diagnostics/step", "diagnostics/max_density_deviation_at",
                          "phase/melted", "bodies/time", "open_boundaries/time"})
      if (rr.has_series(n)) {
        EXPECT_EQ(rs.series_shape(n), rr.series_shape(n)) << n << ", " << ranks << " ranks";
      }
    // Cumulative counters continue across the resume instead of restarting at zero.
    if (rr.has_series("phase/melted")) {
      const auto step = rr.series("diagnostics/step");
      const auto melted = rr.series("phase/melted");
      const auto k = static_cast<std::size_t>(
          std::find(step.begin(), step.end(), static_cast<double>(at)) - step.begin());
      ASSERT_LT(k, step.size()) << "no sample at the checkpoint's step";
      EXPECT_GT(melted[k] + rr.series("phase/solidified")[k], 0.0)
          << "nothing to carry over at the checkpoint";
    }
    for (const char* n : {"phase/melted", "phase/solidified", "phase/reversals",
                          "phase/shortest_reversal_steps", "phase/merged_bodies"})
      if (rr.has_series(n)) {
        EXPECT_EQ(rs.series(n), rr.series(n)) << n << ", " << ranks << " ranks";
      }
  }
  const Fields ref = read_last(dir + "reference/result.h5");
  const double dc = max_relative_difference(ref, read_last(dir + "checkpointed/result.h5"));
  const double d4 = max_relative_difference(ref, read_last(dir + "resumed_4/result.h5"));
  const double d1 = max_relative_difference(ref, read_last(dir + "resumed_1/result.h5"));
  std::printf(
      "%s, %lld steps: uninterrupted 1 rank vs 2 ranks writing a checkpoint at step %d %.3g, "
      "resumed on 4 ranks %.3g, resumed on 1 rank %.3g\n",
      name.c_str(), static_cast<long long>(steps), at, dc, d4, d1);
  EXPECT_EQ(dc, 0.0);
  EXPECT_EQ(d4, 0.0);
  EXPECT_EQ(d1, 0.0);
}

TEST(RankConsistency, OpenChannelResumesFromCheckpointOnAnyRankCount) {
  // The id counter and the boundary tallies are in the checkpoint's state, the buffer
  // membership in its columns.
  check_resume("open", open_channel(), 1500, 700);
}

// The channel drawn backwards through its pressure outlet: the outlet's buffer fills its
// lanes at the far face (new particles, new ids) on whichever rank owns them; 1/2/4 ranks and
// resumed from a checkpoint at step 751. With backflow_stabilization 0.5, whose target
// pressure reads the lane's flux, a sum over the ranks.
TEST(RankConsistency, BackflowThroughAnOutletFillsIdentically) {
  auto c = test::backflow_channel(0.5);
  for (auto& o : *c.mutable_open_boundaries())
    if (o.kind() == v1::OUTFLOW && !o.has_mean_velocity()) o.set_backflow_stabilization(0.5);
  check_rank_counts("backflow", c, 1500);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("backflow", c, 1500, 751);
  if (world_rank() != 0) return;
  test::ResultReader r1(std::string(SPHD_BINARY_DIR) + "/test-output/mpi_backflow_1/result.h5");
  const double in = r1.series("open_boundaries/inlet").back();
  std::printf("backflow channel: %g particles came in through the pressure outlet in 1500 steps\n",
              -in);
  EXPECT_LT(in, -100.0);
}

TEST(RankConsistency, BolusesResumeFromCheckpointOnAnyRankCount) {
  // Bodies, their contact history and phase transitions continue from the checkpoint; the
  // first step's contact drift needs the neighbour list of the checkpointed positions.
  auto c = test::load_case("gastric_boluses_2d");
  c.set_dx(0.4);
  for (auto& b : *c.mutable_bodies()) b.set_initial_concentration(0.79);
  c.mutable_output()->set_series_interval(1e-6);  // every step: rows after the checkpoint
  // Melting starts at step 230: the checkpoint at 300 has melted particles to count on from.
  check_resume("boluses", c, 400, 300);
}

TEST(RankConsistency, MeltingAndFreezingResumesFromCheckpointOnAnyRankCount) {
  // Each particle's last transition is in the checkpoint's columns: the melted particles that
  // freeze after the resume (140 of the 170) count as reversals only if it came back, and
  // where it lands after the resume's migration must not matter.
  auto c = melt_freeze_by_the_hot_wall();
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("melt_freeze", c, 600, 250);
}

TEST(RankConsistency, FrozenDropsMergeAfterAResume) {
  // The checkpoint falls while the two frozen drops are still apart: which particles
  // solidified (each particle's last transition, a checkpointed column) decides that they
  // merge after the resume, on any rank count.
  auto c = test::load_case("frozen_drops_merge_2d");
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("drops_merge", c, kDropsSteps, 10);
  if (world_rank() != 0) return;
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_drops_merge_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto merged = rr.series("phase/merged_bodies");
  const auto step = rr.series("diagnostics/step");
  const auto k = static_cast<std::size_t>(std::find(step.begin(), step.end(), 10.0) - step.begin());
  ASSERT_LT(k, step.size());
  EXPECT_EQ(merged[k], 0.0);      // apart at the checkpoint ...
  EXPECT_EQ(merged.back(), 1.0);  // ... merged after it
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    expect_same_series(rr, rs, {"bodies/mass", "bodies/position", "bodies/velocity"});
  }
}

TEST(RankConsistency, ABodyHalfwayThroughTheOutletResumesFromCheckpoint) {
  // The checkpoint falls while the disk is partly deleted at the outlet: which of its
  // particles came into the outflow's buffer (their zone column) and what remains of the body
  // (its state) must both continue, or the particles deleted after the resume differ.
  auto c = test::load_case("channel_body_outflow_2d");
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  constexpr int kAt = 650;                         // t = 0.37: first particle out at 0.32
  check_resume("body_outflow", c, 900, kAt);
  if (world_rank() != 0) return;
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_body_outflow_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto step = rr.series("diagnostics/step"), time = rr.series("diagnostics/time");
  const auto k = static_cast<std::size_t>(
      std::find(step.begin(), step.end(), static_cast<double>(kAt)) - step.begin());
  ASSERT_LT(k, step.size()) << "no sample at the checkpoint's step";
  const auto body_time = rr.series("bodies/time"), mass = rr.series("bodies/mass");
  const auto b = static_cast<std::size_t>(std::find(body_time.begin(), body_time.end(), time[k]) -
                                          body_time.begin());
  ASSERT_LT(b, mass.size()) << "no body sample at the checkpoint's time";
  std::printf("disk mass at the checkpoint %.4f of %.4f, at the end %g\n", mass[b], mass[0],
              mass.back());
  EXPECT_GT(mass[b], 0.0);
  EXPECT_LT(mass[b], mass[0]) << "the checkpoint is not in the middle of the exit";
  EXPECT_TRUE(std::isnan(mass.back())) << "the disk did not leave within 900 steps";
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    const auto m = rs.series("bodies/mass");
    ASSERT_EQ(m.size(), mass.size()) << ranks << " ranks";
    EXPECT_EQ(std::memcmp(m.data(), mass.data(), m.size() * sizeof(double)), 0)
        << "body mass differs after resuming on " << ranks << " ranks";
  }
}

TEST(RankConsistency, DamBreakRebalances) {
  // After the collapse the particles pile up at the far wall; the decomposition follows. The
  // balanced quantity is the work (fluid particles weigh ten wall particles).
  auto c = test::load_case("dambreak_2d");  // dx = 0.02: 2500 fluid particles
  c.mutable_time()->set_end_time(2.5);
  c.mutable_output()->set_interval(0);
  const std::string out = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_rebalance";
  ASSERT_EQ(run_on(c, 4, out).status, RunStatus::kCompleted);
  if (world_rank() != 0) return;
  test::ResultReader rr(out + "/result.h5");
  const auto t = rr.series("diagnostics/time");
  const auto imb = rr.series("diagnostics/imbalance");
  double worst_late = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > 1.5) worst_late = std::max(worst_late, imb[k]);
  std::printf(
      "Dam break on 4 ranks: largest rank work / mean work after t = 1.5: %.3f (final %.3f)\n",
      worst_late, imb.back());
  EXPECT_LE(worst_late, 1.10);
}

// Verlet lists (neighbor_skin, 0.3 dx by default) change only the order of the sums: the dam
// break with a skin agrees with searching every step to rounding, with far fewer searches.
// (With the double-precision pair kernel table, as by default: PAIR_KERNEL_COMPACT evaluates
// the kernel of a refined list from single-precision squared distances, which moves the
// result by 5e-7 relative over these 1500 steps.)
TEST(RankConsistency, VerletListsAgreeWithSearchingEveryStep) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.04);
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_TABLE);
  c.mutable_time()->set_max_steps(1500);
  c.mutable_output()->set_interval(0);
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_verlet_";
  c.set_neighbor_skin(0);
  const RunOutcome every = run_on(c, 1, base + "every_step");
  ASSERT_EQ(every.status, RunStatus::kCompleted);
  c.clear_neighbor_skin();
  const RunOutcome skin = run_on(c, 2, base + "skin");
  ASSERT_EQ(skin.status, RunStatus::kCompleted);
  if (world_rank() != 0) return;
  const double d = max_relative_difference(read_last(base + "every_step/result.h5"),
                                           read_last(base + "skin/result.h5"));
  std::printf(
      "dam break, 1500 steps: %lld searches without a skin, %lld with 0.3 dx; max relative "
      "difference %.3g\n",
      static_cast<long long>(every.neighbor_searches),
      static_cast<long long>(skin.neighbor_searches), d);
  EXPECT_EQ(every.neighbor_searches, 1501);  // the start and every step
  EXPECT_LT(skin.neighbor_searches, 1500 / 4);
  EXPECT_GT(d, 0.0) << "the skin changed nothing: was it used?";
  EXPECT_LT(d, 1e-9);
}

// A checkpoint between two searches: the resumed run, on any rank count, lists the candidates
// of the search before the checkpoint (the particles carry where they were searched), refines
// them as the uninterrupted run does and searches again at the same steps, so it ends with the
// same bits.
TEST(RankConsistency, VerletListsResumeBetweenSearchesOnAnyRankCount) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.04);
  c.mutable_output()->set_series_interval(1e-12);  // every step
  constexpr int kAt = 700;
  check_resume("verlet", c, 1500, kAt);
  if (world_rank() != 0) return;
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_verlet_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto step = rr.series("diagnostics/step");
  const auto searches = rr.series("diagnostics/neighbor_searches");
  const auto k = static_cast<std::size_t>(
      std::find(step.begin(), step.end(), static_cast<double>(kAt)) - step.begin());
  ASSERT_LT(k + 1, step.size()) << "no sample at the checkpoint's step";
  EXPECT_EQ(searches[k], searches[k - 1]) << "step " << kAt << " searched: not between searches";
  EXPECT_EQ(searches[k + 1], searches[k]) << "the step after the checkpoint searched";
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("diagnostics/neighbor_searches"), searches) << ranks << " ranks";
  }
}

// Surface tension (solver/physics/surface_tension.h): the normals each rank sends its
// neighbours before the curvature pass, and the sums over the neighbours that have one, must
// not depend on the rank count or on a resume: two fluids in a periodic box (the normals of
// the other phase enter with their sign turned), a square drop and a circular one set moving.
TEST(RankConsistency, SurfaceTensionDropsAcrossRanks) {
  auto square = test::load_case("square_droplet_2d");
  square.set_dx(0.1);  // 1024 particles
  check_rank_counts("surface_tension_square", square, 300, false);
  auto drop = test::load_case("oscillating_drop_2d");
  drop.set_dx(0.1);  // 1600 particles
  check_rank_counts("surface_tension_drop", drop, 300, false);
}

TEST(RankConsistency, SurfaceTensionResumesFromCheckpointOnAnyRankCount) {
  auto c = test::load_case("square_droplet_2d");
  c.set_dx(0.1);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("surface_tension", c, 300, 150);
  if (world_rank() != 0) return;
  // The unit's own series carries over and goes on identically.
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_surface_tension_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto count = rr.series("surface_tension/interface_particles");
  EXPECT_GT(count.back(), 0.0);
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("surface_tension/interface_particles"), count) << ranks << " ranks";
    EXPECT_EQ(rs.series("surface_tension/max_curvature"),
              rr.series("surface_tension/max_curvature"))
        << ranks << " ranks";
  }
}

// Surface tension at a free surface (solver/physics/surface_tension_free_surface.h): the void's
// colour sums over everything present, the weighted normals and the curvatures averaged over
// the neighbours (a second halo update) must not depend on the rank count or on a resume: a
// free drop set oscillating and a free square relaxing.
TEST(RankConsistency, SurfaceTensionFreeSurfaceAcrossRanks) {
  auto drop = test::load_case("free_drop_oscillation_2d");
  drop.set_dx(0.1);  // 316 particles
  check_rank_counts("surface_tension_free_drop", drop, 300);
  auto square = test::load_case("free_square_droplet_2d");
  square.set_dx(0.1);  // 256 particles
  check_rank_counts("surface_tension_free_square", square, 300);
}

// The contact-line force at a free surface (surface_tension.h, contact_line_force): the mean
// normal over the neighbours, read from the ghosts, must not depend on the rank count or on a
// resume: a free half drop on a floor with a 60-degree angle.
TEST(RankConsistency, SurfaceTensionFreeSurfaceContactAngleAcrossRanks) {
  auto c = test::load_case("free_drop_contact_angle_2d");
  c.set_dx(0.1);
  check_rank_counts("surface_tension_free_contact_angle", c, 300);
}

TEST(RankConsistency, SurfaceTensionFreeSurfaceContactAngleResumes) {
  auto c = test::load_case("free_drop_contact_angle_2d");
  c.set_dx(0.1);
  check_resume("surface_tension_free_contact_angle", c, 300, 150);
}

TEST(RankConsistency, SurfaceTensionFreeSurfaceResumesFromCheckpointOnAnyRankCount) {
  auto c = test::load_case("free_drop_oscillation_2d");
  c.set_dx(0.1);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("surface_tension_free", c, 300, 150);
  if (world_rank() != 0) return;
  const std::string dir =
      std::string(SPHD_BINARY_DIR) + "/test-output/mpi_surface_tension_free_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto count = rr.series("surface_tension/interface_particles");
  EXPECT_GT(count.back(), 0.0);
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("surface_tension/interface_particles"), count) << ranks << " ranks";
    EXPECT_EQ(rs.series("surface_tension/max_curvature"),
              rr.series("surface_tension/max_curvature"))
        << ranks << " ranks";
  }
}

// Elastic bodies (solver/elastic/): the reference neighbours are found in the neighbour list
// of the current positions, the ghosts carry the reference positions and P B, and the
// energies and observed displacements are exact sums; the fluid-structure coupling adds the
// fluid's force on each elastic particle. A plate oscillating at large amplitude, and a
// plate under a water column, on 1/2/4 ranks and resumed on 1 and 4.
TEST(RankConsistency, ElasticBodiesAcrossRanks) {
  auto plate = test::load_case("oscillating_plate_2d");
  plate.set_dx(0.004);  // 330 particles
  plate.mutable_elastic_bodies(0)
      ->mutable_initial_velocity_field()
      ->mutable_beam_mode()
      ->set_tip_velocity(2.8515);  // the benchmark's large amplitude
  check_rank_counts("elastic_plate", plate, 300, false);
  auto fsi = test::load_case("plate_under_water_2d");
  fsi.set_dx(0.005);  // 800 fluid and 448 plate particles
  check_rank_counts("elastic_fsi", fsi, 300, false);
}

// Anisotropic kernels (ASPH, docs/asph.md): the search radius grows to the longest semi-axis of
// the elliptical support (r times the kernel's), the ghosts carry each particle's kernel map G,
// and the reference pairs are those in either particle's ellipse. The plate with r = 4 at large
// amplitude on 1/2/4 ranks.
TEST(RankConsistency, AnisotropicElasticPlateAcrossRanks) {
  auto plate = test::load_case("oscillating_plate_2d");
  plate.set_dx(0.002);  // 10 particles through the thickness, 8 mm apart along the plate
  plate.mutable_elastic_bodies(0)
      ->mutable_initial_velocity_field()
      ->mutable_beam_mode()
      ->set_tip_velocity(2.8515);
  plate.mutable_elastic_bodies(0)->mutable_anisotropy()->set_ratio(4);
  check_rank_counts("asph_plate", plate, 300, false);
  // The kernel maps are rebuilt from the case on a resume, not read back: the resumed runs
  // must still match the uninterrupted one.
  plate.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("asph_plate", plate, 300, 150);
}

TEST(RankConsistency, ElasticBodiesResumeFromCheckpointOnAnyRankCount) {
  auto c = test::load_case("plate_under_water_2d");
  c.set_dx(0.005);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("elastic_fsi", c, 300, 150);
  if (world_rank() != 0) return;
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_elastic_fsi_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto d = rr.series("elastic/plate/displacement");
  EXPECT_NE(d.back(), 0.0);
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("elastic/plate/displacement"), d) << ranks << " ranks";
    EXPECT_EQ(rs.series("elastic/plate/strain_energy"), rr.series("elastic/plate/strain_energy"))
        << ranks << " ranks";
  }
}

// Sub-cycled elastic bodies (TimeControl.subcycle_elastic_bodies): the sub-steps refresh the
// ghosts' positions and solid velocities, the sub-step count comes from a bound reduced over
// all ranks, and the held fluid force, the solid's own velocity and the shown acceleration are
// persistent columns; the bound travels in the checkpoint. The stiff plate under water (E = 3e8
// Pa, about three sub-steps per fluid step) on 1/2/4 ranks and resumed on 1 and 4.
TEST(RankConsistency, SubcycledElasticBodiesAcrossRanksAndResume) {
  auto c = test::load_case("plate_under_water_2d");
  c.set_dx(0.005);
  c.mutable_materials(1)->set_youngs_modulus(3e8);
  c.mutable_time()->set_subcycle_elastic_bodies(true);
  check_rank_counts("elastic_subcycled", c, 300, false);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("elastic_subcycled", c, 300, 150);
  if (world_rank() != 0) return;
  const std::string dir =
      std::string(SPHD_BINARY_DIR) + "/test-output/mpi_elastic_subcycled_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  const auto d = rr.series("elastic/plate/displacement");
  EXPECT_NE(d.back(), 0.0);
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    EXPECT_EQ(rs.series("elastic/plate/displacement"), d) << ranks << " ranks";
    EXPECT_EQ(rs.series("elastic/plate/kinetic_energy"), rr.series("elastic/plate/kinetic_energy"))
        << ranks << " ranks";
  }
}

// J2 plasticity (Material.plasticity): the plastic state ((Cbar^p)^-1 and the equivalent
// plastic strain) is per particle and persistent, so it migrates with a particle between ranks
// and travels in the checkpoint; the return mapping advances it once per step. The steel bar of
// tests/validation/plasticity_test.cc pulled fast (20 m/s at each grip after 20 us), plastic from
// about step 120 on, on 1/2/4 ranks, and resumed on 1 and 4 ranks from step 150.
TEST(RankConsistency, PlasticBarAcrossRanksAndResume) {
  const v1::Case c = parse_case_text(test::plastic_bar_case(20.0, 2e-5, 1.0));
  check_rank_counts("plastic_bar", c, 300, false);
  v1::Case r = c;
  r.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("plastic_bar", r, 300, 150);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_plastic_bar_";
  // The equivalent plastic strain by particle id, and the grips' forces, to the bit.
  const auto alpha_by_id = [](const std::string& path) {
    test::ResultReader rr(path);
    const test::Snapshot s = rr.last();
    const auto a = rr.snapshot_field(rr.snapshot_count() - 1, "equivalent_plastic_strain");
    std::map<std::int64_t, double> out;
    for (std::size_t i = 0; i < s.size(); ++i) out[s.id[i]] = a[i];
    return out;
  };
  const auto one = alpha_by_id(base + "1/result.h5");
  double largest = 0;
  for (const auto& [id, a] : one) largest = std::max(largest, a);
  std::printf("plastic bar: largest equivalent plastic strain after 300 steps %.4f\n", largest);
  EXPECT_GT(largest, 0.005);
  for (const char* run : {"2/result.h5", "4/result.h5", "resume_resumed_1/result.h5",
                          "resume_resumed_4/result.h5", "resume_checkpointed/result.h5"})
    EXPECT_EQ(alpha_by_id(base + run), one) << run;
  test::ResultReader rr(base + "resume_reference/result.h5");
  const auto f = rr.series("elastic/bar/constraint_force");
  EXPECT_GT(f.back(), 0.0);
  for (const char* run : {"resume_resumed_1/result.h5", "resume_resumed_4/result.h5"}) {
    test::ResultReader rs(base + run);
    EXPECT_EQ(rs.series("elastic/bar/constraint_force"), f) << run;
    EXPECT_EQ(rs.series("elastic/bar/strain_energy"), rr.series("elastic/bar/strain_energy"))
        << run;
  }
}

// Quasi-static loading (time.quasi_static, docs/quasi_static.md): each load step relaxes the
// bodies by inner steps whose count depends on a kinetic energy summed exactly, and the
// relaxation damping reads the neighbours' velocities before its update, so the inner loops end
// at the same step on any rank count. The steel bar stretched quasi-statically (8 load steps,
// plastic after about three) on 1/2/4 ranks, resumed on 1 and 4 ranks from load
// step 4.
TEST(RankConsistency, QuasiStaticBarAcrossRanksAndResume) {
  const double load_step = 0.0098;
  v1::Case c = parse_case_text(
      test::plastic_bar_case(1.6e-3, 1e-6, 0.98, test::plastic_bar_quasi_static(load_step, 0.93)));
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_rank_counts("quasi_static_bar", c, 8, false);
  check_resume("quasi_static_bar", c, 8, 4);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_quasi_static_bar_";
  test::ResultReader rr(base + "resume_reference/result.h5");
  const auto inner = rr.series("elastic/relaxation_steps");
  std::printf("quasi-static bar: %.0f inner steps in 8 load steps\n", inner.back());
  EXPECT_GT(inner.back(), 16.0);
  for (const char* run : {"1/result.h5", "2/result.h5", "4/result.h5", "resume_resumed_1/result.h5",
                          "resume_resumed_4/result.h5"}) {
    test::ResultReader rs(base + run);
    EXPECT_EQ(rs.series("elastic/relaxation_steps").back(), inner.back()) << run;
    EXPECT_EQ(rs.series("elastic/bar/constraint_force").back(),
              rr.series("elastic/bar/constraint_force").back())
        << run;
  }
}

// A porous elastic body (Material.porous, ElasticBody.concentration_holds; docs/porous_media.md)
// under quasi-static loading: the diffusion runs before the relaxation in the same phase, from the
// lists of the last search, and the held particles are found by their reference position, so the
// saturation and the pore pressure it gives are the same on any rank count and across a resume.
// The thesis' porous beam of cases/porous_beam_2d.textproto shortened to 1.25 mm (40 columns),
// 6 load steps of 0.5 s (the droplet on for the first 1 s), on 1/2/4 ranks and resumed from
// load step 3.
TEST(RankConsistency, PorousBeamAcrossRanksAndResume) {
  v1::Case c = test::load_case("porous_beam_2d");
  const double dp = c.dx(), L = 40 * dp;
  auto* beam = c.mutable_elastic_bodies(0);
  beam->mutable_shape()->mutable_box()->mutable_hi()->set_x(L + 3 * dp);
  beam->mutable_constraints(1)->mutable_region()->mutable_box()->mutable_lo()->set_x(L);
  auto* hold = beam->mutable_concentration_holds(0);
  hold->mutable_region()->mutable_box()->mutable_lo()->set_x(0.35 * L);
  hold->mutable_region()->mutable_box()->mutable_hi()->set_x(0.65 * L);
  hold->set_end_time(1.0);
  for (auto& p : *beam->mutable_observation_points()) p.set_x(19.5 * dp);
  c.mutable_time()->set_end_time(3.0);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_rank_counts("porous_beam", c, 6, false);
  check_resume("porous_beam", c, 6, 3);
  if (world_rank() != 0) return;
  const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_porous_beam_";
  test::ResultReader rr(base + "resume_reference/result.h5");
  const auto deflection = rr.series("elastic/beam/displacement");  // 2 points x 2 per row
  const double inner = rr.series("elastic/relaxation_steps").back();
  std::printf("porous beam: centre deflection %.3g m after 6 load steps, %.0f inner steps\n",
              deflection[deflection.size() - 3], inner);
  EXPECT_GT(std::abs(deflection[deflection.size() - 3]), 1e-7);  // it bends
  for (const char* run : {"1/result.h5", "2/result.h5", "4/result.h5", "resume_resumed_1/result.h5",
                          "resume_resumed_4/result.h5"}) {
    test::ResultReader rs(base + run);
    EXPECT_EQ(rs.series("elastic/relaxation_steps").back(), inner) << run;
    EXPECT_EQ(rs.series("elastic/beam/displacement"), deflection) << run;
    // A plain MPI sum (solver/physics/scalar_transport.h), not an exact one: equal to round-off.
    const auto mass = rs.series("diagnostics/species_mass");
    const auto mass_ref = rr.series("diagnostics/species_mass");
    ASSERT_EQ(mass.size(), mass_ref.size()) << run;
    for (std::size_t k = 0; k < mass.size(); ++k)
      EXPECT_NEAR(mass[k], mass_ref[k], 1e-12 * mass_ref[k]) << run;
  }
  // After the droplet leaves (t = 1 s) the beam keeps its water: its free surfaces are closed.
  const auto mass = rr.series("diagnostics/species_mass");
  EXPECT_NEAR(mass.back(), mass[2], 1e-12 * mass[2]);
}

// The single-precision pair kernel across a resume: the values are rounded from each pair's
// distance whenever the lists are refined (the checkpoint carries where the particles were
// searched, not the values), so the resumed runs must round exactly as the uninterrupted one.
// The dam break with Verlet lists (the default skin), checkpoint at step 301.
TEST(RankConsistency, CompactPairKernelResumesFromCheckpointOnAnyRankCount) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.05);
  c.set_pair_kernel_storage(v1::PAIR_KERNEL_COMPACT);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("compact", c, 600, 301);
}

// Density diffusion (solver/physics/density_diffusion.h): the term reads the neighbours'
// density before the continuity equation and refreshes the ghosts' density after it, so the
// continuity sums see the same values on every rank. The dam break with the hydrostatic
// (Fourtakas) form, 1200 steps (t = 0.7, the column collapsing), on 1/2/4 ranks
// and resumed on 1 and 4 ranks from a checkpoint at step 601.
TEST(RankConsistency, DensityDiffusionAcrossRanksAndResume) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.05);  // 400 fluid particles
  c.mutable_fluid_model()->mutable_density_diffusion()->set_form(v1::DensityDiffusion::FOURTAKAS);
  check_rank_counts("density_diffusion", c, 1200);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("density_diffusion", c, 1200, 601);
}

// Riemann dissipation (solver/physics/riemann_dissipation.h) in the continuity and the
// momentum equation: the continuity term reads the neighbours' pressure and density before the
// continuity equation and refreshes the ghosts' density after it; the momentum term reads the
// ghosts' velocity and density of the force pass. The dam break without artificial viscosity
// (the limited momentum term stands in for it), 1200 steps, on 1/2/4 ranks and resumed on 1
// and 4 ranks from a checkpoint at step 601. The case keeps the double pair kernel table by
// default (case/estimate.cc); the single-precision one, which the same passes read through
// their compact form, is run on 1/2/4 ranks too.
TEST(RankConsistency, RiemannDissipationAcrossRanksAndResume) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.05);  // 400 fluid particles
  c.mutable_fluid_model()->set_artificial_viscosity(0);
  c.mutable_fluid_model()->mutable_riemann_dissipation()->set_scope(
      v1::RiemannDissipation::CONTINUITY_AND_MOMENTUM);
  check_rank_counts("riemann_dissipation", c, 1200);
  auto compact = c;
  compact.set_pair_kernel_storage(v1::PAIR_KERNEL_COMPACT);
  check_rank_counts("riemann_dissipation_compact", compact, 1200);
  if (world_rank() == 0) {
    const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_riemann_dissipation";
    const double d = max_relative_difference(read_last(base + "_1/result.h5"),
                                             read_last(base + "_compact_1/result.h5"));
    std::printf(
        "riemann dissipation, compact vs table pair kernel after 1200 steps: max relative "
        "difference %.3g\n",
        d);
    EXPECT_LT(d, 1e-5);  // rounding of W and dW/dr to single precision, not a different scheme
  }
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("riemann_dissipation", c, 1200, 601);
}

v1::Contact parse_contact(const std::string& text) {
  return parse_case_text("contact { " + text + " }").contact();
}

// Two disks thrown at a bar pinned at its centre in a closed water box, with impulse contact
// (RESTITUTION, e = 0.5) and friction: the candidate pairs gathered from every rank, the
// impulses on the replicated body table, and the pinned bar turning while its centre stays.
v1::Case disks_striking_a_pinned_bar() {
  return parse_case_text(R"(
    dimension: 2 dx: 0.02
    domain { lo { x: -0.06 y: -0.06 } hi { x: 0.66 y: 0.66 } }
    materials { name: "water" density: 1000 eos { sound_speed: 4 } kinematic_viscosity: 1e-3 }
    materials { name: "s" phase: SOLID density: 2000 }
    fluids { name: "w" material: "water" shape { box { lo { x: 0 y: 0 } hi { x: 0.6 y: 0.6 } } } }
    walls { name: "box" shape { shell { inner { box { lo { x: 0 y: 0 } hi { x: 0.6 y: 0.6 } } } } } }
    bodies { name: "bar" material: "s" motion_type: PINNED
             shape { box { lo { x: 0.28 y: 0.16 } hi { x: 0.32 y: 0.44 } } }
             initial_angular_velocity { z: 0.5 } }
    bodies { name: "left" material: "s" shape { ball { center { x: 0.225 y: 0.38 } radius: 0.05 } }
             initial_velocity { x: 0.6 } }
    bodies { name: "right" material: "s" shape { ball { center { x: 0.375 y: 0.22 } radius: 0.05 } }
             initial_velocity { x: -0.6 } }
    contact { model: RESTITUTION restitution: 0.5 friction { coefficient: 0.2 } }
    gravity { acceleration { y: -1 } }
    fluid_model { density: SUMMATION }
    time { end_time: 10 }
    output { series_interval: 1e-6 })");
}

TEST(RankConsistency, RestitutionContactWithAPinnedBodyAcrossRanksAndResume) {
  const v1::Case c = disks_striking_a_pinned_bar();
  check_rank_counts("restitution", c, 400);
  if (world_rank() == 0) {
    const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_restitution_";
    test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
    expect_same_series(r1, r4,
                       {"bodies/position", "bodies/velocity", "bodies/angular_velocity",
                        "bodies/contact_force", "bodies/contacts"});
    const auto contacts = r1.series("bodies/contacts"), pos = r1.series("bodies/position");
    double hits = 0, bar_moved = 0;
    for (std::size_t k = 0; k < contacts.size(); k += 3) hits = std::max(hits, contacts[k]);
    for (std::size_t k = 0; k < pos.size(); k += 6)
      bar_moved = std::max({bar_moved, std::abs(pos[k] - pos[0]), std::abs(pos[k + 1] - pos[1])});
    std::printf("pinned bar: most contacts at once %.0f, its centre moved by %.1e\n", hits,
                bar_moved);
    EXPECT_GT(hits, 0.0);  // the disks did strike it
    EXPECT_EQ(bar_moved, 0.0);
  }
  // Contacts at steps 0, 1, 16, and from 212 on (a disk rattling between the bar and the
  // floor): the resume at 250 continues among them.
  check_resume("restitution", c, 400, 250);
}

TEST(RankConsistency, RepulsionAndDampingFromRestitutionAcrossRanks) {
  // The same scene with the particle-pair laws that read the body table inside the force
  // loop: Glowinski's repulsion (range dx/2) and the spring-dashpot whose dashpot each pair
  // takes from the two bodies' reduced mass (restitution 0.5).
  for (const char* contact : {"model: REPULSIVE repulsion { strength: 50 range: 0.01 }",
                              "stiffness: 1e4 restitution: 0.5"}) {
    v1::Case c = disks_striking_a_pinned_bar();
    c.clear_contact();
    c.mutable_contact()->MergeFrom(parse_contact(contact));
    const std::string name = c.contact().model() == v1::REPULSIVE ? "repulsion" : "damping_from_e";
    check_rank_counts(name, c, 300);
    if (world_rank() != 0) continue;
    const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_" + name + "_";
    test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
    expect_same_series(r1, r4, {"bodies/position", "bodies/velocity", "bodies/contact_force"});
    const auto contacts = r1.series("bodies/contacts");
    EXPECT_GT(*std::max_element(contacts.begin(), contacts.end()), 0.0) << name;
  }
}

// Particle shifting (solver/physics/particle_shifting.h): the shift reads the neighbours'
// velocity after the closing kick (refreshed on the ghosts) and their concentration
// gradients (refreshed between its two passes), and moves the particles after every shift is
// computed, so it is the same on any rank count. The dam break with density diffusion and
// shifting at the largest fluid speed (MAXIMUM, every particle shifts), 1200 steps (t = 0.7,
// the column collapsing, its surface shifted tangentially), on 1/2/4 ranks and resumed on 1 and
// 4 ranks from a checkpoint at step 601.
TEST(RankConsistency, ParticleShiftingAcrossRanksAndResume) {
  auto c = test::load_case("dambreak_2d");
  c.set_dx(0.05);  // 400 fluid particles
  c.mutable_fluid_model()->mutable_density_diffusion()->set_form(v1::DensityDiffusion::FOURTAKAS);
  c.mutable_fluid_model()->mutable_particle_shifting()->set_speed(v1::ParticleShifting::MAXIMUM);
  check_rank_counts("particle_shifting", c, 1200);
  c.mutable_output()->set_series_interval(1e-12);  // every step: rows after the checkpoint
  check_resume("particle_shifting", c, 1200, 601);
}

// A wall growing into a driven channel flow (solver/boundaries/wall_growth.h): every fluid
// particle the front passes becomes a wall particle where it stands, and a disk carried by
// the flow (inelastic hard-body contact, as Reder's) is engulfed when the front reaches it
// (about step 560; the contact lists are refreshed without it), on 1/2/4 ranks, and
// resumed on 1 and 4 ranks from a checkpoint at step 600 (the emptied body slot and the
// grown totals in it).
v1::Case floor_growing_under_a_disk() {
  v1::Case c = parse_case_text(test::growing_floor(0.4, 10, R"(
    bodies { name: "disk" material: "solid" shape { ball { center { x: 0.2 y: 0.3 } radius: 0.1 } } }
    contact { model: RESTITUTION restitution: 0 }
    body_force { x: 1 })"));
  c.mutable_output()->set_series_interval(1e-12);
  return c;
}

TEST(RankConsistency, GrowingWallEngulfingADiskAcrossRanksAndResume) {
  const v1::Case c = floor_growing_under_a_disk();
  check_rank_counts("wall_growth", c, 800);
  if (world_rank() == 0) {
    const std::string base = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_wall_growth_";
    test::ResultReader r1(base + "1/result.h5"), r4(base + "4/result.h5");
    expect_same_series(r1, r4,
                       {"wall_growth/floor/particles", "wall_growth/floor/mass",
                        "wall_growth/engulfed_bodies", "bodies/position", "bodies/velocity"});
    const auto grown = r1.series("wall_growth/floor/particles");
    const auto engulfed = r1.series("wall_growth/engulfed_bodies");
    std::printf("growing floor: %.0f particles taken, %.0f body engulfed after 800 steps\n",
                grown.back(), engulfed.back());
    EXPECT_GT(grown.back(), 0.0);
    EXPECT_EQ(engulfed.back(), 1.0);
  }
  check_resume("wall_growth", c, 800, 600);
  if (world_rank() != 0) return;
  const std::string dir = std::string(SPHD_BINARY_DIR) + "/test-output/mpi_wall_growth_resume_";
  test::ResultReader rr(dir + "reference/result.h5");
  for (int ranks : {4, 1}) {
    test::ResultReader rs(dir + "resumed_" + std::to_string(ranks) + "/result.h5");
    // Cumulative totals continue across the resume.
    expect_same_series(
        rr, rs,
        {"wall_growth/floor/particles", "wall_growth/floor/mass", "wall_growth/engulfed_bodies"});
  }
}

}  // namespace
}  // namespace sph
