#pragma once
// Recursive coordinate bisection of the global cell grid into one box per rank, balanced by
// particle count. Every rank computes the same boxes from the same global histogram, so no
// further communication is needed to know who owns a cell.
#include <cstdint>
#include <vector>

#include "solver/core/cell_grid.h"

namespace sph {

template <int D>
class Decomposition {
 public:
  Decomposition() = default;
  // counts: particles per global cell (linear index, CellGrid::linear), length grid.total().
  Decomposition(const CellGrid<D>& grid, int ranks, const std::vector<std::int64_t>& counts);

  const CellBox<D>& box(int rank) const { return boxes_[static_cast<size_t>(rank)]; }
  int ranks() const { return static_cast<int>(boxes_.size()); }
  // Owner of a canonical (wrapped / clamped) cell.
  int owner(const ICoord<D>& c) const;

 private:
  struct Node {
    int axis = -1;  // -1: leaf
    int split = 0;  // cells with c[axis] < split go left
    int left = -1, right = -1;
    int rank = -1;
  };
  int build(const CellGrid<D>& grid, const std::vector<std::int64_t>& counts, CellBox<D> box,
            int r0, int r1);
  std::vector<CellBox<D>> boxes_;
  std::vector<Node> nodes_;
};

}  // namespace sph
