// fluid_model.density_diffusion (solver/physics/density_diffusion.h): the coefficient, the
// density form it needs and the one fluid material it applies to.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::density_diffusion() {
  const auto& fm = c_.fluid_model();
  if (!fm.has_density_diffusion()) return;
  const auto& dd = fm.density_diffusion();
  if (dd.has_delta() && (!finite(dd.delta()) || !(dd.delta() > 0) || dd.delta() > 1))
    error("fluid_model.density_diffusion.delta",
          "must be in (0, 1] (typical 0.1); got " + num(dd.delta()));
  if (!v1::DensityDiffusion::Form_IsValid(dd.form()))
    error("fluid_model.density_diffusion.form",
          "must be MOLTENI_COLAGROSSI or FOURTAKAS; got " + std::to_string(dd.form()));
  if (fm.density() != v1::CONTINUITY)
    error("fluid_model.density_diffusion",
          "needs fluid_model.density: CONTINUITY (it is a term of the continuity equation; "
          "summation density has no density equation to add it to)");
  int fluids = 0;
  for (const auto& m : c_.materials())
    if (m.phase() != v1::SOLID) ++fluids;
  if (fluids > 1)
    error("fluid_model.density_diffusion",
          "applies to cases with one fluid material; the case has " + std::to_string(fluids) +
              " (between phases it would diffuse the density jump of the interface)");
}

}  // namespace sph::case_validation
