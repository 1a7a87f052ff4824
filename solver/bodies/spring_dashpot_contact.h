#pragma once
// Frictionless spring-dashpot contact between particles of different rigid bodies and
// between rigid particles and wall particles (Fuchs 2021 eq. 27, Remark 17):
//   f_rr' = -min(0, k_c (d - dx) + d_c e . u_rr') e    for d = |x_r - x_r'| < dx,
// with e = (x_r - x_r')/d; the min is the tension cut-off.
//
// It runs as the inner level of the bodies' r-RESPA integration (see rigid_bodies.h): during
// the substeps of one fluid step the rigid particles (owned and ghost) are moved with their
// bodies, positions reconstructed as x^n + (c - c^n) + (R - R^n) b from the replicated body
// states, so the substeps need no halo exchange, only one reduction of body forces each.
// Walls keep their positions of the start of the step.
#include <vector>

#include "solver/bodies/rigid_bodies.h"

namespace sph {

template <int D>
class SpringDashpotContact {
 public:
  static constexpr const char* kName = "contact";
  SpringDashpotContact(ParticleStore<D>& s, RigidBodies<D>& bodies, double stiffness,
                       double damping, double dx, bool walls)
      : s_(s), bodies_(bodies), k_(stiffness), d_(damping), dx_(dx), walls_(walls) {}

  // Fuchs 2021 eq. 41: 0.22 sqrt(m_r/k_c) for the lightest rigid particle.
  double time_step(double min_particle_mass) const {
    return 0.22 * std::sqrt(min_particle_mass / k_);
  }
  // Candidates are collected up to this distance (dx plus the motion within a step).
  double candidate_range() const { return 1.5 * dx_; }
  bool with_walls() const { return walls_; }

  // Drifts the bodies over dt in n substeps of kick-drift-kick with the contact forces
  // (free bodies) and moves prescribed ones. Collective.
  void drift(const NeighborList<D>& nl, double dt, int substeps, double t_end, const Comm& comm);
  // Contact forces for the current body states, reduced into the bodies (contact_force,
  // contact_torque, contacts). Collective.
  void evaluate(const NeighborList<D>& nl, const Comm& comm);

 private:
  void snapshot_step_start();

  ParticleStore<D>& s_;
  RigidBodies<D>& bodies_;
  double k_, d_, dx_;
  bool walls_;
  std::vector<Vec<D>> com0_;
  std::vector<Mat<D>> R0_;
};

}  // namespace sph
