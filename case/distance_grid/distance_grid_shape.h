#pragma once
// A shape given by a signed distance sampled on a regular grid (proto DistanceGrid): the
// distance at a point is interpolated between the nodes of its grid cell, bilinearly in 2D and
// trilinearly in 3D, so the zero level between two nodes of opposite sign lies where the linear
// interpolant vanishes and a surface is placed to within O(spacing^2 kappa) of where the field
// puts it. Outside the grid is outside the shape.
#include <cstdint>
#include <vector>

#include "case/geometry.h"
#include "sph/v1/case.pb.h"

namespace sph {

class DistanceGridShape final : public Shape {
 public:
  // `g` is validated: counts match the values and the case's dimension `dim`.
  DistanceGridShape(const v1::DistanceGrid& g, int dim);
  double distance(const Point3& p) const override;
  // The cells that hold a negative node, and one cell around them: where the inside can be.
  Aabb bounds() const override { return inside_; }
  double cost() const override { return 2; }

 private:
  double node(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return values_[static_cast<std::size_t>((k * n_[1] + j) * n_[0] + i)];
  }

  int dim_;
  std::int64_t n_[3] = {1, 1, 1};
  Point3 origin_;
  double spacing_;
  std::vector<double> values_;  // scaled, x fastest
  Aabb grid_, inside_;
};

}  // namespace sph
