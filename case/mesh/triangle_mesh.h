#pragma once
// A triangulated surface as cases give it (proto TriangleMesh, read from STL files): its
// vertices, its triangles, the checks that make an inside test meaningful (closed, consistently
// oriented) and its exact mass properties, against which a body filled from it is checked.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The mesh of a validated proto message, with scale and offset applied.
TriangleMesh mesh_from_proto(const v1::TriangleMesh& m);

// Reads a binary or ASCII STL file into `out` (vertices welded: equal coordinates become one
// vertex, so that edges can be matched). At most `max_triangles` triangles: a larger file is
// refused after that many, not read whole. Throws std::runtime_error naming the file and what
// is wrong with it.
void read_stl(const std::string& path, std::size_t max_triangles, v1::TriangleMesh& out);

// How far a mesh is from the closed, consistently oriented surface the inside test needs.
struct MeshTopology {
  std::size_t open_edges = 0;         // edges of one triangle only (a hole)
  std::size_t flipped_edges = 0;      // edges two triangles run in the same direction
  std::size_t nonmanifold_edges = 0;  // edges of more than two triangles
  std::size_t degenerate = 0;         // triangles with a repeated vertex or zero area
  bool closed_and_oriented() const {
    return open_edges == 0 && flipped_edges == 0 && nonmanifold_edges == 0;
  }
};
MeshTopology check_topology(const TriangleMesh& m);

// Volume, centroid and the inertia tensor about the centroid (unit density) of the solid a
// closed mesh bounds, by the divergence theorem over its triangles (Eberly 2002, "Polyhedral
// Mass Properties (Revisited)", after Mirtich 1996). The volume is negative when the triangles
// face inwards.
struct MassProperties {
  double volume = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
MassProperties mass_properties(const TriangleMesh& m);

}  // namespace sph
