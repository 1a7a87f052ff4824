#pragma once
// Geometry of case shapes: primitives and boolean combinations compiled from the proto into
// signed-distance objects (negative inside). Dimension-aware: in 2D the z coordinate is
// ignored. Distances are exact for primitives and conservative (a lower bound outside)
// for combinations, which is what Shell and the lattice fill need.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

using Point3 = Eigen::Vector3d;

struct Aabb {
  Point3 lo = Point3::Constant(1e300);
  Point3 hi = Point3::Constant(-1e300);
  bool empty() const { return (hi.array() < lo.array()).any(); }
  void grow(const Point3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Aabb& b) {
    if (b.empty()) return;
    grow(b.lo);
    grow(b.hi);
  }
  Aabb inflated(double d) const {
    Aabb b = *this;
    if (!empty()) {
      b.lo.array() -= d;
      b.hi.array() += d;
    }
    return b;
  }
  Aabb intersected(const Aabb& o) const {
    Aabb b;
    b.lo = lo.cwiseMax(o.lo);
    b.hi = hi.cwiseMin(o.hi);
    return b;
  }
};

class Shape {
 public:
  virtual ~Shape() = default;
  // Signed distance: < 0 inside, > 0 outside.
  virtual double distance(const Point3& p) const = 0;
  bool contains(const Point3& p) const { return distance(p) < 0.0; }
  virtual Aabb bounds() const = 0;
  // The work of one distance() call, in units of a box's (at least 1): how validation and
  // estimates budget their lattice walks (case/lattice.h). A polygon costs one unit per
  // vertex, a combination the sum of its parts and one for itself.
  virtual double cost() const = 0;
  // Explicit points (PointSet) replace the lattice fill for this shape.
  virtual const std::vector<Point3>* explicit_points() const { return nullptr; }
};

// Compiles a validated shape. default_shell_thickness is used for Shell without thickness.
std::unique_ptr<Shape> compile_shape(const v1::Shape& s, int dim, double default_shell_thickness);

inline Point3 to_point(const v1::Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace sph
