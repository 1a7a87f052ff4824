// Heat conduction and concentration diffusion: the thermal block and the coefficients
// of every material that takes part.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::thermal() {
  if (!finite(c_.thermal().initial_temperature()))
    error("thermal.initial_temperature", "must be finite");
  if (!finite(c_.thermal().volumetric_heat_source()))
    error("thermal.volumetric_heat_source", "must be finite");
}

// Every material that conducts or diffuses needs its coefficients once the effect is on.
void Validator::transport_properties(const std::string& name, const std::string& field) {
  const int k = material_position(name);
  if (k < 0) return;
  const auto& m = c_.materials(k);
  const std::string mf = idx("materials", k);
  if (c_.has_thermal() && (!m.has_heat_capacity() || !m.has_thermal_conductivity()) &&
      reported_.insert(mf + "t").second)
    error(cat(mf, m.has_heat_capacity() ? "thermal_conductivity" : "heat_capacity"),
          "required: heat conduction is enabled and material '" + name + "' is used by " + field);
  if (c_.has_diffusion() && !m.has_diffusivity() && reported_.insert(mf + "d").second)
    error(cat(mf, "diffusivity"), "required: concentration diffusion is enabled and material '" +
                                      name + "' is used by " + field);
}

}  // namespace sph::case_validation
