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
  // Try every axis with at least two cell slabs and keep the split closest to the target
  // share (the longest axis wins near-ties, which keeps boxes compact). Trying all axes
  // matters when the particles pile up: a water column at a wall is split across its height.
  const int nl = (r1 - r0) / 2;
  struct Candidate {
    int axis, split, len;
    double err;  // |share - target| / total
  };
  std::vector<Candidate> cands;
  for (int a = 0; a < D; ++a) {
    const int len = box.hi[a] - box.lo[a];
    if (len < 2) continue;
    std::vector<double> slab(static_cast<size_t>(len), 0.0);
    ICoord<D> c = box.lo;
    const long long cells = box.cells();
    for (long long k = 0; k < cells; ++k) {
      // A small weight per cell keeps empty regions from collapsing a split onto one side.
      slab[static_cast<size_t>(c[a] - box.lo[a])] +=
          static_cast<double>(counts[static_cast<size_t>(grid.linear(c))]) + 1e-3;
      for (int b = 0; b < D; ++b) {
        if (++c[b] < box.hi[b]) break;
        c[b] = box.lo[b];
      }
    }
    const double total = std::accumulate(slab.begin(), slab.end(), 0.0);
    const double target = total * nl / (r1 - r0);
    Candidate best{a, box.lo[a] + 1, len, 1e300};
    double acc = 0;
    for (int sp = 1; sp < len; ++sp) {
      acc += slab[static_cast<size_t>(sp - 1)];
      const double err = std::abs(acc - target) / total;
      if (err < best.err) {
        best.err = err;
        best.split = box.lo[a] + sp;
      }
    }
    cands.push_back(best);
  }
  int axis = -1, split = 0;
  if (!cands.empty()) {
    double min_err = 1e300;
    for (const auto& c : cands) min_err = std::min(min_err, c.err);
    int best_len = -1;
    for (const auto& c : cands)
      if (c.err <= min_err + 0.005 && c.len > best_len) {
        best_len = c.len;
        axis = c.axis;
        split = c.split;
      }
  }
  if (axis < 0)
    throw std::runtime_error(
        "domain has fewer cells (r_c + neighbor_skin wide) than ranks: use fewer ranks or a "
        "smaller neighbor_skin");
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
