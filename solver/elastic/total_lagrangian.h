#pragma once
// The operators of total Lagrangian SPH over one particle's reference neighbours (X. Tang's
// thesis sec. 3.2-3.3, digest sec. 3.2-3.3; P-I eqs. 17, 35), with the kernel gradient taken
// in the reference configuration,
//
//   grad0 W_ab = dW/dr(|X_ab|) X_ab / |X_ab|,  X_ab = X_a - X_b                      (eq. 3.6)
//
// the true gradient with respect to X_a (the sign convention of digest sec. 1.1, under which
// the physical discretisations below are consistent):
//
//   B_a = (sum_b V0_b (X_b - X_a) (x) grad0 W_ab)^-1                                   (eq. 3.7)
//   F_a = (sum_b V0_b (x_b - x_a) (x) grad0 W_ab) B_a                                  (eq. 3.10)
//   dF_a/dt = (sum_b V0_b (v_b - v_a) (x) grad0 W_ab) B_a                              (P-I eq. 35)
//   m_a dv_a/dt = sum_b V0_a V0_b (P_a B_a + P_b B_b) grad0 W_ab                  (eqs. 3.8-3.9)
//
// Eq. 3.10 is written with u = x - X there: F = (sum V0_b (u_b - u_a) (x) grad0 W) B + I. With
// x - X in place of u, and B the inverse of the same sum over X, the two are the same (the
// X part of the sum is B^-1), but the form above makes F exact for any linear deformation
// x = A X + c, A M B = A, whichever reference neighbours enter M and the sum: it needs M
// invertible, not complete. dF/dt likewise is exact for any linear velocity field. The momentum
// equation is antisymmetric in a and b (grad0 W_ba = -grad0 W_ab), so the internal forces of a
// body sum to zero, and B_a, B_b make it exact for a uniform stress in the interior, where the
// corrected gradients of the lattice cancel. Its sign: a bar stretched along x (P_xx > 0)
// pulls its end particles inwards (tests/unit/total_lagrangian_test.cc).
//
// Which particles are the reference neighbours (the design of the lead, issue #36): those b of
// the same elastic body with |X_b - X_a| < r_c, taken from the solver's neighbour search of the
// current positions (the Verlet candidates within r_c + skin, or the lists where there is no
// skin), where an elastic particle lists every neighbour (fluid ones first). The thesis
// computes B^0 once with a fixed reference neighbour list; here the pairs are taken again at
// every search and B is summed every step over them, which is the thesis' B^0 exactly until a
// stretch carries a reference neighbour out of the search (beyond r_c + skin of the current
// position at a search: B then loses that pair, and F stays exact for linear fields). Taking
// the pairs from the search makes them work
// across MPI ranks through the ghosts the halo already sends (the reference positions, body
// indices, masses and materials are persistent columns, so ghosts carry them) and keeps every
// sum in the list's canonical order: the same bits on any rank count. An elastic body must not
// straddle a periodic boundary: the reference position of a periodic image is not shifted, so
// the pairs across the seam are not found.
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/LU>

#include "solver/core/anisotropic_kernel.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/particle_store.h"

namespace sph {

template <int D>
class ReferenceNeighbors {
 public:
  struct Pair {
    std::uint32_t j;
    Vec<D> g;  // V0_b grad0 W_ab
  };

  // For every owned elastic particle a of s, its reference neighbours among the non-fluid
  // part of its candidates of the last search (NeighborList::candidates_fluid_end(a) ..
  // candidates_end(a)), in list order. X: reference positions, body: elastic body index,
  // inv_rho0: 1 / rho0 per material (V0 = m / rho0), all over owned particles and ghosts. K:
  // the run's kernel (W, dW of the reference distance).
  template <class K>
  void build(const ParticleStore<D>& s, const NeighborList<D>& nl, const Vec<D>* X,
             const std::uint16_t* body, const double* inv_rho0, const K& kernel) {
    const double rc = kernel.support_radius(), rc2 = rc * rc;
    build_pairs(s, nl, body, inv_rho0, [&](std::size_t a) {
      const Vec<D> Xa = X[a];
      return [&, Xa](std::uint32_t b, double V0b, Vec<D>& g) {
        const Vec<D> Xab = Xa - X[b];
        const double r2 = Xab.squaredNorm();
        if (!(r2 < rc2) || r2 == 0.0) return false;
        const double r = std::sqrt(r2);
        g = (V0b * kernel.dW(r) / r) * Xab;  // eq. 3.6
        return true;
      };
    });
  }

