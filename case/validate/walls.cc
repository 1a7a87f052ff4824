// Walls.
#include <algorithm>

#include "case/time_function.h"
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::wall(const v1::Wall& w, const std::string& f) {
  const std::size_t before = errors_.size();
  if (!w.has_shape())
    error(cat(f, "shape"), "is required");
  else
    shape(w.shape(), cat(f, "shape"), true);
  const bool shape_ok = errors_.size() == before;
  material_ref(w.material(), v1::SOLID, cat(f, "material"), false);
  if (w.has_motion()) motion(w.motion(), cat(f, "motion"));
  if (w.has_temperature()) {
    if (!c_.has_thermal())
      error(cat(f, "temperature"),
            "set, but heat conduction is not enabled (add a `thermal { }` block)");
    time_function(w.temperature().value(), cat(f, "temperature.value"));
  }
  if (w.has_concentration()) {
    if (!c_.has_diffusion())
      error(cat(f, "concentration"),
            "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
    time_function(w.concentration().value(), cat(f, "concentration.value"));
  }
  if (!w.material().empty() && (w.has_temperature() || w.has_concentration()))
    transport_properties(w.material(), f + ".material");
  if (w.has_growth_speed()) growth_speed(w, cat(f, "growth_speed"), shape_ok);
}

namespace {
// Whether a shape has a surface a front can grow from: explicit points have none (their
// distance is "far" everywhere, case/geometry.cc), so neither has a union of point sets, an
// intersection with one, or a difference or shell built on one.
bool has_surface(const v1::Shape& s) {
  switch (s.kind_case()) {
    case v1::Shape::kPoints:
      return false;
    case v1::Shape::kUnion:
      return std::any_of(s.union_().shapes().begin(), s.union_().shapes().end(), has_surface);
    case v1::Shape::kIntersection:
      return !s.intersection().shapes().empty() &&
             std::all_of(s.intersection().shapes().begin(), s.intersection().shapes().end(),
                         has_surface);
    case v1::Shape::kDifference:
      return has_surface(s.difference().base());
    case v1::Shape::kShell:
      return has_surface(s.shell().inner());
    default:
      return true;  // a primitive (a missing kind is reported on its own)
  }
}
}  // namespace

// A growing wall (solver/boundaries/wall_growth.h) converts the fluid its front passes; the
// front never moves back, so the speed must be >= 0 at every time.
void Validator::growth_speed(const v1::Wall& w, const std::string& f, bool shape_ok) {
  const v1::TimeFunction& g = w.growth_speed();
  const std::size_t before = errors_.size();
  time_function(g, f);
  if (w.has_motion()) error(f, "a growing wall cannot move (remove `motion` or `growth_speed`)");
  if (!has_surface(w.shape()))
    error(f, "a wall of explicit points has no surface to grow from (give it a shape)");
  switch (g.kind_case()) {
    case v1::TimeFunction::kConstant:
      if (g.constant() < 0)
        error(cat(f, "constant"),
              "must be >= 0 (a front does not recede); got " + num(g.constant()));
      break;
    case v1::TimeFunction::kSine:
      if (g.sine().offset() < std::abs(g.sine().amplitude()))
        error(cat(f, "sine"), "offset must be >= |amplitude| (the speed must stay >= 0)");
      break;
    case v1::TimeFunction::kPiecewiseLinear:
    case v1::TimeFunction::kPiecewiseConstant: {
      const bool lin = g.kind_case() == v1::TimeFunction::kPiecewiseLinear;
      const auto& t = lin ? g.piecewise_linear() : g.piecewise_constant();
      const std::string tf = cat(f, lin ? "piecewise_linear" : "piecewise_constant");
      for (int i = 0; i < t.values_size(); ++i)
        if (!(t.values(i) >= 0))
          error(idx(cat(tf, "values"), i),
                "must be >= 0 (a front does not recede); got " + num(t.values(i)));
      break;
    }
    case v1::TimeFunction::KIND_NOT_SET:
      error(f, "needs a speed (constant, sine or a table) [m/s]");
      break;
  }
  // An open boundary's buffer feeds fluid where the wall would grow over it (the solid-fraction
  // guard then stops the run): a growing wall, as far as it grows by the end time, must keep
  // a kernel support clear of the buffers (let fixed walls line the inflow and outflow).
  const double end = c_.time().end_time(), dx = c_.dx();
  if (!shape_ok || errors_.size() != before || c_.open_boundaries_size() == 0 || !dimension_ok() ||
      !finite(end) || !(end > 0) || !finite(dx) || !(dx > 0))
    return;
  const double reach = TimeFunction(g).integral(end) + kernel_support_radius(c_);
  if (!finite(reach)) return;
  const Aabb grown = compile_shape(w.shape(), c_.dimension(), default_shell_thickness(c_))
                         ->bounds()
                         .inflated(reach);
  for (int b = 0; b < c_.open_boundaries_size(); ++b) {
    const auto& r = c_.open_boundaries(b).region();
    bool overlap = true;
    for (int a = 0; a < c_.dimension(); ++a) {
      const double lo = a == 0 ? r.lo().x() : a == 1 ? r.lo().y() : r.lo().z();
      const double hi = a == 0 ? r.hi().x() : a == 1 ? r.hi().y() : r.hi().z();
      overlap = overlap && grown.lo[a] < hi && grown.hi[a] > lo;
    }
    if (overlap)
      error(f, "the wall, grown by the end time (" + num(reach - kernel_support_radius(c_)) +
                   " m) and a kernel support, reaches the buffer of open_boundaries[" +
                   std::to_string(b) +
                   "]: keep growing walls clear of the buffers (fixed walls along them)");
  }
}

}  // namespace sph::case_validation
