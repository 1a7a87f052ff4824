#pragma once
// How sharp the interfaces between fluid phases stay. The foreign share of a fluid particle is
// the part of its kernel support covered by fluid of another phase (another fluid material),
//   psi_i = sum_{j fluid, material_j != material_i} V_j W_ij / sum_{j incl. i} V_j W_ij,
// with V_j = m_j / rho_j for fluid and the lattice volume dx^d for wall and rigid dummies (which
// count in the support but belong to no phase). At a flat interface the first layer has
// psi = 0.22 with the quintic kernel and a particle on the interface 0.5; a particle past 0.5
// has more of the other phase around it than of its own and solids together: it sits on the
// wrong side of the interface, as a gas particle trapped in the liquid, a liquid particle torn
// off into the gas or a filament thinner than the kernel. A sharp interface keeps the count of
// such stray particles at a small share of those along the interface; interface mixing, the
// classic failure of multi-phase SPH at high density ratio, makes it grow without bound.
// A film of melt on a grain (rigid dummies on one side, gas on the other) stays below 0.5
// because the grain counts in the support. In 2D a lone particle has psi = 0.69, a filament
// one spacing thick 0.44: the count finds particles torn off or trapped, not thin sheets.
#include <cstddef>
#include <cstdint>

#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"

namespace sph {

struct PhaseMixingScan {
  std::size_t stray = 0;      // owned fluid particles with psi > 0.5
  std::size_t interface = 0;  // owned fluid particles with any fluid of another phase in reach
};

template <int D>
PhaseMixingScan phase_mixing(const ParticleStore<D>& s, const NeighborList<D>& nl,
                             const PairKernel<D>& pk, double w0, double dummy_volume) {
  PhaseMixingScan out;
  const std::uint16_t* mat = s.material.data();
  const Kind* kind = s.kind.data();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (kind[i] != Kind::kFluid) continue;
    const std::uint32_t* list = nl.begin(i);
    const std::uint32_t* end = nl.end(i);
    const std::uint32_t* jp = list;
    // Most particles have no foreign neighbour: the kernel values are asked for (evaluated,
    // with PAIR_KERNEL_STREAM) only for those that do.
    while (jp != end && (kind[*jp] != Kind::kFluid || mat[*jp] == mat[i])) ++jp;
    if (jp == end) continue;
    ++out.interface;
    const double* w = pk.weights(nl, i);
    double foreign = 0, all = s.m[i] / s.rho[i] * w0;
    for (jp = list; jp != end; ++jp) {
      const std::uint32_t j = *jp;
      const bool fluid = kind[j] == Kind::kFluid;
      const double vw = (fluid ? s.m[j] / s.rho[j] : dummy_volume) * w[jp - list];
      all += vw;
      if (fluid && mat[j] != mat[i]) foreign += vw;
    }
    if (foreign > 0.5 * all) ++out.stray;
  }
  return out;
}

}  // namespace sph
