#pragma once
// Velocity-Verlet time integration in kick-drift-kick form (Fuchs 2021 eqs. 30, 32, 38),
// with the transport velocity of Adami, Hu, Adams 2013 (eqs. 14-16 there):
//   u^{n+1/2} = u^n + dt/2 a^n,   u~^{n+1/2} = u^{n+1/2} + dt/2 a~^n,   r^{n+1} = r^n + dt
//   u~^{n+1/2}, u^{n+1} = u^{n+1/2} + dt/2 a^{n+1}.
// Owned fluid and elastic particles are integrated (elastic ones drift with u, the thesis'
// position-based Verlet, P-I eqs. 36-38, in the same kick-drift-kick form); walls follow
// their prescribed motion and rigid particles their body.
#include "solver/core/particle_store.h"

namespace sph {

// elastic = false leaves elastic particles to the elastic solid's own sub-steps
// (TimeControl.subcycle_elastic_bodies, solver/elastic/elastic_solid.h).
template <int D>
void kick(ParticleStore<D>& s, double half_dt, bool elastic = true) {
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kFluid || (elastic && s.kind[i] == Kind::kElastic))
      s.v[i] += half_dt * s.a[i];
}

template <int D>
void set_transport_velocity(ParticleStore<D>& s, Column<Vec<D>>& transport,
                            const Column<Vec<D>>& background, double half_dt) {
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kFluid) transport[i] = s.v[i] + half_dt * background[i];
}

template <int D>
void drift(ParticleStore<D>& s, const Column<Vec<D>>& advect, double dt, bool elastic = true) {
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kFluid)
      s.x[i] += dt * advect[i];
    else if (elastic && s.kind[i] == Kind::kElastic)
      s.x[i] += dt * s.v[i];
}

}  // namespace sph
