#include "solver/parallel/decomposition.h"

#include <numeric>
#include <stdexcept>

namespace sph {

template <int D>
Decomposition<D>::Decomposition(const CellGrid<D>& grid, int ranks,
                                const std::vector<std::int64_t>& counts)
    : boxes_(static_cast<size_t>(ranks)) {
  CellBox<D> all;
  for (int a = 0; a < D; ++a) all.hi[a] = grid.n[a];
  build(grid, counts, all, 0, ranks);
}

template <int D>
int Decomposition<D>::build(const CellGrid<D>& grid, const std::vector<std::int64_t>& counts,
                            CellBox<D> box, int r0, int r1) {
  const int me = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  if (r1 - r0 == 1) {
    nodes_[me].rank = r0;
    boxes_[static_cast<size_t>(r0)] = box;
    return me;
  }
  // Split the longest axis that still has at least two cells.
  int axis = -1;
  for (int a = 0; a < D; ++a)
    if (box.hi[a] - box.lo[a] >= 2 && (axis < 0 || box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]))
      axis = a;
  if (axis < 0) throw std::runtime_error("domain has fewer cells than ranks: use fewer ranks");
  // Particle count per slab along `axis` within the box.
  const int len = box.hi[axis] - box.lo[axis];
  std::vector<double> slab(static_cast<size_t>(len), 0.0);
  ICoord<D> c = box.lo;
  const long long cells = box.cells();
  for (long long k = 0; k < cells; ++k) {
    // +1 per cell keeps empty regions from collapsing a split onto one side.
    slab[static_cast<size_t>(c[axis] - box.lo[axis])] +=
        static_cast<double>(counts[static_cast<size_t>(grid.linear(c))]) + 1e-3;
    for (int a = 0; a < D; ++a) {
      if (++c[a] < box.hi[a]) break;
      c[a] = box.lo[a];
    }
  }
  const int nl = (r1 - r0) / 2;
  const double total = std::accumulate(slab.begin(), slab.end(), 0.0);
  const double target = total * nl / (r1 - r0);
  // Choose the split with the smallest imbalance; leave >= 1 slab per side.
  double acc = 0, best = 1e300;
  int split = box.lo[axis] + 1;
  for (int s = 1; s < len; ++s) {
    acc += slab[static_cast<size_t>(s - 1)];
    const double err = std::abs(acc - target);
    if (err < best) {
      best = err;
      split = box.lo[axis] + s;
    }
  }
  CellBox<D> lb = box, rb = box;
  lb.hi[axis] = split;
  rb.lo[axis] = split;
  nodes_[me].axis = axis;
  nodes_[me].split = split;
  const int l = build(grid, counts, lb, r0, r0 + nl);
  const int r = build(grid, counts, rb, r0 + nl, r1);
  nodes_[me].left = l;
  nodes_[me].right = r;
  return me;
}

template <int D>
int Decomposition<D>::owner(const ICoord<D>& c) const {
  int n = 0;
  while (nodes_[static_cast<size_t>(n)].axis >= 0) {
    const Node& nd = nodes_[static_cast<size_t>(n)];
    n = c[nd.axis] < nd.split ? nd.left : nd.right;
  }
  return nodes_[static_cast<size_t>(n)].rank;
}

template class Decomposition<2>;
template class Decomposition<3>;

}  // namespace sph
