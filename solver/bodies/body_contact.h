#pragma once
// The contact unit between rigid bodies and between bodies and walls, as the step loop sees
// it: one of the laws of v1::ContactModel (docs/contact.md). Each moves the bodies over a
// fluid step (drift), since contact acts inside the bodies' drift (rigid_bodies.h): the
// spring-dashpot and the repulsive force as r-RESPA sub-steps, the restitution model by
// impulses before the drift.
#include "solver/bodies/rigid_bodies.h"
#include "solver/core/checkpoint_state.h"
#include "solver/parallel/halo.h"

namespace sph {

template <int D>
class BodyContact {
 public:
  static constexpr const char* kName = "contact";
  virtual ~BodyContact() = default;

  // The contact sub-step for the lightest rigid particle (infinity: no sub-steps needed).
  virtual double time_step(double min_particle_mass) const = 0;
  // Candidates are collected up to this distance (the reach of the law plus the motion
  // within a step), and sub-steps start once two candidates are nearer than touch_range().
  virtual double candidate_range() const = 0;
  virtual double touch_range() const = 0;
  virtual bool with_walls() const = 0;
  // Drifts the bodies over dt (in `substeps` sub-steps where the law is a force) with the
  // contact, and moves prescribed ones to t_end. Collective.
  virtual void drift(const NeighborList<D>& nl, double dt, int substeps, double t_end,
                     const Comm& comm) = 0;
  // Contact forces of the bodies as they are now, after the body table changed. Collective.
  virtual void refresh(const NeighborList<D>& nl, const Comm& comm) = 0;
  // History that moves with particles and into checkpoints (friction); none by default.
  virtual void migrate_history(Halo<D>&) {}
  virtual void prune_history() {}
  virtual void save(CheckpointState&, const Comm&) const {}
  virtual void load(const CheckpointState&) {}
};

}  // namespace sph
