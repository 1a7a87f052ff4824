#pragma once
// Creating and deleting particles during a run with the same outcome on any rank count.
//
// A new particle is a copy of an owned particle (every column, persistent and scratch) that
// the caller then edits (position, state). Its global id comes from a counter that every rank
// holds identically: in each call the parents of all ranks' copies are gathered and sorted
// by id, and the k-th parent's copy gets id next_id + k. So ids depend only on which
// particles spawn, never on where they live. The counter is part of the checkpoint state.
//
// One collective per call (an allgather of the parents' ids, the deletion count and the
// caller's tallies); the particle arrays are touched only when something changes on this rank.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/core/checkpoint_state.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"

namespace sph {

template <int D>
class ParticleLedger {
 public:
  // Ids from `next` on are free (the scene's particles are 0 .. next-1).
  void set_next_id(ParticleId next) { next_id_ = next; }
  ParticleId next_id() const { return next_id_; }

  struct Totals {
    std::int64_t created = 0, deleted = 0;  // over all ranks
    std::size_t first_new = 0;              // row of this rank's first copy (copies follow)
  };
  // Appends a copy of each owned row in `parents` (in that order) with a fresh id, then
  // deletes the owned rows in `doomed` (no parent may be doomed); ghosts are dropped. The
  // copies end up in rows first_new, first_new + 1, ... `tallies` are summed over ranks in
  // place (exactly: integers). Collective.
  Totals apply(ParticleStore<D>& s, const std::vector<std::uint32_t>& parents,
               const std::vector<std::uint32_t>& doomed, std::vector<std::int64_t>& tallies,
               const Comm& comm);

  void save(CheckpointState& state, const std::string& key) const;
  void load(const CheckpointState& state, const std::string& key);

 private:
  ParticleId next_id_ = 0;
};

}  // namespace sph
