#pragma once
// The kernel of the pairs of a neighbour list: the distance r, W(r) and dW/dr at the positions
// of the search, given to the passes over pairs that run at those positions (density, wall
// condition, conduction, forces, solid fraction; not the continuity equation, which uses
// mid-step positions, nor probes and open-boundary samples, which are not pairs) instead of
// each of them taking the square root and the kernel polynomial, with its data-dependent
// branches, again for the same pair. The values are evaluated in loops without branches that
// vectorise (K::evaluate), and equal those the passes computed before to the bit
// (r = |x_i - x_j|, K::evaluate = W and dW), so results are unchanged.
// Two ways to keep them:
//  - kTable: every pair evaluated once when the list is built (24 bytes a pair); the faster
//    of the two (docs/effects.md, "Design measurements").
//  - kStream: a particle's pairs evaluated into a scratch buffer each time a pass asks for
//    them; no storage, each pass gathers and evaluates again.
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

template <int D>
class PairKernel {
 public:
  enum class Storage { kTable, kStream };
  explicit PairKernel(Storage storage = Storage::kTable) : storage_(storage) {}

  // Binds the table to nl as just built from the positions of s (which the passes then use
  // unchanged) and, with kTable, evaluates every pair of the owned particles' lists.
  template <class K>
  void prepare(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    bind(s, nl, k);
    if (storage_ == Storage::kStream) return;
    const std::size_t n = nl.pairs();
    fit(r_, n);
    for (std::size_t i = 0; i < s.owned(); ++i) distances(nl, i, r_.data() + nl.first(i));
    evaluate_table(n, k);
  }

  // Verlet lists: room for the squared distances that nl.refine() writes as it tests the
  // candidates, so that prepare_refined() takes them instead of gathering the positions of
  // every pair a second time (about a third of prepare() in the 3D powder box); nullptr with
  // kStream, which keeps no table.
  double* squared_distances_for(const NeighborList<D>& nl) {
    if (storage_ == Storage::kStream) return nullptr;
    fit(r_, nl.candidate_pairs());
    filled_by_ = nl.generation() + 1;  // the refinement that comes next
    return r_.data();
  }
  // As prepare(), after nl.refine() wrote the squared distances into squared_distances_for():
  // the same bits, r = sqrt(|x_i - x_j|^2) computed alike.
  template <class K>
  void prepare_refined(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    if (storage_ == Storage::kStream) return prepare(s, nl, k);
    if (filled_by_ != nl.generation())
      throw std::logic_error("pair kernel: refine() did not write the squared distances");
    bind(s, nl, k);
    const std::size_t n = nl.pairs();
    for (std::size_t e = 0; e < n; ++e) r_[e] = std::sqrt(r_[e]);
    evaluate_table(n, k);
  }

  // The values of particle i's pairs. With kStream they live in a scratch buffer until the
  // next call.
  PairValues of(const NeighborList<D>& nl, std::size_t i) const {
    // Always checked (one compare per particle and pass): values of another list's pairs
    // would be silently wrong.
    if (generation_ != nl.generation())
      throw std::logic_error("pair kernel values are stale: prepare() after every build()");
    if (storage_ == Storage::kTable) {
      const std::size_t e = nl.first(i);
      return {r_.data() + e, w_.data() + e, dw_.data() + e};
    }
    const auto n = static_cast<std::size_t>(nl.end(i) - nl.begin(i));
    if (r_.size() < n) {  // grows to the longest list once, then never allocates
      r_.resize(n);
      w_.resize(n);
      dw_.resize(n);
    }
    distances(nl, i, r_.data());
    evaluate_(kernel_, n, r_.data(), w_.data(), dw_.data());
    return {r_.data(), w_.data(), dw_.data()};
  }

  std::size_t bytes() const {
    return (r_.capacity() + w_.capacity() + dw_.capacity()) * sizeof(double);
  }

 private:
  template <class K>
  void bind(const ParticleStore<D>& s, const NeighborList<D>& nl, const K& k) {
    s_ = &s;
    kernel_ = &k;
    evaluate_ = [](const void* kernel, std::size_t n, const double* r, double* w, double* dw) {
      static_cast<const K*>(kernel)->evaluate(n, r, w, dw);
    };
    generation_ = nl.generation();
    filled_by_ = std::numeric_limits<std::uint64_t>::max();  // the squared distances are used
  }
  // W and dW/dr of the first n distances in r_.
  template <class K>
  void evaluate_table(std::size_t n, const K& k) {
    fit(w_, n);
    fit(dw_, n);
    k.evaluate(n, r_.data(), w_.data(), dw_.data());
  }
  // At least n values; grown with 25% spare, as the list keeps, and never shrunk, so that
  // sizes changing from step to step neither reallocate nor fill.
  static void fit(std::vector<double>& v, std::size_t n) {
    if (v.size() >= n) return;
    v.reserve(n + n / 4);  // exactly: resize() alone would double the capacity
    v.resize(n + n / 4);
  }

  // |x_i - x_j| of particle i's pairs, as Eigen's norm() (sqrt of squaredNorm) computes it:
  // gathered first, so that the square roots vectorise.
  void distances(const NeighborList<D>& nl, std::size_t i, double* out) const {
    const Vec<D>* x = s_->x.data();
    const Vec<D> xi = x[i];
    double* r = out;
    for (const std::uint32_t* jp = nl.begin(i); jp != nl.end(i); ++jp)
      *r++ = (xi - x[*jp]).squaredNorm();
    const auto n = static_cast<std::size_t>(r - out);
    for (std::size_t e = 0; e < n; ++e) out[e] = std::sqrt(out[e]);
  }

  Storage storage_;
  const ParticleStore<D>* s_ = nullptr;
  const void* kernel_ = nullptr;
  void (*evaluate_)(const void*, std::size_t, const double*, double*, double*) = nullptr;
  std::uint64_t generation_ = std::numeric_limits<std::uint64_t>::max();  // matches no list
  // The generation of the list whose refine() wrote the squared distances into r_.
  std::uint64_t filled_by_ = std::numeric_limits<std::uint64_t>::max();
  mutable std::vector<double> r_, w_, dw_;  // the table, or (kStream) the scratch
};

}  // namespace sph
