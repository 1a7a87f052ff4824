// Shapes of fluid regions, walls and bodies (proto Shape): each kind's fields, recursively.
#include "case/validate/validator.h"

#include <cmath>

namespace sph::case_validation {

void Validator::shape(const v1::Shape& s, const std::string& f, bool top) {
  const int d = c_.dimension();
  switch (s.kind_case()) {
    case v1::Shape::KIND_NOT_SET:
      error(f,
            "shape has no kind (box, ball, cylinder, polygon, polar_curve, points, union, "
            "intersection, difference or shell)");
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
      if (s.polygon().vertices_size() < 3)
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

}  // namespace sph::case_validation
