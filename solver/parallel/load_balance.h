#pragma once
// Load balancing by work, not by particle count: fluid and rigid particles run every pair
// loop, while a wall particle only takes part in the neighbour search and, next to fluid, the
// wall condition. A scene is often mostly wall (a 3D tank), so balancing raw counts would
// leave one rank with all the fluid. Integer weights keep the histogram sums exact, so every
// rank computes the same decomposition.
#include <cstdint>
#include <vector>

#include "solver/core/cell_grid.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "solver/parallel/decomposition.h"

namespace sph {

inline std::int64_t work_weight(Kind k) {
  return k == Kind::kWall ? 1 : 10;
}

// Work of the owned particles per global cell (every rank's share; sum them for the whole).
template <int D>
std::vector<std::int64_t> work_histogram(const ParticleStore<D>& s, const CellGrid<D>& grid) {
  std::vector<std::int64_t> counts(static_cast<std::size_t>(grid.total()), 0);
  for (std::size_t i = 0; i < s.owned(); ++i)
    counts[static_cast<std::size_t>(grid.linear(grid.canonical(grid.coord(s.x[i]))))] +=
        work_weight(s.kind[i]);
  return counts;
}

// The decomposition that balances the owned particles' work over the ranks (collective).
template <int D>
Decomposition<D> balanced_decomposition(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                        const Comm& comm) {
  std::vector<std::int64_t> counts = work_histogram(s, grid);
  comm.sum_inplace(counts);
  return Decomposition<D>(grid, comm.size(), counts);
}

// The largest rank's work over the mean (1: balanced; collective).
template <int D>
double work_imbalance(const ParticleStore<D>& s, const Comm& comm) {
  std::int64_t local = 0;
  for (std::size_t i = 0; i < s.owned(); ++i) local += work_weight(s.kind[i]);
  const std::int64_t total = comm.sum(local), max = comm.max(local);
  return total > 0 ? static_cast<double>(max) * comm.size() / static_cast<double>(total) : 1.0;
}

// Rebalance when the largest rank does more than this share above the mean.
inline constexpr double kRebalanceImbalance = 1.05;
// Steps between imbalance checks.
inline constexpr std::int64_t kRebalanceEvery = 20;

}  // namespace sph
