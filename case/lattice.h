#pragma once
// Placing particles: the cell-centred lattice x = origin + (i + 1/2) dx filled inside shapes.
#include <cstdint>
#include <functional>

#include "case/geometry.h"

namespace sph {

struct LatticeSpec {
  int dim = 2;
  double dx = 1.0;
  Point3 origin = Point3::Zero();
};

// Calls fn for every lattice point inside `shape` and inside `clip`, in a fixed order
// (z slowest, x fastest), or for every explicit point of a PointSet inside `clip`.
void for_each_lattice_point(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            const std::function<void(const Point3&)>& fn);

// Number of points for_each_lattice_point would produce; exact below `exact_limit` lattice
// points in the bounding box, otherwise estimated from a coarser sampling lattice.
double count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            double exact_limit = 4e6);

}  // namespace sph
