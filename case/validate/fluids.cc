// Fluid regions.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::fluid(const v1::FluidRegion& r, const std::string& f) {
  material_ref(r.material(), v1::FLUID, cat(f, "material"), true);
  if (!r.has_shape())
    error(cat(f, "shape"), "is required");
  else
    shape(r.shape(), cat(f, "shape"), true);
  vec(r.initial_velocity(), cat(f, "initial_velocity"));
  velocity_field(r.initial_velocity_field(), cat(f, "initial_velocity_field"), false);
  if (!(r.position_jitter() >= 0 && r.position_jitter() <= 0.5))
    error(cat(f, "position_jitter"), "must be in [0, 0.5] (a fraction of dx)");
  if (r.has_hydrostatic_surface()) {
    if (!finite(r.hydrostatic_surface())) error(cat(f, "hydrostatic_surface"), "must be finite");
    if (!c_.has_gravity()) error(cat(f, "hydrostatic_surface"), "needs gravity");
  }
  if (r.has_initial_temperature() && !c_.has_thermal())
    error(cat(f, "initial_temperature"),
          "set, but heat conduction is not enabled (add a `thermal { }` block)");
  if (r.has_initial_concentration() && !c_.has_diffusion())
    error(cat(f, "initial_concentration"),
          "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
  transport_properties(r.material(), f + ".material");
}

}  // namespace sph::case_validation
