#pragma once
// The kernel of the pairs of a neighbour list: the distance r, W(r) and dW/dr at the positions
// of the search, given to the passes over pairs that run at those positions (density, wall
// condition, conduction, forces, solid fraction; not the continuity equation, which uses
// mid-step positions, nor probes and open-boundary samples, which are not pairs) instead of
// each of them taking the square root and the kernel polynomial, with its data-dependent
// branches, again for the same pair. The values are evaluated in loops without branches that
// vectorise (K::evaluate), and equal those the passes computed before to the bit
// (r = |x_i - x_j|, K::evaluate = W and dW), so results are unchanged.
// Three ways to keep them:
//  - kTable: every pair evaluated once when the list is built and r, W and dW/dr kept in
//    double (24 bytes a pair), the values the passes computed before the table existed, to
//    the bit.
//  - kCompact (a case's default, case/estimate.h pair_kernel_storage()): W and (dW/dr) / r kept
//    in single precision (8 bytes a pair), the two values the passes over pairs need
//    (grad W_ij = (dW/dr / r) x_ij), which they read as they are (compact_of,
//    solver/core/pair_access.h; r from the positions where a pass needs it).
//    of() still gives a particle's values in double to any pass that asks: r from the
//    positions, W widened, dW/dr = ((dW/dr) / r) r. The kernel evaluates
//    both from the squared distance and rounds them in one loop (K::evaluate_over_r; the
//    Wendland kernel's (dW/dr) / r without a division). Each value carries a relative error of
//    at most 2^-23 (1.2e-7; with Verlet lists W and dW/dr are those of the distance from the
//    single-precision square), far below the discretisation error and the same on every rank
//    count.
//  - kStream: a particle's pairs evaluated into a scratch buffer each time a pass asks for
//    them; no storage, each pass gathers and evaluates again. The same bits as kTable.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "solver/core/neighbor_list.h"

namespace sph {

// Views of the values of one particle's pairs, parallel to nl.begin(i) .. nl.end(i).
struct PairValues {
  const double* r;
  const double* w;
  const double* dw;
};

// The compact table's values of one particle's pairs: W and (dW/dr) / r.
struct CompactPairValues {
  const float* w;
  const float* dw_r;
};

template <int D>
class PairKernel {
 public:
  enum class Storage { kTable, kCompact, kStream };
  explicit PairKernel(Storage storage = Storage::kTable) : storage_(storage) {}

  // Binds the table to nl as just built from the positions of s (which the passes then use
  // unchanged) and, with kTable or kCompact, evaluates every pair of the owned particles'
  // lists.
  template <class K>
  void prepare(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    bind(s, nl, k);
    const std::size_t n = nl.pairs();
    if (storage_ == Storage::kTable) {
      fit(r_, n);
      for (std::size_t i = 0; i < s.owned(); ++i) distances(nl, i, r_.data() + nl.first(i));
      evaluate_table(n, k);
    } else if (storage_ == Storage::kCompact) {
      fit(w32_, n);
      fit(dwr32_, n);
      // The squared distances of consecutive particles' lists (which lie one after the other
      // in the storage) gathered into the double scratch until it holds a block, then
      // evaluated and rounded in one loop: few and long loops, the scratch in cache.
      std::size_t e0 = 0, e_end = 0;
      for (std::size_t i = 0; i < s.owned(); ++i) {
        e_end = nl.first(i) + static_cast<std::size_t>(nl.end(i) - nl.begin(i));
        grow_scratch(e_end - e0);
        squared_distances(nl, i, r_.data() + (nl.first(i) - e0));
        if (e_end - e0 >= kBlock) {
          k.evaluate_over_r(e_end - e0, r_.data(), w32_.data() + e0, dwr32_.data() + e0);
          e0 = e_end;
        }
      }
      k.evaluate_over_r(e_end - e0, r_.data(), w32_.data() + e0, dwr32_.data() + e0);
    }
  }

  // Verlet lists: nl.refine() keeping the squared distances it computes as it tests the
  // candidates, so that prepare_refined() takes them instead of gathering the positions of
  // every pair a second time (about a third of prepare() in the 3D powder box). kCompact keeps
  // them in single precision where prepare_refined() then writes (dW/dr) / r.
  void refine(NeighborList<D>& nl, const ParticleStore<D>& s, double rc, double contact_range) {
    if (storage_ == Storage::kTable)
      nl.refine(s, rc, contact_range, r_);
    else if (storage_ == Storage::kCompact)
      nl.refine(s, rc, contact_range, dwr32_);
    else
      nl.refine(s, rc, contact_range);
    filled_by_ = storage_ == Storage::kStream ? kNone : nl.generation();
  }
  // As prepare(), after refine(): with kTable the same bits, r = sqrt(|x_i - x_j|^2) computed
  // alike; with kCompact W and dW/dr of the distance from the single-precision square.
  template <class K>
  void prepare_refined(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    if (storage_ == Storage::kStream) return prepare(s, nl, k);
    if (filled_by_ != nl.generation())
      throw std::logic_error("pair kernel: refine() did not write the squared distances");
    bind(s, nl, k);
    const std::size_t n = nl.pairs();
    if (storage_ == Storage::kTable) {
      for (std::size_t e = 0; e < n; ++e) r_[e] = std::sqrt(r_[e]);
      evaluate_table(n, k);
      return;
    }
    fit(w32_, n);
    // In blocks, so that the double scratch stays small and in cache. Each block's squared
    // distances are read before its values are written over them.
    grow_scratch(kBlock);
    for (std::size_t e0 = 0; e0 < n; e0 += kBlock) {
      const std::size_t len = std::min(kBlock, n - e0);
      for (std::size_t e = 0; e < len; ++e) r_[e] = static_cast<double>(dwr32_[e0 + e]);
      k.evaluate_over_r(len, r_.data(), w32_.data() + e0, dwr32_.data() + e0);
    }
  }

