#include "case/geometry.h"

#include "case/distance_grid/distance_grid_shape.h"
#include "case/mesh/mesh_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sph {
namespace {

constexpr double kHuge = 1e300;

// Shape::cost() of the primitives that do more than a box: a cylinder projects on its axis, a
// polygon visits every edge, a polar curve takes an arc tangent, a sine and a cosine.
constexpr double kCylinderCost = 2;
constexpr double kPolygonVertexCost = 1.5;
constexpr double kPolarCurveCost = 16;

double parts_cost(const std::vector<std::unique_ptr<Shape>>& parts) {
  double c = 1;
  for (const auto& s : parts) c += s->cost();
  return c;
}

class BoxShape final : public Shape {
 public:
  BoxShape(const v1::Box& b, int dim) : dim_(dim) {
    lo_ = to_point(b.lo());
    hi_ = to_point(b.hi());
    if (dim == 2) lo_.z() = hi_.z() = 0.0;
  }
  // Chebyshev distance: a Shell around a box gets square corners, as a tank should.
  double distance(const Point3& p) const override {
    double d = -kHuge;
    for (int a = 0; a < dim_; ++a) {
      const double c = 0.5 * (lo_[a] + hi_[a]), h = 0.5 * (hi_[a] - lo_[a]);
      d = std::max(d, std::abs(p[a] - c) - h);
    }
    return d;
  }
  Aabb bounds() const override { return {lo_, hi_}; }
  double cost() const override { return 1; }

 private:
  int dim_;
  Point3 lo_, hi_;
};

class BallShape final : public Shape {
 public:
  BallShape(const v1::Ball& b, int dim) : c_(to_point(b.center())), r_(b.radius()) {
    if (dim == 2) c_.z() = 0.0;
    dim_ = dim;
  }
  double distance(const Point3& p) const override {
    Point3 d = p - c_;
    if (dim_ == 2) d.z() = 0.0;
    return d.norm() - r_;
  }
  Aabb bounds() const override {
    Aabb b{c_.array() - r_, c_.array() + r_};
    if (dim_ == 2) b.lo.z() = b.hi.z() = 0.0;
    return b;
  }
  double cost() const override { return 1; }

 private:
  Point3 c_;
  double r_;
  int dim_;
};

class CylinderShape final : public Shape {
 public:
  explicit CylinderShape(const v1::Cylinder& c)
      : base_(to_point(c.base())),
        axis_(to_point(c.axis()).normalized()),
        r_(c.radius()),
        len_(c.length()) {}
  double distance(const Point3& p) const override {
    const Point3 d = p - base_;
    const double t = d.dot(axis_);
    const double radial = (d - t * axis_).norm() - r_;
    const double axial = std::abs(t - 0.5 * len_) - 0.5 * len_;
    const double outside = std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
    return outside > 0.0 ? outside : std::max(radial, axial);
  }
  Aabb bounds() const override {
    Aabb b;
    const Point3 top = base_ + len_ * axis_;
    for (int a = 0; a < 3; ++a) {
      // Extent of a disk of radius r with normal `axis` along axis a.
      const double e = r_ * std::sqrt(std::max(0.0, 1.0 - axis_[a] * axis_[a]));
      b.lo[a] = std::min(base_[a], top[a]) - e;
      b.hi[a] = std::max(base_[a], top[a]) + e;
    }
    return b;
  }
  double cost() const override { return kCylinderCost; }

 private:
  Point3 base_, axis_;
  double r_, len_;
};

class PolygonShape final : public Shape {
 public:
  explicit PolygonShape(const v1::Polygon& poly) {
    for (const auto& v : poly.vertices()) v_.emplace_back(v.x(), v.y());
  }
  double distance(const Point3& p3) const override {
    const Eigen::Vector2d p(p3.x(), p3.y());
    double dmin = kHuge;
    bool inside = false;
    const size_t n = v_.size();
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
      const Eigen::Vector2d a = v_[j], b = v_[i];
      const Eigen::Vector2d e = b - a, w = p - a;
      const double t = std::clamp(w.dot(e) / e.squaredNorm(), 0.0, 1.0);
      dmin = std::min(dmin, (w - t * e).norm());
      // Crossing-number test.
      if ((a.y() > p.y()) != (b.y() > p.y())) {
        const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (p.x() < x) inside = !inside;
      }
    }
    return inside ? -dmin : dmin;
  }
  Aabb bounds() const override {
    Aabb b;
    for (const auto& v : v_) b.grow(Point3(v.x(), v.y(), 0.0));
    return b;
  }
  double cost() const override { return std::max<double>(1, kPolygonVertexCost * v_.size()); }

