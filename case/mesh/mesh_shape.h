#pragma once
// A closed triangulated surface as a case shape: signed distance to the nearest triangle, with
// inside decided by the winding number of a ray, both over a bounding-volume hierarchy.
#include <cstdint>
#include <vector>

#include "case/geometry.h"
#include "case/mesh/triangle_mesh.h"

namespace sph {

class MeshShape final : public Shape {
 public:
  // distance() is exact within `exact_within` of the surface; farther away it returns a value
  // of the right sign whose magnitude is at most the true distance (the lattice fill and the
  // boolean combinations need only the sign there), which saves the nearest-triangle search.
  explicit MeshShape(TriangleMesh mesh, double exact_within = 1e300);
  double distance(const Point3& p) const override;
  Aabb bounds() const override { return nodes_.empty() ? Aabb{} : nodes_[0].box; }
  double cost() const override;
  // The winding number of the surface around p: +-1 inside a closed surface (the sign is its
  // orientation), 0 outside.
  int winding_number(const Point3& p) const;
  // Distance from p to the nearest point of the surface, or `cap` when that is farther.
  double unsigned_distance(const Point3& p, double cap = 1e300) const;

 private:
  struct Node {
    Aabb box;
    std::uint32_t first = 0, count = 0;  // a leaf's triangles: order_[first, first + count)
    std::uint32_t left = 0, right = 0;   // an inner node's children (count == 0)
  };
  std::uint32_t build(std::uint32_t first, std::uint32_t count,
                      const std::vector<Point3>& centroids);
  int crossing(std::uint32_t tri, const Point3& p) const;

  TriangleMesh mesh_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
  double exact_within_;
};

}  // namespace sph