  // The values of particle i's pairs. With kStream they live in a scratch buffer until the
  // next call.
  PairValues of(const NeighborList<D>& nl, std::size_t i) const {
    check_fresh(nl);
    if (storage_ == Storage::kTable) {
      const std::size_t e = nl.first(i);
      return {r_.data() + e, w_.data() + e, dw_.data() + e};
    }
    const auto n = static_cast<std::size_t>(nl.end(i) - nl.begin(i));
    grow_scratch(n);
    if (storage_ == Storage::kCompact) {
      const std::size_t e0 = nl.first(i);
      distances(nl, i, r_.data());
      widen(w32_.data() + e0, w_.data(), n);
      const float* dwr = dwr32_.data() + e0;
      for (std::size_t e = 0; e < n; ++e) dw_[e] = static_cast<double>(dwr[e]) * r_[e];
    } else {
      distances(nl, i, r_.data());
      evaluate_(kernel_, n, r_.data(), w_.data(), dw_.data());
    }
    return {r_.data(), w_.data(), dw_.data()};
  }

  // The compact table's own values of particle i's pairs, for the passes that read single
  // precision directly (solver/core/pair_access.h). kCompact only.
  CompactPairValues compact_of(const NeighborList<D>& nl, std::size_t i) const {
    check_fresh(nl);
    const std::size_t e = nl.first(i);
    return {w32_.data() + e, dwr32_.data() + e};
  }
  bool compact() const { return storage_ == Storage::kCompact; }

  // W of particle i's pairs alone, for the passes that read no more (density, the wall
  // condition's weights): kCompact widens only them.
  const double* weights(const NeighborList<D>& nl, std::size_t i) const {
    if (storage_ != Storage::kCompact) return of(nl, i).w;
    check_fresh(nl);
    const auto n = static_cast<std::size_t>(nl.end(i) - nl.begin(i));
    grow_scratch(n);
    widen(w32_.data() + nl.first(i), w_.data(), n);
    return w_.data();
  }

  std::size_t bytes() const {
    return (r_.capacity() + w_.capacity() + dw_.capacity()) * sizeof(double) +
           (w32_.capacity() + dwr32_.capacity()) * sizeof(float);
  }

 private:
  // Always checked (one compare per particle and pass): values of another list's pairs
  // would be silently wrong.
  void check_fresh(const NeighborList<D>& nl) const {
    if (generation_ != nl.generation())
      throw std::logic_error("pair kernel values are stale: prepare() after every build()");
  }
  template <class K>
  void bind(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    s_ = &s;
    kernel_ = &k;
    evaluate_ = [](const void* kernel, std::size_t n, const double* r, double* w, double* dw) {
      static_cast<const K*>(kernel)->evaluate(n, r, w, dw);
    };
    generation_ = nl.generation();
    filled_by_ = kNone;  // the squared distances are used
  }
  // The scratch of kStream and kCompact: grows to the longest list once, then never allocates.
  void grow_scratch(std::size_t n) const {
    if (r_.size() >= n) return;
    r_.resize(n);
    w_.resize(n);
    dw_.resize(n);
  }
  // Separate arrays, one loop each, so that the conversion vectorises.
  static void widen(const float* __restrict in, double* __restrict out, std::size_t n) {
    for (std::size_t e = 0; e < n; ++e) out[e] = in[e];
  }
  // W and dW/dr of the first n distances in r_.
  template <class K>
  void evaluate_table(std::size_t n, const K& k) {
    fit(w_, n);
    fit(dw_, n);
    k.evaluate(n, r_.data(), w_.data(), dw_.data());
  }
  // At least n values; grown with 1/8 spare, as the list keeps, and never shrunk, so that
  // sizes changing from step to step neither reallocate nor fill.
  template <class Real>
  static void fit(std::vector<Real>& v, std::size_t n) {
    if (v.size() >= n) return;
    v.reserve(n + n / 8);  // exactly: resize() alone would double the capacity
    v.resize(n + n / 8);
  }

  // |x_i - x_j|^2 of particle i's pairs.
  void squared_distances(const NeighborList<D>& nl, std::size_t i, double* out) const {
    const Vec<D>* x = s_->x.data();
    const Vec<D> xi = x[i];
    for (const std::uint32_t* jp = nl.begin(i); jp != nl.end(i); ++jp)
      *out++ = (xi - x[*jp]).squaredNorm();
  }
  // |x_i - x_j| of particle i's pairs, as Eigen's norm() (sqrt of squaredNorm) computes it:
  // gathered first, so that the square roots vectorise.
  void distances(const NeighborList<D>& nl, std::size_t i, double* out) const {
    squared_distances(nl, i, out);
    const auto n = static_cast<std::size_t>(nl.end(i) - nl.begin(i));
    for (std::size_t e = 0; e < n; ++e) out[e] = std::sqrt(out[e]);
  }

  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  // Pairs the compact table evaluates at once from the double scratch.
  static constexpr std::size_t kBlock = 512;
  Storage storage_;
  const ParticleStore<D>* s_ = nullptr;
  const void* kernel_ = nullptr;
  void (*evaluate_)(const void*, std::size_t, const double*, double*, double*) = nullptr;
  std::uint64_t generation_ = std::numeric_limits<std::uint64_t>::max();  // matches no list
  // The generation of the list whose refine() wrote the squared distances (r_ or dwr32_).
  std::uint64_t filled_by_ = kNone;
  mutable std::vector<double> r_, w_, dw_;  // the table (kTable), or the scratch
  std::vector<float> w32_, dwr32_;          // the table (kCompact): W, (dW/dr) / r
};

}  // namespace sph
