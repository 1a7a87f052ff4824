// Shapes of fluid regions, walls and bodies (proto Shape): each kind's fields, recursively.
#include "case/validate/validator.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "case/case_limits.h"
#include "case/geometry.h"
#include "case/mesh/triangle_mesh.h"

namespace sph::case_validation {

void Validator::shape(const v1::Shape& s, const std::string& f, bool top) {
  const int d = c_.dimension();
  switch (s.kind_case()) {
    case v1::Shape::KIND_NOT_SET:
      error(f,
            "shape has no kind (box, ball, cylinder, polygon, polar_curve, points, mesh, "
            "distance_grid, union, intersection, difference or shell)");
      break;
    case v1::Shape::kBox: {
      point(s.box().lo(), cat(f, "box.lo"));
      point(s.box().hi(), cat(f, "box.hi"));
      const double lo[3] = {s.box().lo().x(), s.box().lo().y(), s.box().lo().z()};
      const double hi[3] = {s.box().hi().x(), s.box().hi().y(), s.box().hi().z()};
      for (int a = 0; a < d; ++a)
        if (!(hi[a] > lo[a]))
          error(cat(f, std::string("box.hi.") + "xyz"[a]), "must be greater than box.lo");
      break;
    }
    case v1::Shape::kBall:
      point(s.ball().center(), cat(f, "ball.center"));
      positive(s.ball().radius(), cat(f, "ball.radius"));
      extent(s.ball().radius(), cat(f, "ball.radius"));
      break;
    case v1::Shape::kCylinder:
      if (d != 3) error(cat(f, "cylinder"), "only in 3D cases (use ball or box in 2D)");
      point(s.cylinder().base(), cat(f, "cylinder.base"));
      point(s.cylinder().axis(), cat(f, "cylinder.axis"));
      positive(s.cylinder().radius(), cat(f, "cylinder.radius"));
      positive(s.cylinder().length(), cat(f, "cylinder.length"));
      extent(s.cylinder().radius(), cat(f, "cylinder.radius"));
      extent(s.cylinder().length(), cat(f, "cylinder.length"));
      if (s.cylinder().axis().x() == 0 && s.cylinder().axis().y() == 0 &&
          s.cylinder().axis().z() == 0)
        error(cat(f, "cylinder.axis"), "must not be zero");
      break;
    case v1::Shape::kPolygon:
      if (d != 2) error(cat(f, "polygon"), "only in 2D cases");
      if (!s.polygon().file().empty())
        error(cat(f, "polygon.file"),
              "polygon files must be inlined before validation (sphctl and sph-worker do this)");
      else if (s.polygon().vertices_size() < 3)
        error(cat(f, "polygon.vertices"), "needs at least 3 vertices");
      for (int i = 0; i < s.polygon().vertices_size(); ++i)
        if (!point_ok(s.polygon().vertices(i)))
          point(s.polygon().vertices(i), idx(cat(f, "polygon.vertices"), i));
      break;
    case v1::Shape::kPolarCurve: {
      const auto& p = s.polar_curve();
      if (d != 2) error(cat(f, "polar_curve"), "only in 2D cases");
      point(p.center(), cat(f, "polar_curve.center"));
      positive(p.radius(), cat(f, "polar_curve.radius"));
      extent(p.radius(), cat(f, "polar_curve.radius"));
      if (!(std::abs(p.amplitude()) < p.radius()))
        error(cat(f, "polar_curve.amplitude"), "|amplitude| must be less than radius");
      if (p.periods() < 0) error(cat(f, "polar_curve.periods"), "must be >= 0");
      break;
    }
    case v1::Shape::kPoints:
      if (!top) error(cat(f, "points"), "a point set can only be a top-level shape");
      if (!s.points().file().empty())
        error(cat(f, "points.file"),
              "point files must be inlined before validation (sphctl and sph-worker do this)");
      else if (s.points().points_size() == 0)
        error(cat(f, "points.points"), "is empty");
      for (int i = 0; i < s.points().points_size(); ++i)
        if (!point_ok(s.points().points(i)))
          point(s.points().points(i), idx(cat(f, "points.points"), i));
      break;
    case v1::Shape::kMesh:
      mesh(s.mesh(), cat(f, "mesh"));
      break;
    case v1::Shape::kDistanceGrid:
      distance_grid(s.distance_grid(), cat(f, "distance_grid"));
      break;
    case v1::Shape::kUnion:
    case v1::Shape::kIntersection: {
      const bool u = s.kind_case() == v1::Shape::kUnion;
      const auto& l = u ? s.union_() : s.intersection();
      const std::string lf = cat(f, u ? "union.shapes" : "intersection.shapes");
      if (l.shapes_size() == 0) error(lf, "is empty");
      for (int i = 0; i < l.shapes_size(); ++i) shape(l.shapes(i), idx(lf, i), false);
      break;
    }
    case v1::Shape::kDifference:
      if (!s.difference().has_base())
        error(cat(f, "difference.base"), "is required");
      else
        shape(s.difference().base(), cat(f, "difference.base"), false);
      for (int i = 0; i < s.difference().subtract_size(); ++i)
        shape(s.difference().subtract(i), idx(cat(f, "difference.subtract"), i), false);
      break;
    case v1::Shape::kShell:
      if (!s.shell().has_inner())
        error(cat(f, "shell.inner"), "is required");
      else
        shape(s.shell().inner(), cat(f, "shell.inner"), false);
      if (s.shell().has_thickness()) {
        positive(s.shell().thickness(), cat(f, "shell.thickness"));
        extent(s.shell().thickness(), cat(f, "shell.thickness"));
      }
      break;
  }
}

// A mesh must be a closed, consistently oriented surface for its inside to mean anything, and
// should overlap the domain: a mesh far outside it, or far larger or smaller, is most often a
// file in other units than the case.
void Validator::mesh(const v1::TriangleMesh& m, const std::string& f) {
  if (c_.dimension() != 3) {
    error(f, "only in 3D cases (use polygon, or polygon.file, in 2D)");
    return;
  }
  if (!m.file().empty()) {
    error(cat(f, "file"),
          "mesh files must be inlined before validation (sphctl and sph-worker do this)");
    return;
  }
  if (m.has_scale() && !(std::isfinite(m.scale()) && m.scale() > 0)) {
    error(cat(f, "scale"), "must be a finite number > 0");
    return;
  }
  if (!point_ok(m.offset())) {
    point(m.offset(), cat(f, "offset"));
    return;
  }
  if (m.vertices_size() % 3 != 0) {
    error(cat(f, "vertices"), "needs three coordinates a vertex; it has " +
                                  std::to_string(m.vertices_size()) + " numbers");
    return;
  }
  for (int i = 0; i < m.vertices_size(); ++i)
    if (!std::isfinite(m.vertices(i))) {
      error(idx(cat(f, "vertices"), i), "must be a finite number");
      return;
    }
  if (m.triangles_size() == 0 || m.triangles_size() % 3 != 0) {
    error(cat(f, "triangles"),
          "needs three vertex indices a triangle and at least one triangle; it has " +
              std::to_string(m.triangles_size()) + " indices");
    return;
  }
  const auto nv = static_cast<std::uint32_t>(m.vertices_size() / 3);
  for (int i = 0; i < m.triangles_size(); ++i)
    if (m.triangles(i) >= nv) {
      error(idx(cat(f, "triangles"), i), "vertex index " + std::to_string(m.triangles(i)) +
                                             " is not below the " + std::to_string(nv) +
                                             " vertices");
      return;
    }
  const TriangleMesh mesh = mesh_from_proto(m);
  const MeshTopology top = check_topology(mesh);
  if (!top.closed_and_oriented()) {
    std::vector<std::string> parts;
    if (top.open_edges > 0)
      parts.push_back(std::to_string(top.open_edges) +
                      " edges belong to one triangle only (holes)");
    if (top.flipped_edges > 0)
      parts.push_back(std::to_string(top.flipped_edges) +
                      " edges are run in the same direction by both their triangles (flipped "
                      "triangles)");
    if (top.nonmanifold_edges > 0)
      parts.push_back(std::to_string(top.nonmanifold_edges) +
                      " edges belong to more than two triangles");
    std::string what = "the surface must be closed and consistently oriented, but";
    for (std::size_t k = 0; k < parts.size(); ++k) what.append(k ? "; " : " ").append(parts[k]);
    error(f, what);
    return;
  }
  Aabb box;
  for (const auto& v : mesh.vertices) box.grow(v);
  Aabb domain;
  domain.grow(to_point(c_.domain().lo()));
  domain.grow(to_point(c_.domain().hi()));
  const double size = (box.hi - box.lo).maxCoeff(), room = (domain.hi - domain.lo).maxCoeff();
  char buf[400];
  if (size > 100 * room) {
    std::snprintf(buf, sizeof buf,
                  "spans %g m, %.0f times the domain's largest side (%g m): is the file in other "
                  "units (mesh.scale, e.g. 0.001 for millimetres)?",
                  size, size / room, room);
    error(f, buf);
  } else if (box.intersected(domain).empty()) {
    std::snprintf(buf, sizeof buf,
                  "lies outside the domain: the mesh spans [%g, %g] x [%g, %g] x [%g, %g]",
                  box.lo.x(), box.hi.x(), box.lo.y(), box.hi.y(), box.lo.z(), box.hi.z());
    error(f, buf);
  }
}

// The grid must say where it is and hold one value a node; its inside must be closed within it
// (outside the grid is outside the shape, so a negative value on its boundary would cut the
// shape open there) and not empty, and it should overlap the domain.
void Validator::distance_grid(const v1::DistanceGrid& g, const std::string& f) {
  const int d = c_.dimension();
  if (!g.file().empty()) {
    error(cat(f, "file"),
          "distance-grid files must be inlined before validation (sphctl and sph-worker do "
          "this)");
    return;
  }
  if (g.counts_size() != d) {
    error(cat(f, "counts"), "needs one count per dimension of the case (" + std::to_string(d) +
                                "); it has " + std::to_string(g.counts_size()));
    return;
  }
  std::int64_t nodes = 1;
  for (int a = 0; a < d; ++a) {
    if (g.counts(a) < 2) {
      error(idx(cat(f, "counts"), a), "must be >= 2 (nodes along an axis)");
      return;
    }
    nodes *= g.counts(a);  // each count is below 2^32 and the values are bounded: no overflow
    if (nodes > kMaxDistanceGridNodes) {
      error(cat(f, "counts"), "give more than " + std::to_string(kMaxDistanceGridNodes) +
                                  " nodes; the limit is " + std::to_string(kMaxDistanceGridNodes) +
                                  " nodes per case");
      return;
    }
  }
  if (g.values_size() != nodes) {
    error(cat(f, "values"), "needs one value per node, " + std::to_string(nodes) +
                                " by counts; it has " + std::to_string(g.values_size()));
    return;
  }
  if (g.has_scale() && !(std::isfinite(g.scale()) && g.scale() > 0)) {
    error(cat(f, "scale"), "must be a finite number > 0");
    return;
  }
  if (!point_ok(g.origin())) {
    point(g.origin(), cat(f, "origin"));
    return;
  }
  if (!(std::isfinite(g.spacing()) && g.spacing() > 0)) {
    error(cat(f, "spacing"), "must be a finite number > 0");
    return;
  }
  const std::int64_t n[3] = {g.counts(0), g.counts(1), d == 3 ? g.counts(2) : 1};
  std::int64_t negative = 0, open = 0;
  for (std::int64_t k = 0; k < n[2]; ++k)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t i = 0; i < n[0]; ++i) {
        const std::int64_t at = (k * n[1] + j) * n[0] + i;
        const float v = g.values(static_cast<int>(at));
        if (!std::isfinite(v)) {
          error(idx(cat(f, "values"), static_cast<int>(at)), "must be a finite number");
          return;
        }
        if (v < 0) ++negative;
        const bool boundary = i == 0 || i == n[0] - 1 || j == 0 || j == n[1] - 1 ||
                              (d == 3 && (k == 0 || k == n[2] - 1));
        if (boundary && v <= 0) ++open;
      }
  if (negative == 0) {
    error(cat(f, "values"), "are nowhere negative: the shape (where the distance is < 0) is empty");
    return;
  }
  if (open > 0) {
    error(cat(f, "values"), std::to_string(open) +
                                " nodes on the grid's boundary are <= 0: the shape must be closed "
                                "inside the grid (outside it is outside the shape); extend the "
                                "grid by a node beyond the shape");
    return;
  }
  const double s = g.has_scale() ? g.scale() : 1.0;
  Aabb box;
  box.grow(s * to_point(g.origin()));
  Point3 far = s * to_point(g.origin());
  for (int a = 0; a < d; ++a) far[a] += s * g.spacing() * static_cast<double>(n[a] - 1);
  box.grow(far);
  Aabb domain;
  domain.grow(to_point(c_.domain().lo()));
  domain.grow(to_point(c_.domain().hi()));
  if (d == 2) box.lo.z() = box.hi.z() = domain.lo.z() = domain.hi.z() = 0.0;
  if (box.intersected(domain).empty()) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "lies outside the domain: the grid spans [%g, %g] x [%g, %g] x [%g, %g] "
                  "(is it in other units? distance_grid.scale, e.g. 0.001 for millimetres)",
                  box.lo.x(), box.hi.x(), box.lo.y(), box.hi.y(), box.lo.z(), box.hi.z());
    error(f, buf);
  }
}

}  // namespace sph::case_validation
