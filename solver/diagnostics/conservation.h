#pragma once
// Conservation diagnostics of the fluid, reduced over ranks: mass, linear momentum, kinetic
// and potential energy (with respect to gravity), and the extreme density deviation.
#include <vector>

#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"

namespace sph {

template <int D>
struct ConservationSample {
  double mass = 0, kinetic = 0, potential = 0;
  Vec<D> momentum = Vec<D>::Zero();
  double fluid_particles = 0;
};

template <int D>
ConservationSample<D> conservation(const ParticleStore<D>& s, const Vec<D>& gravity,
                                   const Comm& comm) {
  std::vector<double> acc(4 + D, 0.0);
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kFluid) continue;
    const double m = s.m[i];
    acc[0] += m;
    acc[1] += 0.5 * m * s.v[i].squaredNorm();
    acc[2] -= m * gravity.dot(s.x[i]);
    acc[3] += 1;
    for (int a = 0; a < D; ++a) acc[4 + static_cast<size_t>(a)] += m * s.v[i][a];
  }
  comm.sum_inplace(acc);
  ConservationSample<D> out;
  out.mass = acc[0];
  out.kinetic = acc[1];
  out.potential = acc[2];
  out.fluid_particles = acc[3];
  for (int a = 0; a < D; ++a) out.momentum[a] = acc[4 + static_cast<size_t>(a)];
  return out;
}

}  // namespace sph
