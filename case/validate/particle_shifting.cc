// fluid_model.particle_shifting (solver/physics/particle_shifting.h): its coefficients, and the
// cases it refuses: the transport velocity (which already moves particles off the velocity),
// open boundaries (whose buffers place their particles themselves) and several fluid materials
// (shifting across an interface would mix the phases).
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::particle_shifting() {
  const auto& fm = c_.fluid_model();
  if (!fm.has_particle_shifting()) return;
  const auto& ps = fm.particle_shifting();
  if (ps.has_coefficient() &&
      (!finite(ps.coefficient()) || !(ps.coefficient() > 0) || ps.coefficient() > 10))
    error("fluid_model.particle_shifting.coefficient",
          "must be in (0, 10] (Skillen et al. 2013: 1 to 6, default 2); got " +
              num(ps.coefficient()));
  if (ps.has_surface_threshold() && (!finite(ps.surface_threshold()) ||
                                     !(ps.surface_threshold() > 0.5) || ps.surface_threshold() > 1))
    error("fluid_model.particle_shifting.surface_threshold",
          "must be in (0.5, 1] (the kernel-sum completeness below which a particle is at the "
          "free surface; default 0.99); got " +
              num(ps.surface_threshold()));
  if (!v1::ParticleShifting::Speed_IsValid(ps.speed()))
    error("fluid_model.particle_shifting.speed",
          "must be LOCAL or MAXIMUM; got " + std::to_string(ps.speed()));
  if (fm.transport_velocity())
    error("fluid_model.particle_shifting",
          "cannot be combined with fluid_model.transport_velocity: both move the particles off "
          "the velocity to keep them ordered; choose one");
  if (c_.open_boundaries_size() > 0)
    error("fluid_model.particle_shifting",
          "cannot be combined with open_boundaries (their buffers place their particles "
          "themselves); the case has " +
              std::to_string(c_.open_boundaries_size()));
  int fluids = 0;
  for (const auto& m : c_.materials())
    if (m.phase() != v1::SOLID) ++fluids;
  if (fluids > 1)
    error("fluid_model.particle_shifting",
          "applies to cases with one fluid material; the case has " + std::to_string(fluids) +
              " (shifting across an interface would mix the phases)");
}

}  // namespace sph::case_validation
