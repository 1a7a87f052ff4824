#pragma once
// Load balancing by work, not by particle count: fluid and rigid particles run every pair
// loop, while a wall particle only takes part in the neighbour search and, next to fluid, the
// wall condition. A scene is often mostly wall (a 3D tank), so balancing raw counts would
// leave one rank with all the fluid. Integer weights keep the histogram sums exact, so every
// rank computes the same decomposition.
//
// Before the first search the weights are per kind (work_weight); once neighbour lists exist
// a particle's work is counted from its list (pair_work): the pair loops dominate a step, and
// a particle at a free surface, a wall or a body's edge has fewer pairs than one inside the
// fluid. The coefficients come from measured shares of a step (docs/scaling.md, the section
// of 2026-11-27 evening).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solver/core/cell_grid.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "solver/parallel/decomposition.h"

namespace sph {

inline std::int64_t work_weight(Kind k) {
  return k == Kind::kWall ? 1 : 10;
}

// Work of owned particle i from its neighbour list, in quarter visits of a fluid pair. A
// fluid, rigid or elastic particle visits each of its pairs in the pair kernel, the density
// and the forces, and has per-particle work (state, integration, guards) of about three pair
// visits; a wall particle lists only its fluid neighbours and visits them once, in the wall
// condition, which costs about a quarter of a fluid particle's visit, and is searched, binned
// and scanned like any other (about two pair visits, also with no fluid near).
template <int D>
std::int64_t pair_work(const ParticleStore<D>& s, const NeighborList<D>& nl, std::size_t i) {
  const auto pairs = static_cast<std::int64_t>(nl.end(i) - nl.begin(i));
  return s.kind[i] == Kind::kWall ? 8 + pairs : 12 + 4 * pairs;
}

// The lists to count work from: nl if it lists every owned particle on every rank (the same
// choice everywhere, so every rank computes the same decomposition), else none (by kind).
template <int D>
const NeighborList<D>* work_lists(const ParticleStore<D>& s, const Comm& comm,
                                  const NeighborList<D>* nl) {
  const std::int64_t ok = nl && nl->listed() == s.owned() ? 1 : 0;
  return comm.min(ok) == 1 ? nl : nullptr;
}

// Work of the owned particles per global cell (every rank's share; sum them for the whole):
// from the neighbour lists when given (they must be those of the owned particles now), else
// by kind.
template <int D>
std::vector<std::int64_t> work_histogram(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                         const NeighborList<D>* nl) {
  std::vector<std::int64_t> counts(static_cast<std::size_t>(grid.total()), 0);
  for (std::size_t i = 0; i < s.owned(); ++i)
    counts[static_cast<std::size_t>(grid.linear(grid.canonical(grid.coord(s.x[i]))))] +=
        nl ? pair_work(s, *nl, i) : work_weight(s.kind[i]);
  return counts;
}

// The work of the whole scene per global cell (collective).
template <int D>
std::vector<std::int64_t> global_work_histogram(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                                const Comm& comm, const NeighborList<D>* nl) {
  std::vector<std::int64_t> counts = work_histogram(s, grid, work_lists(s, comm, nl));
  comm.sum_inplace(counts);
  return counts;
}

// The decomposition that balances the owned particles' work over the ranks (collective).
template <int D>
Decomposition<D> balanced_decomposition(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                        const Comm& comm, const NeighborList<D>* nl) {
  return Decomposition<D>(grid, comm.size(), global_work_histogram(s, grid, comm, nl));
}

// The largest box's work over the mean in decomposition d of the global histogram `work`
// (the same on every rank: integer sums).
template <int D>
double decomposition_imbalance(const Decomposition<D>& d, const CellGrid<D>& grid,
                               const std::vector<std::int64_t>& work) {
  std::int64_t total = 0, largest = 0;
  for (int r = 0; r < d.ranks(); ++r) {
    const CellBox<D>& b = d.box(r);
    std::int64_t sum = 0;
    ICoord<D> c = b.lo;
    for (long long k = 0; k < b.cells(); ++k) {
      sum += work[static_cast<std::size_t>(grid.linear(c))];
      for (int a = 0; a < D; ++a) {
        if (++c[a] < b.hi[a]) break;
        c[a] = b.lo[a];
      }
    }
    total += sum;
    largest = std::max(largest, sum);
  }
  return total > 0 ? static_cast<double>(largest) * d.ranks() / static_cast<double>(total) : 1.0;
}

// The largest rank's work over the mean (1: balanced; collective), counted as
// work_histogram() counts it.
template <int D>
double work_imbalance(const ParticleStore<D>& s, const Comm& comm, const NeighborList<D>* nl) {
  nl = work_lists(s, comm, nl);
  std::int64_t local = 0;
  for (std::size_t i = 0; i < s.owned(); ++i)
    local += nl ? pair_work(s, *nl, i) : work_weight(s.kind[i]);
  const std::int64_t total = comm.sum(local), max = comm.max(local);
  return total > 0 ? static_cast<double>(max) * comm.size() / static_cast<double>(total) : 1.0;
}

// Rebalance when the largest rank does more than this share above the mean, and a new
// decomposition would lower that by kRebalanceGain at least: a rebalance costs a few steps
// (migration, a search at the reference positions), and cells bound how well bisection can
// balance, so without the second condition a scene that cannot do better than 1.05 would
// rebalance at every check.
inline constexpr double kRebalanceImbalance = 1.05;
inline constexpr double kRebalanceGain = 0.02;
// Steps between imbalance checks.
inline constexpr std::int64_t kRebalanceEvery = 20;

}  // namespace sph
