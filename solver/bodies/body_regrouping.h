#pragma once
// Rebuilding bodies after some of their particles changed (Fuchs 2021, "Modeling thermally
// driven reversible phase transitions", eq. 29): phase transitions (a particle melted out of
// a body, or froze onto one) and open boundaries (a body's particles left through an outlet)
// both end here.
//
// The rigid particles of every involved body, and the rigid particles without a body (body
// index -1: solidified this step), are linked when closer than the join radius and either in
// the same body or one of them new. Each connected piece becomes a body: a piece of an old
// body keeps it (a body broken in two becomes two), a piece joining several bodies merges
// them, a piece of only new particles starts a new body. Mass, centre of mass and inertia are
// recomputed from the particles (eqs. 20-23, Remark 13). A piece of one old body keeps its
// angular velocity and gets u_k = u'_k + omega_k x (r_k - r'_k) (eq. 29); a merged or new
// body gets the total linear and angular momentum of what it is made of. Particles that left
// a body (melted, or deleted at an outlet) take their momentum with them.
//
// Bodies that merge on touching (merge_touching, PhaseTransition.merge_bodies): a rigid
// particle of a merging material also links to one of another body of the same material when
// one of the two has solidified during the run, so two such bodies that touch become one
// piece, rebuilt like a piece a freezing particle joins (total linear and angular momentum).
// The case's own bodies, as placed, do not glue to each other: only what froze does.
//
// Bodies cut at an outlet (Pieces::kWhole) are not split: a rigid body stays one body however
// much of it is gone, even if what remains is not connected (a body built of separate shapes,
// or a non-convex one cut across), so the pieces of each old body are simply its remaining
// particles and no new bodies arise.
//
// Forces: a rebuilt body gets the sum of its own particles' fluid forces (eq. 19) and their
// moments about its new centre (eqs. 24-26), not its parent's: a piece broken off a body
// would otherwise be kicked with the whole body's force over its own small mass. A new
// particle brings the force the caller put in its fluid_force entry (PhaseTransitions: its
// force as a fluid particle), so the next half kick hands out what the last one did and
// momentum is conserved. The contact force of a rebuilt
// body is zero: the simulation evaluates contact again with the new bodies
// (SpringDashpotContact::refresh) after searching neighbours again. Its mean contact force
// over the last step (what the fluid's wall condition sees, RigidBody) is each parent's in
// proportion to the mass the piece took from it.
//
// Parallel: the particles taking part are gathered on every rank (ordered by id) and every
// rank runs the same union-find, so the body table stays replicated and results do not depend
// on the rank count. Only steps that change a body pay for the gather, and only for the
// bodies involved.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/bodies/rigid_bodies.h"

namespace sph {

template <int D>
class BodyRegrouping {
 public:
  // kConnected: eq. 29's pieces (phase transitions); kWhole: each old body stays one (outlets).
  enum class Pieces { kConnected, kWhole };

  // `slots_field`: the case field that sets max_bodies, named in the error when a regrouping
  // needs more bodies at once.
  BodyRegrouping(double join_radius, std::size_t max_bodies, double dx, std::string slots_field)
      : join_radius_(join_radius),
        max_bodies_(max_bodies),
        dx_(dx),
        slots_field_(std::move(slots_field)) {}

  // Bodies that only lose particles (cut at an outlet) and are never split.
  static BodyRegrouping whole_bodies(double dx) {
    BodyRegrouping r(0.0, 0, dx, "");
    r.pieces_ = Pieces::kWhole;
    return r;
  }

  std::size_t max_bodies() const { return max_bodies_; }
  double join_radius() const { return join_radius_; }

  // Bodies of the materials marked in `by_material` (indexed by material) merge on touching.
  void merge_touching(std::vector<std::uint8_t> by_material) { merging_ = std::move(by_material); }
  // Whether rigid particles of material m link across bodies (merge_touching).
  bool merges(std::uint16_t m) const { return m < merging_.size() && merging_[m] != 0; }

  // `involved[k] != 0` for the bodies that lost or may gain particles (the first
  // bodies().size() entries, identical on every rank). Sets the body index, body-frame
  // offset, rigid velocity (eq. 40) and acceleration (as RigidBodies::place_owned_particles)
  // of the owned particles of the rebuilt bodies; a piece of one body keeps the rigid motion
  // of its particles, accelerations included (the wall condition may read them before the
  // next placement: a cut at an outlet happens mid-step). Collective. Returns an error when
  // the run cannot go on, else "". `solidified` (with merge_touching): per owned particle,
  // non-zero when a rigid particle solidified during the run. `merged`, if given, is increased
  // by the number of old bodies that merged into another (identical on every rank).
  std::string run(ParticleStore<D>& s, RigidBodies<D>& bodies,
                  const std::vector<std::int64_t>& involved, const Comm& comm,
                  const Column<std::int64_t>* solidified = nullptr,
                  std::int64_t* merged = nullptr) const;

 private:
  struct Record {  // a particle taking part in a regrouping
    ParticleId id;
    std::int32_t old_body;  // -1: new
    std::uint16_t material;
    std::uint8_t merges;      // links across bodies of its material (merge_touching)
    std::uint8_t solidified;  // solidified during the run
    double m;
    Vec<D> x, v;
    Vec<D> f;  // fluid force on the particle (eq. 19) of this step; zero for a new one
  };
  std::string regroup(std::vector<Record>& recs, const std::vector<std::int64_t>& involved,
                      RigidBodies<D>& bodies, std::int64_t& merged) const;

  // Which records form each piece: indices into the id-ordered records, keyed by their
  // smallest index.
  std::map<std::size_t, std::vector<std::size_t>> pieces_of(const std::vector<Record>& recs) const;

  Pieces pieces_ = Pieces::kConnected;
  double join_radius_;
  std::size_t max_bodies_;
  double dx_;
  std::string slots_field_;
  std::vector<std::uint8_t> merging_;  // per material: merges on touching
};

}  // namespace sph