 private:
  std::vector<Eigen::Vector2d> v_;
};

class PolarCurveShape final : public Shape {
 public:
  explicit PolarCurveShape(const v1::PolarCurve& c)
      : c_(c.center().x(), c.center().y()),
        r_(c.radius()),
        a_(c.amplitude()),
        k_(c.periods()),
        phase_(c.phase()) {}
  double distance(const Point3& p3) const override {
    const Eigen::Vector2d d(p3.x() - c_.x(), p3.y() - c_.y());
    const double rho = d.norm();
    const double phi = std::atan2(d.y(), d.x());
    const double rc = r_ + a_ * std::sin(k_ * phi + phase_);
    const double drc = a_ * k_ * std::cos(k_ * phi + phase_);  // dr/dphi
    // First-order distance to the curve along the radial direction, corrected by the slope.
    const double scale = std::sqrt(1.0 + (drc * drc) / std::max(rc * rc, 1e-300));
    return (rho - rc) / scale;
  }
  Aabb bounds() const override {
    const double R = r_ + std::abs(a_);
    return {Point3(c_.x() - R, c_.y() - R, 0), Point3(c_.x() + R, c_.y() + R, 0)};
  }
  double cost() const override { return kPolarCurveCost; }

 private:
  Eigen::Vector2d c_;
  double r_, a_;
  int k_;
  double phase_;
};

class PointSetShape final : public Shape {
 public:
  PointSetShape(const v1::PointSet& ps, int dim) {
    for (const auto& v : ps.points()) {
      Point3 p = to_point(v);
      if (dim == 2) p.z() = 0.0;
      pts_.push_back(p);
    }
  }
  // A point set has no interior: it contributes its points and claims nothing else.
  double distance(const Point3&) const override { return kHuge; }
  Aabb bounds() const override {
    Aabb b;
    for (const auto& p : pts_) b.grow(p);
    return b;
  }
  double cost() const override { return 1; }
  const std::vector<Point3>* explicit_points() const override { return &pts_; }

 private:
  std::vector<Point3> pts_;
};

class UnionShape final : public Shape {
 public:
  explicit UnionShape(std::vector<std::unique_ptr<Shape>> parts) : parts_(std::move(parts)) {}
  double distance(const Point3& p) const override {
    double d = kHuge;
    for (const auto& s : parts_) d = std::min(d, s->distance(p));
    return d;
  }
  Aabb bounds() const override {
    Aabb b;
    for (const auto& s : parts_) b.grow(s->bounds());
    return b;
  }
  double cost() const override { return parts_cost(parts_); }

 private:
  std::vector<std::unique_ptr<Shape>> parts_;
};

class IntersectionShape final : public Shape {
 public:
  explicit IntersectionShape(std::vector<std::unique_ptr<Shape>> parts)
      : parts_(std::move(parts)) {}
  double distance(const Point3& p) const override {
    double d = -kHuge;
    for (const auto& s : parts_) d = std::max(d, s->distance(p));
    return d;
  }
  Aabb bounds() const override {
    Aabb b = parts_.front()->bounds();
    for (size_t i = 1; i < parts_.size(); ++i) b = b.intersected(parts_[i]->bounds());
    return b;
  }
  double cost() const override { return parts_cost(parts_); }

 private:
  std::vector<std::unique_ptr<Shape>> parts_;
};

