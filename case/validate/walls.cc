// Walls.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::wall(const v1::Wall& w, const std::string& f) {
  if (!w.has_shape())
    error(cat(f, "shape"), "is required");
  else
    shape(w.shape(), cat(f, "shape"), true);
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
}

}  // namespace sph::case_validation
