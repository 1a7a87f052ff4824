// fluid_model.riemann_dissipation (solver/physics/riemann_dissipation.h): its scope and
// limiter, and the cases it refuses: summation density (no continuity equation to dissipate
// in), density diffusion at once (both damp the same noise; their sum is neither), artificial
// viscosity with the momentum term (which is itself a limited artificial viscosity) and
// several fluid materials (one sound speed and impedance per pair).
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::riemann_dissipation() {
  const auto& fm = c_.fluid_model();
  if (!fm.has_riemann_dissipation()) return;
  const auto& rd = fm.riemann_dissipation();
  if (!v1::RiemannDissipation::Scope_IsValid(rd.scope()))
    error("fluid_model.riemann_dissipation.scope",
          "must be CONTINUITY or CONTINUITY_AND_MOMENTUM; got " + std::to_string(rd.scope()));
  if (rd.has_limiter_eta() &&
      (!finite(rd.limiter_eta()) || !(rd.limiter_eta() > 0) || rd.limiter_eta() > 1e6))
    error("fluid_model.riemann_dissipation.limiter_eta",
          "must be in (0, 1e6] (Zhang, Hu, Adams 2017: 3, the default); got " +
              num(rd.limiter_eta()));
  if (fm.density() != v1::CONTINUITY)
    error("fluid_model.riemann_dissipation",
          "needs fluid_model.density: CONTINUITY (it replaces the pair velocity of the "
          "continuity equation; summation density has no density equation)");
  if (fm.has_density_diffusion())
    error("fluid_model.riemann_dissipation",
          "cannot be combined with fluid_model.density_diffusion: both add a diffusion of "
          "density (pressure) to the continuity equation; choose one");
  if (rd.scope() == v1::RiemannDissipation::CONTINUITY_AND_MOMENTUM &&
      fm.artificial_viscosity() != 0)
    error("fluid_model.riemann_dissipation.scope",
          "CONTINUITY_AND_MOMENTUM is a limited artificial viscosity itself; set "
          "fluid_model.artificial_viscosity to 0 (got " +
              num(fm.artificial_viscosity()) + ") or use scope CONTINUITY");
  int fluids = 0;
  for (const auto& m : c_.materials())
    if (m.phase() != v1::SOLID) ++fluids;
  if (fluids > 1)
    error("fluid_model.riemann_dissipation",
          "applies to cases with one fluid material; the case has " + std::to_string(fluids) +
              " (a pair across an interface would need the two materials' impedances)");
}

}  // namespace sph::case_validation
