#pragma once
// How far fluid has crossed into walls and bodies. The solid fraction of a fluid particle is
// the share of its kernel support covered by dummy (wall or rigid) particles,
//   phi_i = sum_{j dummy} V_j W_ij,  V_j = dx^d (the dummies' lattice volume).
// With the quintic kernel it is 0.22 for a particle in the first layer at a flat wall, 0.5 at
// the wall surface, 0.78 half a spacing inside and 0.94 one spacing inside; a particle
// squeezed in a closing gap between two solids reaches about 0.9. A particle past
// guards.max_solid_fraction (0.97) has crossed into the solid (a leaking wall condition, a
// body driven through the fluid faster than the pressure can push it away, or a fluid region
// that overlaps a wall from the start).
#include <cstddef>

#include "solver/core/neighbor_list.h"

namespace sph {

struct SolidFractionScan {
  double max = 0;         // largest phi over owned fluid particles
  std::size_t worst = 0;  // its particle index (valid when max > 0)
};

template <int D, class K>
SolidFractionScan solid_fraction(const ParticleStore<D>& s, const NeighborList<D>& nl,
                                 const K& kernel, double dummy_volume) {
  SolidFractionScan out;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kFluid) continue;
    double phi = 0;
    for (const std::uint32_t* j = nl.begin(i); j != nl.end(i); ++j)
      if (s.kind[*j] != Kind::kFluid) phi += kernel.W((s.x[i] - s.x[*j]).norm());
    phi *= dummy_volume;
    if (phi > out.max) {
      out.max = phi;
      out.worst = i;
    }
  }
  return out;
}

}  // namespace sph
