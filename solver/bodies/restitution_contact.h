#pragma once
// Hard-body contact by impulses (v1::RESTITUTION; Johnson & Tezduyar 1996, Reder et al. 2021
// eqs. 25-26): before the bodies drift over a fluid step, every pair of bodies (and every body
// with each wall) whose particles would touch within the step gets the collision impulse of
// restitution_impulse.h, as Reder's step 8 checks the velocities for an overlap they would
// produce in the step. A contact of body p with body q (or wall w) gathers the rigid-particle
// pairs (r of p, r' of q) with
//   |x_r - x_r'| - dx < dt max(0, -(v_r - v_r') . e_rr'),   e_rr' = (x_r - x_r') / |x_r - x_r'|,
// its normal the normalised sum of their e_rr' and its point the mean of their midpoints.
// Simultaneous contacts are resolved by sweeping over all of them, in a fixed order, until
// none approaches (at most kMaxSweeps sweeps), so a body wedged between others or in a corner
// gets the impulses of all its contacts.
//
// Every rank gathers all candidate pairs once per step (positions and the walls' velocities at
// the start of the drift) and resolves them in the order of the particle ids on the replicated
// body table: the same impulses to the bit on any number of ranks, and no reduction.
// Stateless between steps: nothing to migrate or checkpoint.
#include <limits>
#include <vector>

#include "solver/bodies/body_contact.h"

namespace sph {

template <int D>
class RestitutionContact final : public BodyContact<D> {
 public:
  static constexpr int kMaxSweeps = 50;
  // wall_index: which wall each wall particle belongs to (null: one wall).
  RestitutionContact(ParticleStore<D>& s, RigidBodies<D>& bodies, double restitution,
                     double friction, double dx, bool walls,
                     const Column<std::uint16_t>* wall_index)
      : s_(s),
        bodies_(bodies),
        e_(restitution),
        mu_(friction),
        dx_(dx),
        walls_(walls),
        wall_index_(wall_index) {}

  double time_step(double) const override { return std::numeric_limits<double>::infinity(); }
  double touch_range() const override { return dx_; }
  double candidate_range() const override { return 1.5 * dx_; }
  bool with_walls() const override { return walls_; }
  void drift(const NeighborList<D>& nl, double dt, int substeps, double t_end,
             const Comm& comm) override;
  // Impulses act within a step's drift; between steps there is no contact force.
  void refresh(const NeighborList<D>&, const Comm&) override {}

  // A candidate pair: rigid particle r of body `body` and particle r' of body `partner`
  // (>= 0, > body) or of wall -1 - partner.
  struct Pair {
    ParticleId id_r, id_other;
    std::int32_t body, partner;
    Vec<D> x_r, x_other, v_wall;
  };
  // The impulses for the gathered pairs over a step dt; returns the contacts that got one.
  // Public for tests.
  std::int64_t resolve(const std::vector<Pair>& pairs, double dt);

 private:
  std::vector<Pair> gather(const NeighborList<D>& nl, const Comm& comm) const;

  ParticleStore<D>& s_;
  RigidBodies<D>& bodies_;
  double e_, mu_, dx_;
  bool walls_;
  const Column<std::uint16_t>* wall_index_;
  std::vector<Vec<D>> impulse_;
  std::vector<AngVec<D>> angular_impulse_;
};

}  // namespace sph