  // As build(), for a run with anisotropic bodies (ASPH, solver/core/anisotropic_kernel.h):
  // every elastic particle has its own kernel map G (isotropic ones I / h), a pair is a
  // reference pair when X_ab lies in either particle's elliptical support, and its gradient is
  // the symmetrised one of P-II eqs. 16-17 (thesis eq. 3.23),
  //   grad0 W_ab = (det G_a w'(|G_a X_ab|) G_a^T G_a X_ab / |G_a X_ab| + (same with G_b)) / 2,
  // antisymmetric in a and b as eq. 3.6 is.
  template <class AK>
  void build_anisotropic(const ParticleStore<D>& s, const NeighborList<D>& nl, const Vec<D>* X,
                         const std::uint16_t* body, const double* inv_rho0, const Mat<D>* G,
                         const AK& kernel) {
    const double s2 = AK::kSupport * AK::kSupport;
    build_pairs(s, nl, body, inv_rho0, [&](std::size_t a) {
      const Vec<D> Xa = X[a];
      const Mat<D> Ga = G[a];
      const double det_a = Ga.determinant();
      return [&, Xa, Ga, det_a](std::uint32_t b, double V0b, Vec<D>& g) {
        const Vec<D> Xab = Xa - X[b];
        if (G[b] == Ga) {
          // One map for both (a body's own): the symmetrised gradient is the particle's, since
          // (g + g) / 2 = g to the bit; one product and one kernel derivative per pair, which
          // matters since the list holds about r times the ellipse's pairs.
          const Vec<D> eta = Ga * Xab;
          const double q2 = eta.squaredNorm();
          if (!(q2 < s2) || q2 == 0.0) return false;
          g = V0b * kernel.grad_at(Ga, det_a, eta, std::sqrt(q2));
          return true;
        }
        if (Xab.squaredNorm() == 0.0 || !kernel.in_support(Ga, G[b], Xab)) return false;
        g = V0b * kernel.grad_pair(Ga, det_a, G[b], G[b].determinant(), Xab);
        return true;
      };
    });
  }

  // Whether the pairs were built from the candidates of `nl`'s last search. The reference
  // positions and kernel maps never change, so the pairs (and their gradients) hold until the
  // next search: a Verlet run evaluates them once per search, not once per step.
  bool current(const NeighborList<D>& nl) const { return built_for_ == nl.search_generation(); }

  const Pair* begin(std::size_t a) const { return pairs_.data() + start_[a]; }
  const Pair* end(std::size_t a) const { return pairs_.data() + start_[a + 1]; }
  std::size_t size(std::size_t a) const { return start_[a + 1] - start_[a]; }
  std::size_t pairs() const { return pairs_.size(); }
  std::size_t bytes() const {
    return start_.capacity() * sizeof(std::uint32_t) + pairs_.capacity() * sizeof(Pair);
  }