class DifferenceShape final : public Shape {
 public:
  DifferenceShape(std::unique_ptr<Shape> base, std::vector<std::unique_ptr<Shape>> sub)
      : base_(std::move(base)), sub_(std::move(sub)) {}
  double distance(const Point3& p) const override {
    double d = base_->distance(p);
    for (const auto& s : sub_) d = std::max(d, -s->distance(p));
    return d;
  }
  Aabb bounds() const override { return base_->bounds(); }
  double cost() const override { return base_->cost() + parts_cost(sub_); }

 private:
  std::unique_ptr<Shape> base_;
  std::vector<std::unique_ptr<Shape>> sub_;
};

class ShellShape final : public Shape {
 public:
  ShellShape(std::unique_ptr<Shape> inner, double t) : inner_(std::move(inner)), t_(t) {}
  // Inside when 0 < d_inner <= t; the distance is that of the band [0, t].
  double distance(const Point3& p) const override {
    const double d = inner_->distance(p);
    return std::max(-d, d - t_);
  }
  Aabb bounds() const override { return inner_->bounds().inflated(t_); }
  double cost() const override { return 1 + inner_->cost(); }

 private:
  std::unique_ptr<Shape> inner_;
  double t_;
};

std::unique_ptr<Shape> compile(const v1::Shape& s, int dim, double t, double exact_within);

std::vector<std::unique_ptr<Shape>> compile_list(const v1::ShapeList& l, int dim, double t,
                                                 double exact_within) {
  std::vector<std::unique_ptr<Shape>> out;
  for (const auto& s : l.shapes()) out.push_back(compile(s, dim, t, exact_within));
  return out;
}

// exact_within: how far from its surface a shape's distance must be exact (a shell reads its
// inner shape's distance up to its thickness, nested shells the sum); beyond, any value of the
// right sign no larger in magnitude than the true distance will do, which lets a mesh skip its
// nearest-triangle search far from its surface.
std::unique_ptr<Shape> compile(const v1::Shape& s, int dim, double t, double exact_within) {
  switch (s.kind_case()) {
    case v1::Shape::kBox:
      return std::make_unique<BoxShape>(s.box(), dim);
    case v1::Shape::kBall:
      return std::make_unique<BallShape>(s.ball(), dim);
    case v1::Shape::kCylinder:
      return std::make_unique<CylinderShape>(s.cylinder());
    case v1::Shape::kPolygon:
      return std::make_unique<PolygonShape>(s.polygon());
    case v1::Shape::kPolarCurve:
      return std::make_unique<PolarCurveShape>(s.polar_curve());
    case v1::Shape::kPoints:
      return std::make_unique<PointSetShape>(s.points(), dim);
    case v1::Shape::kUnion:
      return std::make_unique<UnionShape>(compile_list(s.union_(), dim, t, exact_within));
    case v1::Shape::kIntersection:
      return std::make_unique<IntersectionShape>(
          compile_list(s.intersection(), dim, t, exact_within));
    case v1::Shape::kDifference: {
      std::vector<std::unique_ptr<Shape>> sub;
      for (const auto& x : s.difference().subtract())
        sub.push_back(compile(x, dim, t, exact_within));
      return std::make_unique<DifferenceShape>(compile(s.difference().base(), dim, t, exact_within),
                                               std::move(sub));
    }
    case v1::Shape::kMesh:
      return std::make_unique<MeshShape>(mesh_from_proto(s.mesh()), exact_within);
    case v1::Shape::kDistanceGrid:
      return std::make_unique<DistanceGridShape>(s.distance_grid(), dim);
    case v1::Shape::kShell: {
      const double thickness = s.shell().has_thickness() ? s.shell().thickness() : t;
      return std::make_unique<ShellShape>(
          compile(s.shell().inner(), dim, t, exact_within + thickness), thickness);
    }
    case v1::Shape::KIND_NOT_SET:
      break;
  }
  throw std::invalid_argument("shape has no kind");
}

}  // namespace

std::unique_ptr<Shape> compile_shape(const v1::Shape& s, int dim, double t) {
  return compile(s, dim, t, 0.0);
}

}  // namespace sph
