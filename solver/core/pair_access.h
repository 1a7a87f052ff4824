#pragma once
// What the passes over pairs read of pair k of a particle, from the double values (table or
// stream: r, W, dW/dr) or as the compact table keeps them (W and (dW/dr) / r in single
// precision, read without a widened copy: no division by r, and r_ij^2 from the positions
// where a pass needs it). A pass is written once against this shape and instantiated for
// both; the double form computes exactly what the passes computed before it existed, to the
// bit, so each method keeps the order of operations of the expression it stands for.
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "solver/core/pair_kernel.h"

namespace sph {

struct ExactPairs {
  const double *r, *w, *dw;
  // Coincident particles (no direction; the passes skip them).
  template <class V>
  bool coincident(std::size_t k, const V& /*rij*/) const {
    return r[k] == 0.0;
  }
  bool coincident(std::size_t k) const { return r[k] == 0.0; }
  double dwdr_r(std::size_t k) const { return dw[k] / r[k]; }
  // x / r * dW/dr (the conduction flux of Cleary & Monaghan).
  double over_r_times_dwdr(double x, std::size_t k) const { return x / r[k] * dw[k]; }
  // x dW/dr / r (a V_j grad W_ij written as (V_j dW/dr / r) x_ij).
  double times_dwdr_over_r(double x, std::size_t k) const { return x * dw[k] / r[k]; }
  // r_ij, for the passes that need the distance itself (a unit vector, the nearest pair).
  template <class V>
  double distance(std::size_t k, const V& /*rij*/) const {
    return r[k];
  }
  // dW/dr at the distance r = distance(k, rij).
  double dwdr_at(std::size_t k, double /*r*/) const { return dw[k]; }
  template <class V>
  double r2(std::size_t k, const V& /*rij*/) const {
    return r[k] * r[k];
  }
  double W(std::size_t k) const { return w[k]; }
  // dW/dr and r as DummyPair takes them (it divides the one by the other).
  double dummy_dwdr(std::size_t k) const { return dw[k]; }
  double dummy_r(std::size_t k) const { return r[k]; }
};

struct CompactPairs {
  const float *w, *dw_r;
  template <class V>
  bool coincident(std::size_t /*k*/, const V& rij) const {
    return rij.squaredNorm() == 0.0;
  }
  // Without the positions: (dW/dr) / r is 0 exactly where r = 0 (both kernels' dW/dr vanish
  // there; PairKernel divides by 1), and elsewhere only where the pair adds nothing anyway.
  bool coincident(std::size_t k) const { return dw_r[k] == 0.0f; }
  double dwdr_r(std::size_t k) const { return dw_r[k]; }
  double over_r_times_dwdr(double x, std::size_t k) const {
    return x * static_cast<double>(dw_r[k]);
  }
  double times_dwdr_over_r(double x, std::size_t k) const {
    return x * static_cast<double>(dw_r[k]);
  }
  template <class V>
  double distance(std::size_t /*k*/, const V& rij) const {
    return std::sqrt(rij.squaredNorm());
  }
  double dwdr_at(std::size_t k, double r) const { return static_cast<double>(dw_r[k]) * r; }
  template <class V>
  double r2(std::size_t /*k*/, const V& rij) const {
    return rij.squaredNorm();
  }
  double W(std::size_t k) const { return w[k]; }
  double dummy_dwdr(std::size_t k) const { return dw_r[k]; }
  double dummy_r(std::size_t /*k*/) const { return 1.0; }
};

// Calls pass(std::bool_constant<kCompact>{}) with the form pk keeps its values in, so that a
// pass written once against pairs_of<kCompact> runs on either:
//   with_pair_form(ctx.pairs, [&](auto compact) { sweep<decltype(compact)::value>(ctx); });
template <int D, class Pass>
decltype(auto) with_pair_form(const PairKernel<D>& pk, Pass&& pass) {
  if (pk.compact()) return pass(std::true_type{});
  return pass(std::false_type{});
}

// Particle i's pairs in the form the instantiation reads.
template <bool kCompact, int D>
auto pairs_of(const PairKernel<D>& pk, const NeighborList<D>& nl, std::size_t i) {
  if constexpr (kCompact) {
    const CompactPairValues g = pk.compact_of(nl, i);
    return CompactPairs{g.w, g.dw_r};
  } else {
    const PairValues g = pk.of(nl, i);
    return ExactPairs{g.r, g.w, g.dw};
  }
}

}  // namespace sph
