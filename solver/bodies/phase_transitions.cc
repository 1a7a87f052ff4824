#include "solver/bodies/phase_transitions.h"

#include <algorithm>
#include <limits>

namespace sph {

template <int D>
typename PhaseTransitions<D>::Outcome PhaseTransitions<D>::run(
    ParticleStore<D>& s, const NeighborList<D>& nl, RigidBodies<D>& bodies,
    const Column<double>* temperature, const Column<double>* concentration,
    Column<Vec<D>>* transport, const Vec<D>& fluid_body_force, std::int64_t step,
    const Comm& comm) {
  Outcome out;
  auto& bs = bodies.bodies();
  auto& body = bodies.body_index();
  const std::size_t nb = bs.size();
  auto value = [&](const PhaseRule& r, std::size_t i) {
    return r.temperature ? (*temperature)[i] : (*concentration)[i];
  };
  // 1. Decide on the state at the end of the step (ghosts as built at its start, like the
  //    owned particles' kinds and bodies), before anything changes: rank-independent.
  std::vector<std::pair<std::size_t, const PhaseRule*>> melt, freeze;
  // Per body, then the counts of melted, solidified, reversing and touching particles.
  std::vector<std::int64_t> involved(nb + 4, 0);
  // Bodies that merge on touching link at the regrouping's radius, so that every pair found
  // here links there and the check does not find the same pair again next step.
  const double merge_r2 = regrouping_.join_radius() * regrouping_.join_radius();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    bool melts = false;
    for (const PhaseRule& r : rules_) {
      if (s.kind[i] == Kind::kRigid && s.material[i] == r.solid && value(r, i) > r.melt_above) {
        melt.push_back({i, &r});
        involved[static_cast<std::size_t>(body[i])] = 1;
        melts = true;
        break;
      }
      if (s.kind[i] == Kind::kFluid && r.reversible && s.material[i] == r.fluid &&
          value(r, i) < r.freeze_below) {
        freeze.push_back({i, &r});
        // Every body it could join is involved (a new particle may bridge two bodies).
        const double jr2 = r.join_radius * r.join_radius;
        for (const std::uint32_t* jp = nl.begin(i); jp != nl.end(i); ++jp)
          if (s.kind[*jp] == Kind::kRigid && s.material[*jp] == r.solid &&
              (s.x[i] - s.x[*jp]).squaredNorm() < jr2)
            involved[static_cast<std::size_t>(body[*jp])] = 1;
        break;
      }
    }
    // A solidified particle (rigid, its last transition a freezing) next to a particle of
    // another body of its material: both bodies merge. Seen from the solidified particle's
    // owner, whose list is the same on any rank count.
    if (merging_ && !melts && s.kind[i] == Kind::kRigid && changed_[i] > 0 &&
        regrouping_.merges(s.material[i]))
      for (const std::uint32_t* jp = nl.fluid_end(i); jp != nl.end(i); ++jp) {
        const std::uint32_t j = *jp;
        if (s.kind[j] != Kind::kRigid || s.material[j] != s.material[i] || body[j] == body[i] ||
            body[j] < 0 || (s.x[i] - s.x[j]).squaredNorm() >= merge_r2)
          continue;
        involved[static_cast<std::size_t>(body[i])] = 1;
        involved[static_cast<std::size_t>(body[j])] = 1;
        ++involved[nb + 3];
      }
  }
  // Reversals: particles changing phase again, and the fewest steps since their last change.
  std::int64_t shortest = std::numeric_limits<std::int64_t>::max();
  for (const auto* list : {&melt, &freeze})
    for (const auto& [i, r] : *list) {
      if (changed_[i] > 0) {
        ++involved[nb + 2];
        shortest = std::min(shortest, step + 1 - changed_[i]);
      }
      changed_[i] = step + 1;
    }
  involved[nb] = static_cast<std::int64_t>(melt.size());
  involved[nb + 1] = static_cast<std::int64_t>(freeze.size());
  comm.sum_inplace(involved);
  out.melted = involved[nb];
  out.solidified = involved[nb + 1];
  out.touching = involved[nb + 3];
  if (out.melted == 0 && out.solidified == 0 && out.touching == 0) return out;
  melted_total_ += out.melted;
  solidified_total_ += out.solidified;
  if (involved[nb + 2] > 0) {  // a global count: every rank takes part in the minimum
    reversals_total_ += involved[nb + 2];
    shortest = comm.min(shortest);
    shortest_reversal_ = shortest_reversal_ > 0 ? std::min(shortest_reversal_, shortest) : shortest;
  }

  // 2. Apply the change of phase to the owned particles. Forces for the next half kick: the
  //    body received the sum of its particles' fluid forces (eq. 19) in this step's last
  //    half kick, and the next one must hand out the same sum, split anew, or momentum is
  //    lost. A melted particle takes its own share f_r (plus the fluid's body force), not
  //    the body's acceleration at its place (eq. 36), which includes the pull of the rest of
  //    the body that keeps it on the rigid motion, a force nothing balances once the particle
  //    is fluid, so the total momentum would drift (docs/effects.md, "Design measurements").
  //    A frozen particle brings its force as a fluid particle, m (a - b), into its body's
  //    sum; its share from rigid neighbours is balanced in their bodies' sums.
  auto& fluid_force = bodies.fluid_force();
  for (const auto& [i, r] : melt) {
    s.kind[i] = Kind::kFluid;
    s.material[i] = r->fluid;
    body[i] = -1;
    s.a[i] = fluid_force[i] / s.m[i] + fluid_body_force;
    s.rho[i] = r->fluid_rho0;
    if (transport) (*transport)[i] = s.v[i];
  }
  for (const auto& [i, r] : freeze) {
    s.kind[i] = Kind::kRigid;
    s.material[i] = r->solid;
    body[i] = -1;  // assigned by the regrouping
    fluid_force[i] = s.m[i] * (s.a[i] - fluid_body_force);
  }

  // 3. Rebuild the bodies that lost or may gain particles, or touch.
  out.error =
      regrouping_.run(s, bodies, involved, comm, merging_ ? &changed_ : nullptr, &out.merged);
  merged_total_ += out.merged;
  return out;
}

template class PhaseTransitions<2>;
template class PhaseTransitions<3>;

}  // namespace sph
