#pragma once
// What a case will cost before it runs: particle counts per kind, the time step from
// Fuchs 2021 eq. (41) at rest (and, with elastic bodies, the thesis eq. (33) bound of their
// material), step count and memory. Used by `sphctl submit --dry-run`,
// the server's size limit, and progress ETA before the first step.
#include <cstdint>
#include <string>

#include "sph/v1/case.pb.h"

namespace sph {

struct CaseEstimate {
  double fluid_particles = 0;
  double wall_particles = 0;
  double rigid_particles = 0;
  double elastic_particles = 0;
  // The elastic bodies' particles were every one resolved isotropically (spacing dx): above
  // elastic_particles by what anisotropic resolution (ElasticBody.anisotropy) saves.
  double elastic_isotropic_particles = 0;
  double total() const {
    return fluid_particles + wall_particles + rigid_particles + elastic_particles;
  }
  double initial_dt = 0;  // [s]
  double steps = 0;       // end_time / initial_dt (adaptive runs may differ)
  // Quasi-static loading (time.quasi_static): steps are the outer (load) steps, and each takes
  // at most load_step / (the elastic bound at rest) inner steps; inner_steps is that total,
  // what plain small steps would take. The relaxation ends most inner loops well before.
  double inner_steps = 0;
  double bytes = 0;           // particle storage + neighbour lists, all ranks
  std::string dt_limited_by;  // which criterion is the smallest
};

// Requires a case that passed the structural checks of validate_case (shapes compile). The
// particle counts are exact within kEstimateWork (case/case_limits.h) and counted on a sample
// of each region's lattice points beyond it.
CaseEstimate estimate_case(const v1::Case& c);

// Cut-off radius over smoothing length for the case's kernel (kappa).
double kernel_support_factor(const v1::Case& c);
// h = smoothing_length_ratio * dx (h = dx unless the case says otherwise).
double smoothing_length(const v1::Case& c);
// r_c = kappa h.
double kernel_support_radius(const v1::Case& c);
// The Verlet skin of the neighbour search [m]: neighbor_skin (default 0.3) times dx, 0 with
// open boundaries (particles come and go every few steps), and at most what leaves every
// periodic axis of the domain two cells of r_c + skin (no pair through two images).
double neighbor_skin(const v1::Case& c);
// The step a run takes whatever its state: time.fixed_dt, or the load step of quasi-static
// loading; 0 for an adaptive step.
double fixed_time_step(const v1::Case& c);
// How the run keeps the kernel values of its pairs: as the case asks, and by default the
// compact table (single precision), which every pass over pairs reads as it is
// (solver/core/pair_access.h), except in a case with Riemann dissipation: its passes need r
// and dW/dr themselves, a square root a pair on the compact table, which cost them 10% of a
// step (docs/effects.md, "Memory per particle"), so there the double table is the default.
v1::PairKernelStorage pair_kernel_storage(const v1::Case& c);
// The thickness a `shell` wall gets when it gives none: whole layers of dx covering r_c
// (Adami 2012 sec. 3).
double default_shell_thickness(const v1::Case& c);

}  // namespace sph
