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
  if (r.initial_velocity_field().has_taylor_green()) {
    const auto& tg = r.initial_velocity_field().taylor_green();
    if (c_.dimension() != 2)
      error(cat(f, "initial_velocity_field.taylor_green"), "only in 2D cases");
    positive(tg.wavelength(), cat(f, "initial_velocity_field.taylor_green.wavelength"));
    if (!finite(tg.amplitude()))
      error(cat(f, "initial_velocity_field.taylor_green.amplitude"), "must be finite");
  }
  if (r.initial_velocity_field().has_linear()) {
    const auto& lf = r.initial_velocity_field().linear();
    const std::string g = cat(f, "initial_velocity_field.linear");
    vec(lf.center(), cat(g, "center"));
    vec(lf.gradient_x(), cat(g, "gradient_x"));
    vec(lf.gradient_y(), cat(g, "gradient_y"));
    if (c_.dimension() == 2 &&
        (lf.gradient_z().x() != 0 || lf.gradient_z().y() != 0 || lf.gradient_z().z() != 0))
      error(cat(g, "gradient_z"), "must be 0 in 2D cases");
    else if (c_.dimension() == 3)
      vec(lf.gradient_z(), cat(g, "gradient_z"));
  }
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
