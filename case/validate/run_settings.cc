// Run settings: artificial viscosity, gravity and body force, time stepping, output,
// guards and stop conditions.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::run_settings() {
  const auto& fm = c_.fluid_model();
  non_negative(fm.artificial_viscosity(), "fluid_model.artificial_viscosity");
  if (c_.has_gravity()) {
    vec(c_.gravity().acceleration(), "gravity.acceleration");
    non_negative(c_.gravity().damping_time(), "gravity.damping_time");
  }
  vec(c_.body_force(), "body_force");
  const auto& t = c_.time();
  positive(t.end_time(), "time.end_time");
  if (t.has_cfl_factor() && (!(t.cfl_factor() > 0) || t.cfl_factor() > 2))
    error("time.cfl_factor", "must be in (0, 2] (got " + num(t.cfl_factor()) + ")");
  non_negative(t.fixed_dt(), "time.fixed_dt");
  // A fluid material a phase transition produces gives the bound its sound speed too, and an
  // elastic body its own bound (thesis eq. 33, with the sound speed of its material).
  if (c_.fluids_size() == 0 && c_.phase_transitions_size() == 0 && c_.elastic_bodies_size() == 0 &&
      !(t.fixed_dt() > 0))
    error("time.fixed_dt",
          "is required when the case has no fluid or elastic body (the bound of Fuchs 2021 eq. "
          "41 needs a sound speed)");
  if (t.max_steps() < 0) error("time.max_steps", "must be >= 0");
  if (t.has_quasi_static()) {
    const auto& q = t.quasi_static();
    positive(q.load_step(), "time.quasi_static.load_step");
    positive(q.damping(), "time.quasi_static.damping");
    positive(q.kinetic_energy_threshold(), "time.quasi_static.kinetic_energy_threshold");
    if (q.load_step() > 0 && t.end_time() > 0 && q.load_step() > t.end_time())
      error("time.quasi_static.load_step",
            "must be at most time.end_time (" + num(t.end_time()) + ")");
    // Dynamic relaxation damps the elastic bodies alone; a fluid would see them move by load
    // steps far beyond its own bound.
    if (c_.fluids_size() > 0 || c_.phase_transitions_size() > 0)
      error("time.quasi_static", "is for elastic bodies alone: the case has fluid");
    if (c_.bodies_size() > 0)
      error("time.quasi_static", "is for elastic bodies alone: the case has rigid bodies");
    if (c_.elastic_bodies_size() == 0)
      error("time.quasi_static", "needs at least one elastic body");
    if (t.fixed_dt() > 0)
      error("time.fixed_dt", "must be unset with time.quasi_static (its load_step is the step)");
    if (t.subcycle_elastic_bodies())
      error("time.subcycle_elastic_bodies",
            "must be unset with time.quasi_static (the inner steps take its place)");
    quasi_static_diffusion();
  }
  const auto& o = c_.output();
  non_negative(o.interval(), "output.interval");
  // Every snapshot time is stored up front and each snapshot is a full particle dump.
  constexpr double kMaxSnapshots = 100000;
  if (o.interval() > 0 && t.end_time() > 0 && t.end_time() / o.interval() > kMaxSnapshots)
    error("output.interval", "gives " + num(t.end_time() / o.interval()) +
                                 " snapshots (end_time / interval); at most 100000 are allowed");
  non_negative(o.series_interval(), "output.series_interval");
  non_negative(o.checkpoint_wall_interval(), "output.checkpoint_wall_interval");
  for (int i = 0; i < o.times_size(); ++i)
    if (!(o.times(i) >= 0) || o.times(i) > t.end_time())
      error(idx("output.times", i), "must be within [0, time.end_time]");
  const auto& g = c_.guards();
  if (g.has_max_density_deviation())
    positive(g.max_density_deviation(), "guards.max_density_deviation");
  if (g.has_min_dt_fraction()) positive(g.min_dt_fraction(), "guards.min_dt_fraction");
  if (g.has_max_mach()) positive(g.max_mach(), "guards.max_mach");
  if (g.has_max_solid_fraction() && (!(g.max_solid_fraction() > 0) || g.max_solid_fraction() > 1))
    error("guards.max_solid_fraction",
          "must be in (0, 1] (got " + num(g.max_solid_fraction()) + ")");
  if (g.has_max_contact_substeps() && g.max_contact_substeps() < 1)
    error("guards.max_contact_substeps", "must be >= 1");
  non_negative(c_.stop().max_wall_seconds(), "stop.max_wall_seconds");
  non_negative(c_.stop().steady_kinetic_energy(), "stop.steady_kinetic_energy");
}

}  // namespace sph::case_validation
