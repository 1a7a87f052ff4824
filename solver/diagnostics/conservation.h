#pragma once
// Conservation diagnostics of the fluid, reduced over ranks: mass, linear momentum, kinetic,
// potential (with respect to gravity) and elastic energy. Their sum is what an SPH fluid
// conserves without viscosity: kinetic and potential alone swing with the acoustic waves, by
// enough to hide what viscosity takes from a decaying wave (docs/effects.md, "Design
// measurements").
#include <vector>

#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D>
struct ConservationSample {
  double mass = 0, kinetic = 0, potential = 0, elastic = 0;
  Vec<D> momentum = Vec<D>::Zero();
  double fluid_particles = 0;
};

template <int D>
ConservationSample<D> conservation(const ParticleStore<D>& s,
                                   const std::vector<FluidConstants>& fluids, const Vec<D>& gravity,
                                   const Comm& comm) {
  std::vector<double> acc(5 + D, 0.0);
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kFluid) continue;
    const double m = s.m[i];
    acc[0] += m;
    acc[1] += 0.5 * m * s.v[i].squaredNorm();
    acc[2] -= m * gravity.dot(s.x[i]);
    acc[3] += 1;
    acc[4] += m * fluids[s.material[i]].elastic_energy(s.rho[i]);
    for (int a = 0; a < D; ++a) acc[5 + static_cast<size_t>(a)] += m * s.v[i][a];
  }
  comm.sum_inplace(acc);
  ConservationSample<D> out;
  out.mass = acc[0];
  out.kinetic = acc[1];
  out.potential = acc[2];
  out.fluid_particles = acc[3];
  out.elastic = acc[4];
  for (int a = 0; a < D; ++a) out.momentum[a] = acc[5 + static_cast<size_t>(a)];
  return out;
}

}  // namespace sph
