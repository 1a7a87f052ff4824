#pragma once
// Density by kernel summation over all neighbours (fluid, wall and rigid):
// rho_i = m_i sum_j W_ij (Fuchs 2021 eq. 14). Exact mass conservation; suited to confined flows.
#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"

namespace sph {

template <int D, class K>
class DensitySummation {
 public:
  static constexpr const char* kName = "density_summation";
  DensitySummation(ParticleStore<D>& s, const K& kernel) : s_(s), k_(kernel) {}

  void run(const NeighborList<D>& nl, const PairKernel<D>& pk) {
    const double w0 = k_.W(0.0);
    for (std::size_t i = 0; i < s_.owned(); ++i) {
      if (s_.kind[i] != Kind::kFluid) continue;
      double sum = w0;
      const double* g_w = pk.weights(nl, i);
      for (const std::uint32_t* j = nl.begin(i); j != nl.end(i); ++j, ++g_w) sum += *g_w;
      s_.rho[i] = s_.m[i] * sum;
    }
  }

 private:
  ParticleStore<D>& s_;
  const K& k_;
};

}  // namespace sph
