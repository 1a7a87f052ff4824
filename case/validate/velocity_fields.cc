// Initial velocity fields (proto VelocityField) of fluid regions and elastic bodies.
#include "case/validate/validator.h"

#include <cmath>

namespace sph::case_validation {

namespace {

bool is_zero(const v1::Vec3& v) {
  return v.x() == 0 && v.y() == 0 && v.z() == 0;
}

// |a x b| relative to |a| |b|: 0 for parallel vectors.
double sine_between(const v1::Vec3& a, const v1::Vec3& b) {
  const double cx = a.y() * b.z() - a.z() * b.y();
  const double cy = a.z() * b.x() - a.x() * b.z();
  const double cz = a.x() * b.y() - a.y() * b.x();
  const double na = std::hypot(a.x(), a.y(), a.z()), nb = std::hypot(b.x(), b.y(), b.z());
  return std::hypot(cx, cy, cz) / (na * nb);
}

}  // namespace

void Validator::velocity_field(const v1::VelocityField& v, const std::string& f,
                               bool elastic_body) {
  if (v.has_taylor_green()) {
    const auto& tg = v.taylor_green();
    if (c_.dimension() != 2) error(cat(f, "taylor_green"), "only in 2D cases");
    positive(tg.wavelength(), cat(f, "taylor_green.wavelength"));
    if (!finite(tg.amplitude())) error(cat(f, "taylor_green.amplitude"), "must be finite");
  }
  if (v.has_linear()) {
    const auto& lf = v.linear();
    const std::string g = cat(f, "linear");
    vec(lf.center(), cat(g, "center"));
    vec(lf.gradient_x(), cat(g, "gradient_x"));
    vec(lf.gradient_y(), cat(g, "gradient_y"));
    if (c_.dimension() == 2 && !is_zero(lf.gradient_z()))
      error(cat(g, "gradient_z"), "must be 0 in 2D cases");
    else if (c_.dimension() == 3)
      vec(lf.gradient_z(), cat(g, "gradient_z"));
  }
  if (v.has_beam_mode()) {
    // The first bending mode of a clamped-free beam (thesis digest sec. 8.4 eq. 40): a
    // transverse velocity, so its direction must cross the beam's axis.
    const auto& bm = v.beam_mode();
    const std::string g = cat(f, "beam_mode");
    if (!elastic_body) {
      error(g,
            "elastic bodies only (the bending mode of a clamped beam; a fluid region takes "
            "taylor_green or linear)");
      return;
    }
    point(bm.root(), cat(g, "root"));
    vec(bm.axis(), cat(g, "axis"));
    vec(bm.direction(), cat(g, "direction"));
    if (is_zero(bm.axis())) error(cat(g, "axis"), "must not be zero");
    if (is_zero(bm.direction()))
      error(cat(g, "direction"), "must not be zero");
    else if (!is_zero(bm.axis()) && sine_between(bm.axis(), bm.direction()) < 1e-9)
      error(cat(g, "direction"),
            "must not be parallel to axis: the bending mode moves the beam across its axis");
    positive(bm.length(), cat(g, "length"), "must be > 0 (the free length L [m])");
    extent(bm.length(), cat(g, "length"));
    if (!finite(bm.tip_velocity())) error(cat(g, "tip_velocity"), "must be finite");
  }
}

}  // namespace sph::case_validation
