#pragma once
// Reversible melting and solidification between a SOLID and a FLUID material (Fuchs 2021,
// "Modeling thermally driven reversible phase transitions", eq. 29; Remark 4 for a
// concentration-driven transition).
//
// At the end of a step every owned particle is checked against the transition rules:
//  - a rigid particle of the solid material whose temperature (concentration) exceeds
//    T_t + hysteresis/2 leaves its body and becomes a fluid particle of the fluid material.
//    It keeps mass, position, temperature and the velocity the body gave it (eq. 36), its
//    acceleration for the next half kick is the body's at its place; its density starts at
//    the fluid's reference density (the wall condition gave it the density of the
//    neighbouring fluid, which may be another phase) and its pressure is the one the wall
//    condition gave it, so the forces on its neighbours do not jump;
//  - a fluid particle of the fluid material below T_t - hysteresis/2 (reversible rules only)
//    becomes a rigid particle of the solid material.
// Bodies are then regrouped: the rigid particles of every body that lost or may gain
// particles, and the new rigid particles, are linked when closer than the join radius and
// either in the same body or one of them new. Each connected piece becomes a body: a piece of
// an old body keeps it (a body broken in two becomes two), a piece joining several bodies
// merges them, a piece of only new particles starts a new body. Mass, centre of mass and
// inertia are recomputed from the particles (eqs. 20-23, Remark 13). A piece of one old body
// keeps its angular velocity and gets u_k = u'_k + omega_k x (r_k - r'_k) (eq. 29); a merged
// or new body gets the total linear and angular momentum of what it is made of. Melted
// particles carry their momentum into the fluid, so momentum is conserved throughout.
//
// Forces: the next step's first half kick (eq. 31) uses the fluid force and torque of the
// step that just ended. A rebuilt body gets the sum of its own particles' fluid forces
// (eq. 19) and their moments about its new centre (eqs. 24-26), not its parent's: a piece
// broken off a body would otherwise be kicked with the whole body's force over its own small
// mass. A particle frozen this step brings no fluid force (its force as a fluid particle
// mixes in rigid and wall neighbours), one step's half kick of one particle's force. The
// contact force of a rebuilt body is zero here: the simulation evaluates contact again with
// the new bodies (SpringDashpotContact::refresh) after searching neighbours again. Its mean
// contact force over the last step (what the fluid's wall condition sees, RigidBody) is
// each parent's in proportion to the mass the piece took from it.
//
// Parallel: the particles taking part in a regrouping are gathered on every rank (ordered by
// id) and every rank runs the same union-find, so the body table stays replicated and results
// do not depend on the rank count. Only steps with a transition pay for the gather, and only
// for the bodies involved.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/bodies/rigid_bodies.h"
#include "solver/io/checkpoint_state.h"

namespace sph {

struct PhaseRule {
  std::uint16_t solid = 0, fluid = 0;  // material indices
  double fluid_rho0 = 1;               // reference density of the fluid material
  bool temperature = true;             // driver: temperature, else concentration
  double melt_above = 0, freeze_below = 0;
  bool reversible = false;
  double join_radius = 0;
};

template <int D>
class PhaseTransitions {
 public:
  static constexpr const char* kName = "phase_transition";

  PhaseTransitions(std::vector<PhaseRule> rules, std::size_t max_bodies, double dx)
      : rules_(std::move(rules)), max_bodies_(max_bodies), dx_(dx) {}

  struct Outcome {
    std::int64_t melted = 0, solidified = 0;  // this step, all ranks
    std::string error;                        // non-empty: the run cannot go on
  };

  // Collective. `temperature`/`concentration` may be null when no rule uses them;
  // `transport` is the transport velocity column (null without TVF).
  Outcome run(ParticleStore<D>& s, const NeighborList<D>& nl, RigidBodies<D>& bodies,
              const Column<double>* temperature, const Column<double>* concentration,
              Column<Vec<D>>* transport, const Comm& comm);

  std::int64_t melted_total() const { return melted_total_; }
  std::int64_t solidified_total() const { return solidified_total_; }
  std::size_t max_bodies() const { return max_bodies_; }
  // The running totals are cumulative series: a resumed run continues them.
  void save(CheckpointState& state) const {
    state["phase_melted_total"] = static_cast<double>(melted_total_);
    state["phase_solidified_total"] = static_cast<double>(solidified_total_);
  }
  // Checkpoints written before the totals were saved restart them at zero.
  void load(const CheckpointState& state) {
    if (state.count("phase_melted_total"))
      melted_total_ = static_cast<std::int64_t>(state_value(state, "phase_melted_total"));
    if (state.count("phase_solidified_total"))
      solidified_total_ = static_cast<std::int64_t>(state_value(state, "phase_solidified_total"));
  }

 private:
  struct Record {  // a particle taking part in a regrouping
    ParticleId id;
    std::int32_t old_body;  // -1: solidified this step
    double m;
    Vec<D> x, v;
    Vec<D> f;  // fluid force on the particle (eq. 19) of this step; zero for a new one
  };
  // involved[k] != 0 for the bodies taking part (the first bodies().size() entries).
  void regroup(std::vector<Record>& recs, const std::vector<std::int64_t>& involved,
               RigidBodies<D>& bodies, Outcome& out) const;

  std::vector<PhaseRule> rules_;
  std::size_t max_bodies_;
  double dx_;
  std::int64_t melted_total_ = 0, solidified_total_ = 0;
};

}  // namespace sph
