// Checks of single fields that every section uses, and the error list they fill.
#include "case/validate/validator.h"

#include <cmath>

#include "case/case_bounds.h"
#include "case/case_limits.h"

namespace sph::case_validation {

void Validator::error(const std::string& field, const std::string& msg) {
  if (errors_.size() < static_cast<std::size_t>(kMaxReportedErrors))
    errors_.push_back({field, msg});
  else
    ++unreported_;
}

void Validator::add(const std::vector<FieldError>& errors) {
  for (const auto& e : errors) error(e.field, e.message);
}

void Validator::add_uncapped(std::vector<FieldError> errors) {
  for (auto& e : errors) errors_.push_back(std::move(e));
}

std::vector<FieldError> Validator::reported() {
  if (unreported_ > 0)
    errors_.push_back({"", "and " + std::to_string(unreported_) + " more error" +
                               (unreported_ == 1 ? "" : "s") + " (only the first " +
                               std::to_string(kMaxReportedErrors) + " are listed)"});
  return std::move(errors_);
}

void Validator::positive(double v, const std::string& field, const std::string& what) {
  if (!finite(v) || v <= 0) error(field, what + " (got " + num(v) + ")");
}

void Validator::non_negative(double v, const std::string& field) {
  if (!finite(v) || v < 0) error(field, "must be >= 0 (got " + num(v) + ")");
}

void Validator::vec(const v1::Vec3& v, const std::string& field) {
  if (!finite(v.x()) || !finite(v.y()) || !finite(v.z())) error(field, "must be finite");
  if (c_.dimension() == 2 && v.z() != 0.0)
    error(cat(field, "z"), "must be 0 in a 2D case (got " + num(v.z()) + ")");
}

// A position or length of a shape: finite (vec() and positive() name that) and within
// kMaxCoordinate, so that its squares and the lattice walk over its bounds stay finite.
void Validator::extent(double v, const std::string& field) {
  if (finite(v) && std::abs(v) > kMaxCoordinate)
    error(field, "is " + count_text(v) + " m; coordinates and lengths must lie within +-" +
                     count_text(kMaxCoordinate) + " m");
}

// Whether point() finds nothing wrong; a point set of millions names only the points that
// are wrong, not build each one's field path.
bool Validator::point_ok(const v1::Vec3& v) const {
  auto ok = [](double x) { return finite(x) && std::abs(x) <= kMaxCoordinate; };
  return ok(v.x()) && ok(v.y()) && (c_.dimension() == 2 ? v.z() == 0.0 : ok(v.z()));
}

void Validator::point(const v1::Vec3& v, const std::string& field) {
  vec(v, field);
  extent(v.x(), cat(field, "x"));
  extent(v.y(), cat(field, "y"));
  if (c_.dimension() == 3) extent(v.z(), cat(field, "z"));
}

}  // namespace sph::case_validation
