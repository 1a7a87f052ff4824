#pragma once
// Contact forces between particles of different rigid bodies and between rigid particles and
// wall particles: the spring-dashpot (below), or instead the short-range repulsion of
// Glowinski et al. 1999 (Reder et al. 2021 eq. 24, repulsive_force.h) on the same pairs.
// Spring-dashpot (Fuchs 2021 eq. 27, Remark 17):
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

#include "solver/bodies/body_contact.h"
#include "solver/bodies/repulsive_force.h"

namespace sph {

// The pair law and its parameters (v1::Contact).
struct ParticleContactLaw {
  double stiffness = 0;  // k_c
  double damping = 0;    // d_c
  // >= 0: the dashpot of each pair is 2 zeta sqrt(k_c m_eff) with m_eff the reduced mass of
  // the two bodies (from a requested restitution, restitution_damping.h); < 0: `damping`.
  double damping_ratio = -1;
  double friction = 0, tangential_stiffness = 0;
  // > 0: Glowinski's repulsion of this strength and range instead of eq. 27.
  double repulsion_strength = 0, repulsion_range = 0;
};

template <int D>
class SpringDashpotContact final : public BodyContact<D> {
 public:
  SpringDashpotContact(ParticleStore<D>& s, RigidBodies<D>& bodies, double stiffness,
                       double damping, double dx, bool walls, double friction = 0,
                       double tangential_stiffness = 0)
      : SpringDashpotContact(
            s, bodies,
            ParticleContactLaw{stiffness, damping, -1, friction, tangential_stiffness, 0, 0}, dx,
            walls) {}
  SpringDashpotContact(ParticleStore<D>& s, RigidBodies<D>& bodies, const ParticleContactLaw& law,
                       double dx, bool walls)
      : s_(s),
        bodies_(bodies),
        k_(law.stiffness),
        d_(law.damping),
        zeta_(law.damping_ratio),
        dx_(dx),
        walls_(walls),
        mu_(law.friction),
        kt_(law.tangential_stiffness),
        repulsion_(law.repulsion_strength, law.repulsion_range) {}

  // Fuchs 2021 eq. 41: 0.22 sqrt(m_r/k) for the lightest rigid particle and the stiffer spring,
  // and the dashpot's own bound (dashpot_time_step). The repulsion's stiffness is its slope
  // at an overlap of one range (RepulsiveForce::stiffness).
  double time_step(double min_particle_mass) const override {
    const double k = repulsive() ? repulsion_.stiffness() : std::max(k_, kt_);
    return std::min(0.22 * std::sqrt(min_particle_mass / k), dashpot_time_step());
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
  // With a damping ratio the dashpot of a body's pairs is at most 2 zeta sqrt(k_c M).
  double dashpot_time_step() const {
    double h = std::numeric_limits<double>::infinity();
    if (repulsive() || (zeta_ < 0 && d_ <= 0) || zeta_ == 0) return h;
    for (const auto& b : bodies_.bodies()) {
      if (!b.translates_freely() && !b.rotates_freely()) continue;
      const double d = zeta_ >= 0 ? 2 * zeta_ * std::sqrt(k_ * b.mass) : d_;
      const double pairs = std::max<double>(1, 2 * static_cast<double>(b.contacts));
      h = std::min(h, b.mass / (2 * d * pairs));
    }
    return h;
  }
  bool friction() const { return kt_ > 0; }
  bool repulsive() const { return repulsion_.strength > 0; }
  // Pairs interact below this distance: dx (particles touch), plus the repulsion's range.
  double touch_range() const override { return dx_ + repulsion_.range; }
  // Candidates are collected up to this distance (touch_range plus the motion within a step).
  double candidate_range() const override { return touch_range() + 0.5 * dx_; }
  bool with_walls() const override { return walls_; }

  // Drifts the bodies over dt in n substeps of kick-drift-kick with the contact forces
  // (free bodies) and moves prescribed ones. Collective.
  void drift(const NeighborList<D>& nl, double dt, int substeps, double t_end,
             const Comm& comm) override;
  // Contact forces for the current body states, reduced into the bodies (contact_force,
  // contact_torque, contacts). Collective. h > 0 advances the friction history by h.
  void evaluate(const NeighborList<D>& nl, const Comm& comm, double h = 0);
  // Contact forces of the bodies as they are now, after the body table changed (phase
  // transitions rebuild bodies between steps; the next step's first contact kick uses these).
  // The friction history is kept as it is. Collective.
  void refresh(const NeighborList<D>& nl, const Comm& comm) override {
    snapshot_step_start();
    evaluate(nl, comm, 0.0);
  }
  // Sends the friction history of particles that migrated to their new ranks. Collective.
  void migrate_history(Halo<D>& halo) override;
  // Keeps only the history of owned particles (after a resume gave every rank all of it).
  void prune_history() override;
  // Collective: every rank adds every rank's entries (the checkpoint attributes are written
  // collectively, so all ranks must pass the same state).
  void save(CheckpointState& state, const Comm& comm) const override;
  void load(const CheckpointState& state) override;

 private:
  void snapshot_step_start();
  // The dashpot of a pair of body i's particle with body j's (j < 0: a wall).
  double pair_damping(std::int32_t bi, std::int32_t bj) const {
    if (zeta_ < 0) return d_;
    const auto& bs = bodies_.bodies();
    const double inv = bs[static_cast<std::size_t>(bi)].inverse_mass() +
                       (bj < 0 ? 0.0 : bs[static_cast<std::size_t>(bj)].inverse_mass());
    return inv > 0 ? 2 * zeta_ * std::sqrt(k_ / inv) : 0.0;
  }
  using PairKey = std::pair<ParticleId, ParticleId>;
  std::map<PairKey, Vec<D>> history_, next_history_;

  ParticleStore<D>& s_;
  RigidBodies<D>& bodies_;
  double k_, d_, zeta_, dx_;
  bool walls_;
  double mu_, kt_;
  RepulsiveForce repulsion_;
  std::vector<Vec<D>> com0_;
  std::vector<RotationMatrix<D>> R0_;
  // Contact impulse of each body over the current fluid step (its mean force, see RigidBody).
  std::vector<Vec<D>> impulse_;
  std::vector<AngVec<D>> angular_impulse_;
};

}  // namespace sph
