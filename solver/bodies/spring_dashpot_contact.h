#pragma once
// Spring-dashpot contact between particles of different rigid bodies and between rigid
// particles and wall particles (Fuchs 2021 eq. 27, Remark 17):
//   f_rr' = -min(0, k_c (d - dx) + d_c e . u_rr') e    for d = |x_r - x_r'| < dx,
// with e = (x_r - x_r')/d; the min is the tension cut-off. Optional Coulomb friction with a
// tangential spring (Cundall & Strack 1979): each touching pair keeps its tangential
// displacement delta (projected into the current tangent plane and grown by the tangential
// relative velocity), f_t = -k_t delta capped at mu |f_n|, and on sliding delta is reset to
// the capped force. The history of a pair lives on the rank owning its first particle and
// moves with it (migrate_history) and into checkpoints (save/load).
//
// It runs as the inner level of the bodies' r-RESPA integration (see rigid_bodies.h): during
// the substeps of one fluid step the rigid particles (owned and ghost) are moved with their
// bodies, positions reconstructed as x^n + (c - c^n) + (R - R^n) b from the replicated body
// states, so the substeps need no halo exchange, only one reduction of body forces each.
// Walls keep their positions of the start of the step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "solver/bodies/rigid_bodies.h"
#include "solver/core/checkpoint_state.h"
#include "solver/parallel/halo.h"

namespace sph {

template <int D>
class SpringDashpotContact {
 public:
  static constexpr const char* kName = "contact";
  SpringDashpotContact(ParticleStore<D>& s, RigidBodies<D>& bodies, double stiffness,
                       double damping, double dx, bool walls, double friction = 0,
                       double tangential_stiffness = 0)
      : s_(s),
        bodies_(bodies),
        k_(stiffness),
        d_(damping),
        dx_(dx),
        walls_(walls),
        mu_(friction),
        kt_(tangential_stiffness) {}

  // Fuchs 2021 eq. 41: 0.22 sqrt(m_r/k) for the lightest rigid particle and the stiffer spring,
  // and the dashpot's own bound (dashpot_time_step).
  double time_step(double min_particle_mass) const {
    return std::min(0.22 * std::sqrt(min_particle_mass / std::max(k_, kt_)), dashpot_time_step());
  }
  // The dashpot of eq. 27 is explicit: N touching pairs damp a body's normal velocity at the
  // rate lambda = N d_c / M (and its rotation at a comparable rate), and a step h is only stable
  // for h lambda < 2. Eq. 41 bounds the spring alone, since with the paper's 2D parameters
  // (d_c = 100 on bodies of 1e-2 kg) the dashpot is never the limit; with its 3D powder
  // parameters (d_c = 1 kg/s on grains of 2.5e-11 kg) lambda is 4e10 per pair, and a step
  // bounded by the spring alone blows the grains apart within four steps. Bound: h lambda <= 1
  // with lambda = 2 d_c N / M for each free body (the 2 covers the reduced mass of two bodies
  // and the rotation), N = twice the pairs of the last evaluation (contacts form during the
  // step) and at least one pair (a first contact).
  double dashpot_time_step() const {
    double h = std::numeric_limits<double>::infinity();
    if (d_ <= 0) return h;
    for (const auto& b : bodies_.bodies()) {
      if (!b.moves_freely()) continue;
      const double pairs = std::max<double>(1, 2 * static_cast<double>(b.contacts));
      h = std::min(h, b.mass / (2 * d_ * pairs));
    }
    return h;
  }
  bool friction() const { return kt_ > 0; }
  // Candidates are collected up to this distance (dx plus the motion within a step).
  double candidate_range() const { return 1.5 * dx_; }
  bool with_walls() const { return walls_; }

  // Drifts the bodies over dt in n substeps of kick-drift-kick with the contact forces
  // (free bodies) and moves prescribed ones. Collective.
  void drift(const NeighborList<D>& nl, double dt, int substeps, double t_end, const Comm& comm);
  // Contact forces for the current body states, reduced into the bodies (contact_force,
  // contact_torque, contacts). Collective. h > 0 advances the friction history by h.
  void evaluate(const NeighborList<D>& nl, const Comm& comm, double h = 0);
  // Contact forces of the bodies as they are now, after the body table changed (phase
  // transitions rebuild bodies between steps; the next step's first contact kick uses these).
  // The friction history is kept as it is. Collective.
  void refresh(const NeighborList<D>& nl, const Comm& comm) {
    snapshot_step_start();
    evaluate(nl, comm, 0.0);
  }
  // Sends the friction history of particles that migrated to their new ranks. Collective.
  void migrate_history(Halo<D>& halo);
  // Keeps only the history of owned particles (after a resume gave every rank all of it).
  void prune_history();
  // Collective: every rank adds every rank's entries (the checkpoint attributes are written
  // collectively, so all ranks must pass the same state).
  void save(CheckpointState& state, const Comm& comm) const;
  void load(const CheckpointState& state);

 private:
  void snapshot_step_start();
  using PairKey = std::pair<ParticleId, ParticleId>;
  std::map<PairKey, Vec<D>> history_, next_history_;

  ParticleStore<D>& s_;
  RigidBodies<D>& bodies_;
  double k_, d_, dx_;
  bool walls_;
  double mu_, kt_;
  std::vector<Vec<D>> com0_;
  std::vector<RotationMatrix<D>> R0_;
  // Contact impulse of each body over the current fluid step (its mean force, see RigidBody).
  std::vector<Vec<D>> impulse_;
  std::vector<AngVec<D>> angular_impulse_;
};

}  // namespace sph
