#pragma once
// How far fluid has crossed into a wall or a body. The solid fraction of a fluid particle in
// a solid object (one wall, one body) is the share of its kernel support covered by that
// object's dummy particles,
//   phi_i = sum_{j in object} V_j W_ij,  V_j = dx^d (the dummies' lattice volume).
// With the quintic kernel it is 0.22 for a particle in the first layer at a flat wall, 0.5 at
// the wall surface, 0.78 half a spacing inside and 0.94 one spacing inside. Taken per object,
// a particle squeezed between two solids (a disk landing on the floor) stays near 0.5 in each
// although the two together cover its whole support. A particle past
// guards.max_solid_fraction (0.9) has crossed into the object: a leaking wall condition, a
// body driven through the fluid faster than the pressure can push the fluid away.
#include <array>
#include <cstddef>
#include <cstdint>

#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"

namespace sph {

struct SolidFractionScan {
  double max = 0;         // largest phi over owned fluid particles and objects
  std::size_t worst = 0;  // its particle index (valid when max > 0)
};

// `wall_index` (per particle, may be null without walls) names the wall of a wall particle,
// `body_index` (may be null without bodies) the body of a rigid particle.
template <int D>
SolidFractionScan solid_fraction(const ParticleStore<D>& s, const NeighborList<D>& nl,
                                 const PairKernel<D>& pk, double dummy_volume,
                                 const std::uint16_t* wall_index, const std::int32_t* body_index) {
  SolidFractionScan out;
  // The objects around one particle: a few at most (a wall, a body, a second body); more
  // share the last slot, which can only make the guard more cautious.
  constexpr int kSlots = 8;
  constexpr std::int64_t kElasticKey = -(std::int64_t{1} << 40);
  std::array<std::int64_t, kSlots> key{};
  std::array<double, kSlots> sum{};
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kFluid) continue;
    int used = 0;
    // The solid neighbours follow the fluid ones. Most fluid particles have none: the values
    // are asked for (evaluated, with PAIR_KERNEL_STREAM) only for those that do.
    const std::uint32_t* list = nl.begin(i);
    const std::uint32_t* solid = nl.fluid_end(i);
    if (solid == nl.end(i)) continue;
    const double* w = pk.weights(nl, i);
    for (const std::uint32_t* jp = solid; jp != nl.end(i); ++jp) {
      const std::uint32_t j = *jp;
      // Walls are keys >= 0, rigid bodies < 0, and the elastic bodies one key below them all
      // (taken together, which can only make the guard more cautious).
      const std::int64_t k = s.kind[j] == Kind::kWall      ? (wall_index ? wall_index[j] : 0)
                             : s.kind[j] == Kind::kElastic ? kElasticKey
                                                           : -1 - (body_index ? body_index[j] : 0);
      int slot = 0;
      while (slot < used && key[static_cast<std::size_t>(slot)] != k) ++slot;
      if (slot == used) {
        if (used < kSlots) {
          key[static_cast<std::size_t>(used)] = k;
          sum[static_cast<std::size_t>(used)] = 0;
          ++used;
        } else {
          slot = kSlots - 1;
        }
      }
      sum[static_cast<std::size_t>(slot)] += w[jp - list];
    }
    for (int slot = 0; slot < used; ++slot) {
      const double phi = dummy_volume * sum[static_cast<std::size_t>(slot)];
      if (phi > out.max) {
        out.max = phi;
        out.worst = i;
      }
    }
  }
  return out;
}

}  // namespace sph
