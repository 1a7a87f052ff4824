#pragma once
// The damping of dynamic relaxation (X. Tang's thesis eq. 25, P-III sec. 4, after Zhu, Zhang &
// Hu 2022): a viscous force eta lap v over the reference configuration,
//   m_a dv_a/dt = -2 eta sum_b V0_a V0_b (v_a - v_b) |dW/dr|_ab / r_ab,
// the Laplacian form of Morris 1997 (the thesis prints grad W and the index a in the sum:
// erratum 9 of the digest). It drives the elastic bodies to rest at their equilibrium without
// changing where that is: it acts on relative velocities only.
//
// Explicitly it would bound the step by 0.125 h^2 rho / eta, ten or more times below the solid's
// own bound at the damping the thesis uses, so it is applied implicitly. Zhu et al. split it into
// pairs updated one after another, which depends on the order of the pairs and so on the
// decomposition; here each particle is updated implicitly against its neighbours' velocities
// before the update (a point-implicit, Jacobi form):
//   v_a' = (m_a v_a + sum_b k_ab v_b) / (m_a + sum_b k_ab),  k_ab = 2 eta dt V0_a V0_b |dW/dr| / r,
// which equals the explicit update to first order in dt and, being a weighted mean of
// velocities, never amplifies one, whatever dt; it reads the neighbours' old velocities only, so
// it is the same on any rank count. It does not conserve momentum exactly (the pair sums are not
// symmetric), which a relaxation to rest does not need.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "solver/core/types.h"
#include "solver/elastic/total_lagrangian.h"

namespace sph {

// The damped velocities out[a] of the owned, unconstrained elastic particles a < n (others copied
// from v): eta_dt = eta dt; X reference positions, v velocities (ghosts included), V0 = m / rho0.
template <int D>
void relaxation_damping(const ReferenceNeighbors<D>& refs, std::size_t n, const Kind* kind,
                        const std::int32_t* constraint, const Vec<D>* X, const double* m,
                        const std::uint16_t* mat, const double* inv_rho0, double eta_dt,
                        const Vec<D>* v, Vec<D>* out) {
  for (std::size_t a = 0; a < n; ++a) {
    out[a] = v[a];
    if (kind[a] != Kind::kElastic || constraint[a] >= 0) continue;
    const double c = 2.0 * eta_dt * m[a] * inv_rho0[mat[a]];  // 2 eta dt V0_a
    const Vec<D> Xa = X[a];
    double weight = m[a];
    Vec<D> sum = m[a] * v[a];
    for (const auto* p = refs.begin(a); p != refs.end(a); ++p) {
      // p->g = V0_b (dW/dr / r) X_ab, so -p->g . X_ab / r^2 = V0_b |dW/dr| / r.
      const Vec<D> Xab = Xa - X[p->j];
      // (An elliptical kernel's symmetrised gradient can lean off X_ab: never a negative k.)
      const double k = std::max(0.0, -c * p->g.dot(Xab) / Xab.squaredNorm());
      weight += k;
      sum += k * v[p->j];
    }
    out[a] = sum / weight;
  }
}

}  // namespace sph
