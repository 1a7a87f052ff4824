#pragma once
// The bounds of case/case_limits.h, checked before anything else looks at a case: validation,
// estimation and the scene builder recurse over shapes, loop over lattice indices and copy
// names into messages, and may only do so on a case that keeps them. Every walk here is
// iterative, so it is safe on a shape tree of any depth.
#include <cstdint>
#include <vector>

#include "case/validate.h"
#include "sph/v1/case.pb.h"

namespace sph {

// What one shape tree holds, measured without recursion.
struct ShapeTreeSize {
  int depth = 0;  // 1 for a primitive, 1 + the deepest part for a combination
  int shapes = 0;
  int polygon_vertices = 0;
  int points = 0;                   // explicit points of point sets
  std::int64_t mesh_triangles = 0;  // triangles of meshes
  std::int64_t grid_nodes = 0;      // values of signed-distance grids
};
ShapeTreeSize measure_shape(const v1::Shape& s);

// "shapes nest 4000 deep; the limit is 32" when `depth` exceeds kMaxShapeDepth, else "".
std::string shape_depth_error(int depth);

// Errors for every bound the case breaks: string lengths, numbers that are not finite (NaN,
// infinities), counts of repeated parts, shape
// depth and count, points, and the lattice range of dx, domain and lattice_origin. A case with
// any of these errors must not be validated further.
std::vector<FieldError> check_case_bounds(const v1::Case& c);

// A number for limit messages: integers below 1e6 written out ("406"), others with three
// significant digits and a plain exponent ("3.1e8", "1e-300").
std::string count_text(double v);

}  // namespace sph
