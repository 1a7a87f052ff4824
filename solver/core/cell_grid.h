#pragma once
// The global cell lattice over the computational domain. It is the same on every rank, so
// subdomains are sets of whole cells and the neighbour order (cell by cell, ids ascending
// within a cell) does not depend on the decomposition: results are identical for any rank
// count. Cells are at least r_c wide, so all neighbours of a particle lie in the 3^D block of
// cells around it (Fuchs 2021, "Parallelization via spatial decomposition").
#include <algorithm>
#include <array>
#include <cmath>

#include "solver/core/types.h"

namespace sph {

template <int D>
using ICoord = std::array<int, D>;

template <int D>
struct CellGrid {
  Vec<D> lo;      // domain lower corner
  Vec<D> length;  // domain extent
  Vec<D> cell;    // cell size (>= r_c) along each axis
  ICoord<D> n{};  // cells along each axis
  std::array<bool, D> periodic{};

  CellGrid() = default;
  CellGrid(const Vec<D>& lo_, const Vec<D>& hi_, double rc, const std::array<bool, D>& per)
      : lo(lo_), length(hi_ - lo_), periodic(per) {
    for (int a = 0; a < D; ++a) {
      n[a] = std::max(1, static_cast<int>(std::floor(length[a] / rc * (1 + 1e-12))));
      cell[a] = length[a] / n[a];
    }
  }

  // Cell coordinate of a position; clamped to [-1, n] (the ghost layer) so that a corrupted
  // position (NaN, far outside) cannot index out of bounds: the stability guard reports it.
  ICoord<D> coord(const Vec<D>& x) const {
    ICoord<D> c;
    for (int a = 0; a < D; ++a) {
      const double f = (x[a] - lo[a]) / cell[a];
      int i = std::isfinite(f) ? static_cast<int>(std::floor(std::clamp(f, -2.0, n[a] + 1.0))) : 0;
      c[a] = std::clamp(i, -1, n[a]);
    }
    return c;
  }
  // The cell a particle is binned in for neighbour search: non-periodic axes clamped into
  // [0, n), so that a wall particle on or beyond the domain's edge sits in the same cell
  // (hence the same place in the canonical neighbour order) whether it is owned or a ghost;
  // periodic images keep their cell outside [0, n).
  ICoord<D> bin(const Vec<D>& x) const {
    ICoord<D> c = coord(x);
    for (int a = 0; a < D; ++a)
      if (!periodic[a]) c[a] = std::clamp(c[a], 0, n[a] - 1);
    return c;
  }
  // The half cell (each cell split in two along every axis) of a position for the neighbour
  // search, clamped like bin(): half cell h lies in cell floor(h / 2) = bin(x).
  ICoord<D> half_bin(const Vec<D>& x) const {
    ICoord<D> c;
    for (int a = 0; a < D; ++a) {
      const double f = (x[a] - lo[a]) / cell[a];
      int i =
          std::isfinite(f) ? static_cast<int>(std::floor(2 * std::clamp(f, -2.0, n[a] + 1.0))) : 0;
      c[a] = periodic[a] ? std::clamp(i, -2, 2 * n[a] + 1) : std::clamp(i, 0, 2 * n[a] - 1);
    }
    return c;
  }
  // Wraps periodic axes into [0, n) and clamps the others.
  ICoord<D> canonical(ICoord<D> c) const {
    for (int a = 0; a < D; ++a) {
      if (periodic[a])
        c[a] = ((c[a] % n[a]) + n[a]) % n[a];
      else
        c[a] = std::clamp(c[a], 0, n[a] - 1);
    }
    return c;
  }
  long long total() const {
    long long t = 1;
    for (int a = 0; a < D; ++a) t *= n[a];
    return t;
  }
  long long linear(const ICoord<D>& c) const {
    long long i = 0;
    for (int a = D - 1; a >= 0; --a) i = i * n[a] + c[a];
    return i;
  }
};

// A box of cells [lo, hi) in global cell coordinates.
template <int D>
struct CellBox {
  ICoord<D> lo{}, hi{};
  bool contains(const ICoord<D>& c) const {
    for (int a = 0; a < D; ++a)
      if (c[a] < lo[a] || c[a] >= hi[a]) return false;
    return true;
  }
  bool empty() const {
    for (int a = 0; a < D; ++a)
      if (hi[a] <= lo[a]) return true;
    return false;
  }
  long long cells() const {
    long long t = 1;
    for (int a = 0; a < D; ++a) t *= std::max(0, hi[a] - lo[a]);
    return t;
  }
};

}  // namespace sph
