#pragma once
// What a unit sees when the step loop calls it (solver/seam/unit.h): the particles, the
// neighbour lists and pair kernel of this step's positions, the halo to refresh the ghost
// copies of a column it computed, and the step's time. Built by the step loop once per phase;
// references only, nothing is copied.
#include <cstdint>

#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"
#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "solver/parallel/halo.h"

namespace sph {

template <int D>
struct StepContext {
  ParticleStore<D>& particles;
  const NeighborList<D>& neighbors;  // fluid neighbours first, then walls and rigid particles
  const PairKernel<D>& pairs;        // r, W and dW/dr of the listed pairs
  Halo<D>& halo;                     // halo.update(particles, {&column}) after a pass (collective)
  const Comm& comm;
  double t = 0;   // time of the state being evaluated (t^{n+1} inside a step)
  double dt = 0;  // length of the step (0 while a run is primed)
  std::int64_t step = 0;
};

}  // namespace sph
