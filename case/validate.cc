#include "case/validate.h"

#include "case/validate/validator.h"
#include "case/validate_reference.h"
#include "case/validate_surface_tension.h"

namespace sph {

// The sections run in this order, which is the order of the errors (case/validate/: one file
// per section).
std::vector<FieldError> validate_case(const v1::Case& c, const ValidationLimits& limits,
                                      CaseEstimate* estimate) {
  using case_validation::idx;
  case_validation::Validator v(c, limits, estimate);
  // The checks below recurse over shapes and do lattice arithmetic: only within the bounds.
  if (!v.within_bounds()) return v.reported();
  v.top_level();
  if (!v.dimension_ok()) return v.reported();
  v.materials();
  for (int i = 0; i < c.fluids_size(); ++i) v.fluid(c.fluids(i), idx("fluids", i));
  for (int i = 0; i < c.walls_size(); ++i) v.wall(c.walls(i), idx("walls", i));
  for (int i = 0; i < c.bodies_size(); ++i) v.body(c.bodies(i), idx("bodies", i));
  for (int i = 0; i < c.elastic_bodies_size(); ++i)
    v.elastic_body(c.elastic_bodies(i), idx("elastic_bodies", i));
  if (c.has_contact()) v.contact();
  v.phase_transitions();
  if (c.has_thermal()) v.thermal();
  v.open_boundaries();
  v.add_uncapped(validate_reference(c));
  v.add(validate_surface_tension(c));
  v.run_settings();
  v.density_diffusion();
  v.particle_shifting();
  v.riemann_dissipation();
  v.probes();
  v.case_size();
  return v.reported();
}

std::string join_errors(const std::vector<FieldError>& errors) {
  std::string s;
  for (const auto& e : errors) s += (s.empty() ? "" : "; ") + e.to_string();
  return s;
}

}  // namespace sph
