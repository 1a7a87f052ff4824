// The interface-sharpness diagnostic (solver/diagnostics/phase_mixing.h) on lattices whose
// answer is known by construction: two fluid phases layered in a periodic box have no stray
// particle and four rows of interface particles per interface (two on each side); particles of one
// phase planted in the bulk of the other are each counted as stray; a particle of one phase on a
// solid surface, with the other phase around it, is not.
#include <gtest/gtest.h>

#include <functional>

#include "solver/core/kernel.h"
#include "solver/diagnostics/phase_mixing.h"
#include "solver/parallel/halo.h"

namespace sph {
namespace {

// A power of two, so that lattice distances and r_c are exact: a pair exactly r_c apart (three
// rows across an interface) stays out of the neighbour list.
constexpr double kDx = 0.125;
constexpr int kColumns = 20, kRows = 24;

// A periodic kColumns x kRows lattice; `setup(column, row, kind, material)` sets each particle
// (fluid material 0 has density 1, 1 has 0.01: a volume of dx^2 either way, as the scan takes it
// from m / rho).
PhaseMixingScan scan_lattice(const std::function<void(int, int, Kind&, std::uint16_t&)>& setup) {
  const QuinticSpline<2> kernel(kDx);
  const double rc = kernel.support_radius();
  CellGrid<2> grid(Vec<2>(0, 0), Vec<2>(kColumns * kDx, kRows * kDx), rc, {true, true});
  Comm comm(MPI_COMM_WORLD);
  Halo<2> halo(grid, comm);
  std::vector<std::int64_t> counts(static_cast<size_t>(grid.total()), 1);
  halo.set_decomposition(Decomposition<2>(grid, 1, counts));
  ParticleStore<2> s;
  const std::size_t n = kColumns * kRows;
  s.resize(n, n);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      const auto i = static_cast<std::size_t>(r * kColumns + c);
      s.x[i] = Vec<2>((c + 0.5) * kDx, (r + 0.5) * kDx);
      s.id[i] = static_cast<ParticleId>(i);
      Kind kind = Kind::kFluid;
      std::uint16_t material = 0;
      setup(c, r, kind, material);
      s.kind[i] = kind;
      s.material[i] = material;
      s.rho[i] = material == 0 ? 1.0 : 0.01;
      s.m[i] = s.rho[i] * kDx * kDx;
    }
  halo.migrate(s);
  halo.build_ghosts(s);
  NeighborList<2> nl;
  nl.build(s, grid, halo.ghost_box(), rc);
  PairKernel<2> pk;
  pk.prepare(s, nl, kernel);
  return phase_mixing<2>(s, nl, pk, kernel.W(0.0), kDx * kDx);
}

TEST(PhaseMixing, LayeredPhasesHaveNoStrayParticle) {
  // Rows 0-11 material 0, 12-23 material 1: two interfaces (one across the periodic edge).
  const auto scan = scan_lattice([](int, int r, Kind&, std::uint16_t& m) { m = r < 12 ? 0 : 1; });
  EXPECT_EQ(scan.stray, 0u);
  // With r_c = 3 dx, the rows 0.5 and 1.5 dx from an interface reach across it, 2.5 dx do not.
  EXPECT_EQ(scan.interface, static_cast<std::size_t>(2 * 4 * kColumns));
}

TEST(PhaseMixing, ParticlesPlantedInTheOtherPhaseAreStray) {
  // Three particles of material 1 deep in material 0 and two of material 0 deep in material 1,
  // their neighbourhoods (the 5 x 5 lattice points around each, all nearer than r_c = 3 dx)
  // apart from one another and from the interface rows.
  const auto scan = scan_lattice([](int c, int r, Kind&, std::uint16_t& m) {
    m = r < 12 ? 0 : 1;
    if (r == 6 && (c == 2 || c == 8 || c == 14)) m = 1;
    if (r == 18 && (c == 3 || c == 11)) m = 0;
  });
  EXPECT_EQ(scan.stray, 5u);
  EXPECT_EQ(scan.interface, static_cast<std::size_t>(2 * 4 * kColumns + 5 * 25));
}

TEST(PhaseMixing, AParticleOnAGrainIsNotStrayButTheSameInTheGasIs) {
  // Rows 0-9 rigid dummies (a grain); in row 10, two particles of material 0 (melt, 10 dx
  // apart) with gas (material 1) beside and above them. The grain fills 22% of their kernel
  // support, the gas 47%: not stray. Without the grain, gas fills 69%: stray.
  const auto on_grain = scan_lattice([](int c, int r, Kind& k, std::uint16_t& m) {
    k = r < 10 ? Kind::kRigid : Kind::kFluid;
    m = r == 10 && (c == 5 || c == 15) ? 0 : 1;
  });
  EXPECT_EQ(on_grain.stray, 0u);
  const auto in_gas = scan_lattice(
      [](int c, int r, Kind&, std::uint16_t& m) { m = r == 10 && (c == 5 || c == 15) ? 0 : 1; });
  EXPECT_EQ(in_gas.stray, 2u);
}

}  // namespace
}  // namespace sph
