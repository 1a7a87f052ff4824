#pragma once
// Reversible melting and solidification between a SOLID and a FLUID material (Fuchs 2021,
// "Modeling thermally driven reversible phase transitions", eq. 29; Remark 4 for a
// concentration-driven transition).
//
// At the end of a step every owned particle is checked against the transition rules:
//  - a rigid particle of the solid material whose temperature (concentration) exceeds
//    T_t + hysteresis/2 leaves its body and becomes a fluid particle of the fluid material.
//    It keeps mass, position, temperature and the velocity the body gave it (eq. 36), its
//    acceleration for the next half kick is its own share of the fluid force on the body
//    (eq. 19) plus the fluid's body force, so momentum is conserved; its density starts at
//    the fluid's reference density (the wall condition gave it the density of the
//    neighbouring fluid, which may be another phase) and its pressure is the one the wall
//    condition gave it, so the forces on its neighbours do not jump;
//  - a fluid particle of the fluid material below T_t - hysteresis/2 (reversible rules only)
//    becomes a rigid particle of the solid material.
// Bodies are then regrouped (BodyRegrouping: pieces, merges and new bodies with eq. 29's
// velocities); melted particles carry their momentum into the fluid, so momentum is conserved
// throughout.
//
// Bodies that merge on touching (PhaseRule::merge_bodies): a solidified rigid particle of the
// rule's solid closer than the join radius to a rigid particle of another body of the same
// material involves both bodies, and the regrouping links them into one (BodyRegrouping::
// merge_touching). Eq. 29 links a freezing particle to the bodies within the join radius at
// the moment it freezes; a particle that froze farther away stays a body of its own for good
// unless bodies that come together later merge too. The check reads the neighbour lists of
// the step (rigid particles list their rigid neighbours when conduction or diffusion runs,
// which a transition needs), so it costs a pass over the solidified particles' non-fluid
// neighbours per step and no search.
//
// Flicker, a particle changing phase back and forth while its value hovers at the threshold,
// is what the hysteresis band prevents; the run measures it. Every particle carries the step
// of its last transition, and a transition of a particle that has changed phase before is a
// reversal: the unit counts them and keeps the fewest steps between a particle's two
// transitions. A reversal every few steps is flicker; one per thermal cycle is physics.
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/bodies/body_regrouping.h"
#include "solver/bodies/rigid_bodies.h"
#include "solver/core/checkpoint_state.h"

namespace sph {

struct PhaseRule {
  std::uint16_t solid = 0, fluid = 0;  // material indices
  double fluid_rho0 = 1;               // reference density of the fluid material
  bool temperature = true;             // driver: temperature, else concentration
  double melt_above = 0, freeze_below = 0;
  bool reversible = false;
  double join_radius = 0;
  bool merge_bodies = false;  // bodies of `solid` merge on touching
};

template <int D>
class PhaseTransitions {
 public:
  static constexpr const char* kName = "phase_transition";

  // Adds the per-particle step of the last transition to `s` (persistent: it migrates and is
  // checkpointed; zero, never, in checkpoints written before it existed).
  PhaseTransitions(ParticleStore<D>& s, std::vector<PhaseRule> rules, std::size_t max_bodies,
                   double dx)
      : rules_(std::move(rules)),
        regrouping_(largest_join_radius(rules_), max_bodies, dx, "phase_transitions[].max_bodies"),
        changed_(s.template add<std::int64_t>("phase_changed_at", kName, true)) {
    changed_.set_ghost(false);
    changed_.set_zero_if_absent(true);
    std::vector<std::uint8_t> merging;
    for (const PhaseRule& r : rules_)
      if (r.merge_bodies) {
        merging.resize(std::max<std::size_t>(merging.size(), r.solid + 1u), 0);
        merging[r.solid] = 1;
      }
    merging_ = !merging.empty();
    if (merging_) regrouping_.merge_touching(std::move(merging));
  }

  struct Outcome {
    std::int64_t melted = 0, solidified = 0;  // this step, all ranks
    // Pairs of a solidified particle and a particle of another body of its material within
    // the join radius (counted from the solidified particle; merge_bodies only), and the
    // bodies that merged into another this step (by touching, or by a freezing particle
    // linking them).
    std::int64_t touching = 0, merged = 0;
    std::string error;  // non-empty: the run cannot go on
  };

  // Collective, at the end of step `step`. `temperature`/`concentration` may be null when no
  // rule uses them; `transport` is the transport velocity column (null without TVF);
  // `fluid_body_force` the body force per unit mass on the fluid (gravity) at the end of the
  // step.
  Outcome run(ParticleStore<D>& s, const NeighborList<D>& nl, RigidBodies<D>& bodies,
              const Column<double>* temperature, const Column<double>* concentration,
              Column<Vec<D>>* transport, const Vec<D>& fluid_body_force, std::int64_t step,
              const Comm& comm);

  std::int64_t melted_total() const { return melted_total_; }
  std::int64_t solidified_total() const { return solidified_total_; }
  // Transitions of particles that had changed phase before, all ranks, since the start.
  std::int64_t reversals_total() const { return reversals_total_; }
  // The fewest steps between two transitions of one particle so far (0: no reversal yet).
  std::int64_t shortest_reversal() const { return shortest_reversal_; }
  // Bodies that merged into another, all ranks, since the start.
  std::int64_t merged_total() const { return merged_total_; }
  std::size_t max_bodies() const { return regrouping_.max_bodies(); }
  // The running totals are cumulative series: a resumed run continues them.
  void save(CheckpointState& state) const {
    state["phase_melted_total"] = static_cast<double>(melted_total_);
    state["phase_solidified_total"] = static_cast<double>(solidified_total_);
    state["phase_reversals_total"] = static_cast<double>(reversals_total_);
    state["phase_shortest_reversal"] = static_cast<double>(shortest_reversal_);
    state["phase_merged_total"] = static_cast<double>(merged_total_);
  }
  // Checkpoints written before a total was saved restart it at zero.
  void load(const CheckpointState& state) {
    auto total = [&](const char* key, std::int64_t& value) {
      if (state.count(key)) value = static_cast<std::int64_t>(state_value(state, key));
    };
    total("phase_melted_total", melted_total_);
    total("phase_solidified_total", solidified_total_);
    total("phase_reversals_total", reversals_total_);
    total("phase_shortest_reversal", shortest_reversal_);
    total("phase_merged_total", merged_total_);
  }

 private:
  static double largest_join_radius(const std::vector<PhaseRule>& rules) {
    double r = 0;
    for (const PhaseRule& rule : rules) r = std::max(r, rule.join_radius);
    return r;
  }

  std::vector<PhaseRule> rules_;
  BodyRegrouping<D> regrouping_;
  // Per particle: 1 + the step of its last transition, 0 if it has not changed phase.
  Column<std::int64_t>& changed_;
  bool merging_ = false;  // a rule's bodies merge on touching
  std::int64_t melted_total_ = 0, solidified_total_ = 0;
  std::int64_t reversals_total_ = 0, shortest_reversal_ = 0;
  std::int64_t merged_total_ = 0;
};

}  // namespace sph
