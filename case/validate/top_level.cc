// The case as a whole: case_limits.h's bounds, dimension, dx, smoothing length, domain.
#include "case/validate/validator.h"

#include "case/case_bounds.h"
#include "case/estimate.h"

namespace sph::case_validation {

bool Validator::within_bounds() {
  auto bounds = check_case_bounds(c_);
  for (auto& e : bounds) error(e.field, e.message);
  return bounds.empty();
}

void Validator::top_level() {
  if (c_.dimension() != 2 && c_.dimension() != 3) {
    error("dimension", "must be 2 or 3 (got " + std::to_string(c_.dimension()) + ")");
    dim_ok_ = false;
    return;
  }
  positive(c_.dx(), "dx");
  if (c_.has_smoothing_length_ratio() &&
      !(c_.smoothing_length_ratio() >= 1.0 && c_.smoothing_length_ratio() <= 4.0))
    error("smoothing_length_ratio",
          "must be between 1 and 4 (got " + num(c_.smoothing_length_ratio()) + ")");
  if (c_.has_neighbor_skin() && !(c_.neighbor_skin() >= 0.0 && c_.neighbor_skin() <= 2.0))
    error("neighbor_skin",
          "must be between 0 and 2 (times dx; got " + num(c_.neighbor_skin()) + ")");
  if (!c_.has_domain()) {
    error("domain", "is required (the bounding box of the computational domain)");
  } else {
    vec(c_.domain().lo(), "domain.lo");
    vec(c_.domain().hi(), "domain.hi");
    const char* axes = "xyz";
    for (int a = 0; a < c_.dimension(); ++a) {
      const double lo = a == 0   ? c_.domain().lo().x()
                        : a == 1 ? c_.domain().lo().y()
                                 : c_.domain().lo().z();
      const double hi = a == 0   ? c_.domain().hi().x()
                        : a == 1 ? c_.domain().hi().y()
                                 : c_.domain().hi().z();
      if (!(hi > lo))
        error(std::string("domain.hi.") + axes[a],
              "must be greater than domain.lo." + std::string(1, axes[a]));
      else if (c_.dx() > 0 && (hi - lo) < 2 * kernel_support_radius(c_))
        error(std::string("domain.hi.") + axes[a],
              "domain is narrower than two kernel supports along " + std::string(1, axes[a]));
    }
  }
  if (c_.dimension() == 2 && c_.periodic_z()) error("periodic_z", "not allowed in a 2D case");
  vec(c_.lattice_origin(), "lattice_origin");
  if (c_.fluids_size() == 0 && c_.bodies_size() == 0 && c_.elastic_bodies_size() == 0)
    error("fluids", "a case needs at least one fluid region, rigid body or elastic body");
}

}  // namespace sph::case_validation
