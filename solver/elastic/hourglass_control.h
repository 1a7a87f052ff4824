#pragma once
// Hourglass control for total Lagrangian SPH after G. C. Ganzenmüller, "An hourglass control
// algorithm for Lagrangian Smooth Particle Hydrodynamics", CMAME 286 (2015) 87-106, sec. 3.
//
// Why: the deformation gradient of eq. 3.10 (total_lagrangian.h) is a kernel-weighted sum of
// the pair separations, and patterns of particle displacement exist that leave every F
// unchanged, the checkerboard on a lattice above all (its differences to the neighbours are
// even under b -> -b, the gradients odd, so the sum vanishes). Such a mode costs no strain
// energy and nothing in the momentum equation resists it: it grows from round-off and from the
// nonlinear coupling of a large deformation until a particle inverts (docs/elastic_solids.md,
// the bar at 8% strain). Ganzenmüller's remedy asks each pair to lie where the particle's own F
// predicts it, x_ab = F_a X_ab, and pulls it there with a spring along the pair whose stiffness
// is that of the material:
//
//   eps_ab^a = F_a X_ab - x_ab,   eps_ab^b = F_b X_ab - x_ab      (X_ab = X_a - X_b, x_ab = x_a -
//   x_b) f_a = sum_b V0_a V0_b W(|X_ab|) / |X_ab|^2 (k_a eps_ab^a + k_b eps_ab^b) . x_ab / |x_ab|^2
//   x_ab, k = alpha E / 2,
//
// his correction force with the error of each side projected on the current pair direction
// (delta = eps . x_ab / |x_ab|) and its alpha E / 2 (a material's alpha,
// Material.hourglass_control; each side its own, equal within a body). Properties, each checked in
// tests/unit/total_lagrangian_test.cc:
//   - zero for any linear deformation x = A X + c, rigid rotations included, at boundary
//     particles too: F is exact there (eq. 3.10), so both errors vanish;
//   - the pair term is antisymmetric (swapping a and b negates X_ab, x_ab and both errors, and
//     leaves the scalar factor alone) and along x_ab: linear and angular momentum are conserved
//     as by a central pair force;
//   - a checkerboard displacement u, F = I: eps = -(u_a - u_b), a restoring force of about
//     -alpha E V0 (sum_b V0_b W / |X_ab|^2) u: the zero-energy mode gets a frequency
//     omega^2 = alpha (E / rho0) sum_b V0_b W / X^2 instead of none.
// It is a penalty, not derived from a potential: the hourglass mode's energy is not in the strain
// energy series, and a curved (non-affine) deformation, where F X_ab misses x_ab at second order
// in |X_ab|, feels a small spurious stiffness (the cantilever's period, docs/elastic_solids.md).
//
// The sums run over the reference neighbours in the list's order (total_lagrangian.h), with F of
// the neighbours from the ghosts: the same bits on any rank count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "case/materials.h"
#include "solver/elastic/total_lagrangian.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class HourglassControl {
 public:
  HourglassControl() = default;
  // The coefficients of the case's materials (index as in `materials`), and the step bound
  // their hourglass stiffness sets on a lattice of spacing dx with the kernel's support.
  template <class K>
  HourglassControl(const v1::Case& c, const std::vector<MaterialParams>& materials, const K& kernel,
                   double dx)
      : stiffness_(materials.size(), 0.0) {
    const double s = lattice_sum(kernel, dx);
    double c2 = 0;  // largest alpha E / rho0 of the materials
    for (std::size_t k = 0;
         k < materials.size() && k < static_cast<std::size_t>(c.materials_size()); ++k) {
      const v1::Material& m = c.materials(static_cast<int>(k));
      // Off unless the case sets it (docs/elastic_solids.md: why no default).
      const double alpha = m.hourglass_control();
      if (!(alpha > 0) || !(materials[k].youngs_modulus > 0) || !(materials[k].rho0 > 0)) continue;
      stiffness_[k] = 0.5 * alpha * materials[k].youngs_modulus;
      c2 = std::max(c2, alpha * materials[k].youngs_modulus / materials[k].rho0);
      active_ = true;
    }
    // omega^2 = alpha (E / rho0) S of the checkerboard; h / c_hg with c_hg = h omega, the form of
    // the acoustic bound h / c_s, so that the solid's factor 0.6 (thesis eq. 33) keeps its margin.
    if (c2 > 0 && s > 0) step_length_ = 1.0 / std::sqrt(c2 * s);
  }

  bool active() const { return active_; }
  // 1 / omega of the stiffest material's checkerboard on the lattice (infinity when inactive):
  // the unit bounds its step by 0.6 cfl_factor of it, as h / c_s.
  double time_scale() const { return step_length_; }
  // alpha E / 2 of material k.
  double stiffness(std::size_t k) const { return stiffness_[k]; }

  // The hourglass force on owned particle a (formula above). X, x, F, m, mat over owned particles
  // and ghosts; inv_rho0 per material (V0 = m / rho0); kernel: the run's.
  template <class K>
  Vec<D> force(const ReferenceNeighbors<D>& refs, std::size_t a, const Vec<D>* X, const Vec<D>* x,
               const Mat<D>* F, const double* m, const std::uint16_t* mat, const double* inv_rho0,
               const K& kernel) const {
    Vec<D> f = Vec<D>::Zero();
    const Vec<D> Xa = X[a], xa = x[a];
    const Mat<D> Fa = F[a];
    const double ka = stiffness_[mat[a]];
    for (const auto* p = refs.begin(a); p != refs.end(a); ++p) {
      const std::uint32_t b = p->j;
      const Vec<D> Xab = Xa - X[b];
      const Vec<D> xab = xa - x[b];
      const double r2 = xab.squaredNorm();
      if (!(r2 > 0)) continue;  // coincident particles: no direction (the guard names them)
      const double R2 = Xab.squaredNorm();
      const double V0b = m[b] * inv_rho0[mat[b]];
      const Vec<D> error = ka * (Fa * Xab - xab) + stiffness_[mat[b]] * (F[b] * Xab - xab);
      f.noalias() += (V0b * kernel.W(std::sqrt(R2)) / R2 * error.dot(xab) / r2) * xab;
    }
    return (m[a] * inv_rho0[mat[a]]) * f;
  }

  // S = sum over the points of a lattice of spacing dx within the kernel's support (the origin
  // left out) of dx^D W(r) / r^2: the checkerboard's frequency is sqrt(alpha (E / rho0) S).
  template <class K>
  static double lattice_sum(const K& kernel, double dx) {
    if (!(dx > 0)) return 0;
    const double rc = kernel.support_radius();
    const int n = static_cast<int>(std::ceil(rc / dx));
    double s = 0;
    const int nz = D == 3 ? n : 0;
    for (int k = -nz; k <= nz; ++k)
      for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
          const double r2 = dx * dx * (i * i + j * j + k * k);
          if (r2 == 0 || !(r2 < rc * rc)) continue;
          s += std::pow(dx, D) * kernel.W(std::sqrt(r2)) / r2;
        }
    return s;
  }

 private:
  std::vector<double> stiffness_;  // alpha E / 2 per material
  bool active_ = false;
  double step_length_ = std::numeric_limits<double>::infinity();
};

}  // namespace sph
