#pragma once
// Checkpoints: everything needed to continue a run bit for bit. Every persistent particle
// column is stored bytewise under /particles/<column>, and the integrator and output state
// as attributes of /state. The file is written under a temporary name and renamed into place,
// so a checkpoint on disk is always complete. Reading gives each rank a contiguous slice of
// the particles; the caller then migrates them to their owners, so a checkpoint can be
// resumed on any number of ranks.
#include <map>
#include <string>

#include "solver/core/checkpoint_state.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"

namespace sph {

template <int D>
void write_checkpoint(const Comm& comm, const std::string& path, const ParticleStore<D>& s,
                      const CheckpointState& state);

// Throws std::runtime_error naming what does not match (dimension, a missing column).
template <int D>
CheckpointState read_checkpoint(const Comm& comm, const std::string& path, ParticleStore<D>& s);

}  // namespace sph