 private:
  // The loop of build() and build_anisotropic(): for_particle(a) gives the test of a's pairs,
  // pair(b, V0_b, g) -> whether b is a reference neighbour, with V0_b grad0 W_ab in g.
  template <class ForParticle>
  void build_pairs(const ParticleStore<D>& s, const NeighborList<D>& nl, const std::uint16_t* body,
                   const double* inv_rho0, ForParticle&& for_particle) {
    const std::size_t n = s.owned();
    start_.resize(n + 1);
    pairs_.clear();
    const Kind* kind = s.kind.data();
    const double* m = s.m.data();
    const std::uint16_t* mat = s.material.data();
    for (std::size_t a = 0; a < n; ++a) {
      start_[a] = static_cast<std::uint32_t>(pairs_.size());
      if (kind[a] != Kind::kElastic) continue;
      const std::uint16_t ba = body[a];
      const auto pair = for_particle(a);
      Vec<D> g;
      for (const std::uint32_t* jp = nl.candidates_fluid_end(a); jp != nl.candidates_end(a); ++jp) {
        const std::uint32_t b = *jp;
        if (kind[b] != Kind::kElastic || body[b] != ba) continue;
        if (pair(b, m[b] * inv_rho0[mat[b]], g)) pairs_.push_back({b, g});
      }
    }
    start_[n] = static_cast<std::uint32_t>(pairs_.size());
    built_for_ = nl.search_generation();
  }

  std::vector<std::uint32_t> start_;
  std::vector<Pair> pairs_;
  std::uint64_t built_for_ = ~std::uint64_t{0};
};

// The three sums of a particle over its reference neighbours, in one pass:
//   moment   = sum_b V0_b (X_b - X_a) (x) grad0 W_ab   (B^-1, eq. 3.7)
//   position = sum_b V0_b (x_b - x_a) (x) grad0 W_ab   (F B^-1, eq. 3.10)
//   velocity = sum_b V0_b (v_b - v_a) (x) grad0 W_ab   (dF/dt B^-1, P-I eq. 35)
template <int D>
struct ReferenceSums {
  Mat<D> moment, position, velocity;
};

template <int D>
ReferenceSums<D> reference_sums(const ReferenceNeighbors<D>& refs, std::size_t a, const Vec<D>* X,
                                const Vec<D>* x, const Vec<D>* v) {
  ReferenceSums<D> out{Mat<D>::Zero(), Mat<D>::Zero(), Mat<D>::Zero()};
  const Vec<D> Xa = X[a], xa = x[a], va = v[a];
  for (const auto* p = refs.begin(a); p != refs.end(a); ++p) {
    const std::uint32_t b = p->j;
    out.moment.noalias() += (X[b] - Xa) * p->g.transpose();
    out.position.noalias() += (x[b] - xa) * p->g.transpose();
    out.velocity.noalias() += (v[b] - va) * p->g.transpose();
  }
  return out;
}

// How far the moment matrix M is from singular, scale-free: det M / (tr M / D)^D, 1 for an
// isotropic M (a full kernel support on a lattice), about 0.5 at a corner of a lattice block,
// and 0 when the reference neighbours left span a line (2D) or a plane (3D). Not finite or
// <= 0 when M is not positive: no reference neighbours, or a corrupted state.
template <int D>
double moment_conditioning(const Mat<D>& M) {
  const double t = M.trace() / D;
  return M.determinant() / std::pow(t, D);
}

// The internal force on particle a, sum_b V0_a V0_b (P_a B_a + P_b B_b) grad0 W_ab (eqs. 3.8,
// 3.9), from the P B of a and its neighbours (ghosts included); divide by m_a for dv/dt. With
// anisotropic kernels B is not symmetric and the corrected gradient is B^T grad0 W (thesis eqs.
// 3.30-3.33: F = sum V0_b x_ba (x) B^T grad0 W_ab), so PB holds P B^T there (P-II eq. 32).
template <int D>
Vec<D> internal_force(const ReferenceNeighbors<D>& refs, std::size_t a, const Mat<D>* PB,
                      double V0a) {
  Vec<D> f = Vec<D>::Zero();
  const Mat<D> PBa = PB[a];
  for (const auto* p = refs.begin(a); p != refs.end(a); ++p) f.noalias() += (PBa + PB[p->j]) * p->g;
  return V0a * f;
}

}  // namespace sph
