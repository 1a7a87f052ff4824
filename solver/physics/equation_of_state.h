#pragma once
// Pressure of fluid particles from their density (Adami 2012 eq. 3 / Fuchs 2021 eq. 18).
#include <vector>

#include "solver/core/particle_store.h"
#include "solver/physics/fluid_table.h"

namespace sph {

template <int D>
void apply_equation_of_state(ParticleStore<D>& s, const std::vector<FluidConstants>& fluids) {
  for (std::size_t i = 0; i < s.owned(); ++i)
    if (s.kind[i] == Kind::kFluid) s.p[i] = fluids[s.material[i]].pressure(s.rho[i]);
}

}  // namespace sph
