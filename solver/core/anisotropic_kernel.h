#pragma once
// Anisotropic kernels (ASPH) after X. Tang's thesis sec. 3.5 and P-II sec. 2.2-2.3 (Tang, Wu,
// Wang, Haidn, Hu, Eng. Anal. Bound. Elem. 167 (2024) 105886; digest sec. 7): a particle's
// support is an ellipse (ellipsoid) given by a linear map G of the separation,
//
//   eta = G r,   W(r) = det(G) w(|eta|)                                   (eqs. 3.21-3.22)
//   grad W(r) = det(G) w'(|eta|) G^T eta / |eta|                                 (eq. 3.23)
//
// with w the kernel of unit smoothing length (K(1.0): W and dW of solver/core/kernel.h at
// h = 1) and det G its normalisation (P-II eq. 9: ||G|| is det G), so that W integrates to one
// for any G. The isotropic kernel is G = I / h. The thesis' G are symmetric (a rotation R of the
// semi-axes h_k: G = R diag(1/h_k) R^T), where G^T = G and eq. 3.23 reads as printed; G^T is
// kept here so the gradient is the true one for any map. The support is |G r| < kSupport, an
// ellipse whose largest semi-axis is kSupport h_max.
//
// Particle-wise G (P-II eqs. 16-17): a pair's kernel and gradient are the means of the two
// particles' own,
//
//   W_ij = (W_i(r_ij) + W_j(r_ij)) / 2,   grad_i W_ij = (grad W_i(r_ij) + grad W_j(r_ij)) / 2,
//
// with r_ij = r_i - r_j, so that grad_i W_ij = -grad_j W_ji (pairwise antisymmetry: momentum is
// conserved) whatever G_i and G_j are.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "solver/core/types.h"

namespace sph {

// Thesis eq. 3.25 (P-II eq. 18): 2D, semi-major h1 rotated by theta from x, semi-minor h2.
inline Mat<2> anisotropy_map(double h1, double h2, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double a = 1.0 / h1, b = 1.0 / h2;
  Mat<2> G;
  G << a * c * c + b * s * s, (a - b) * c * s, (a - b) * c * s, a * s * s + b * c * c;
  return G;
}

// The rotation of P-II eqs. 20-22 (digest sec. 7): R = Rz(omega) Ry(psi) Rx(chi), whose columns
// are the directions of the semi-axes h1, h2, h3.
inline Mat<3> anisotropy_rotation(double omega, double psi, double chi) {
  const double w1 = std::cos(omega), w2 = std::sin(omega);
  const double p1 = std::cos(psi), p2 = std::sin(psi);
  const double c1 = std::cos(chi), c2 = std::sin(chi);
  Mat<3> R;
  R << w1 * p1, w1 * p2 * c2 - w2 * c1, w1 * p2 * c1 + w2 * c2,  //
      w2 * p1, w2 * p2 * c2 + w1 * c1, w2 * p2 * c1 - w1 * c2,   //
      -p2, p1 * c2, p1 * c1;
  return R;
}

// P-II eqs. 20-22: 3D, semi-axes h1, h2, h3 along the columns of anisotropy_rotation(omega, psi,
// chi); G = R diag(1/h1, 1/h2, 1/h3) R^T, which is the printed G_11 ... G_33.
inline Mat<3> anisotropy_map(double h1, double h2, double h3, double omega, double psi,
                             double chi) {
  const Mat<3> R = anisotropy_rotation(omega, psi, chi);
  const Eigen::Vector3d inv(1.0 / h1, 1.0 / h2, 1.0 / h3);
  return R * inv.asDiagonal() * R.transpose();
}

// A plate or shell: smoothing length h_plane along its surface, h_thick through its thickness
// along the unit normal n, G = I / h_plane + (1 / h_thick - 1 / h_plane) n n^T (eq. 3.25 in 2D
// with theta the angle of the surface; in 3D eqs. 20-22 with h1 = h2 = h_plane).
template <int D>
Mat<D> plate_anisotropy_map(double h_plane, double h_thick, const Vec<D>& n) {
  const double a = 1.0 / h_plane, b = 1.0 / h_thick;
  return a * Mat<D>::Identity() + (b - a) * (n * n.transpose());
}

// The largest semi-axis of the ellipse |G r| = 1, 1 / (smallest singular value of G), the
// singular values being the square roots of the eigenvalues of G^T G: the support's reach is
// kSupport times it, the radius a neighbour search must cover.
template <int D>
double largest_semi_axis(const Mat<D>& G) {
  const Eigen::Matrix<double, D, D> M = G.transpose() * G;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> es(M, Eigen::EigenvaluesOnly);
  return 1.0 / std::sqrt(es.eigenvalues()(0));
}

// K: one of the kernels of solver/core/kernel.h; the anisotropic kernel evaluates it at h = 1.
template <int D, class K>
class AnisotropicKernel {
 public:
  static constexpr double kSupport = K::kSupport;
  AnisotropicKernel() : base_(1.0) {}

  // W of a particle with map G (det G given, it is the same for every pair of the particle) at
  // separation r.
  double W(const Mat<D>& G, double det_G, const Vec<D>& r) const {
    return det_G * base_.W((G * r).norm());
  }
  // Its gradient with respect to the particle's position (eq. 3.23); zero at r = 0 and beyond
  // the support.
  Vec<D> grad(const Mat<D>& G, double det_G, const Vec<D>& r) const {
    const Vec<D> eta = G * r;
    const double q = eta.norm();
    if (!(q > 0) || !(q < kSupport)) return Vec<D>::Zero();
    return grad_at(G, det_G, eta, q);
  }
  // The same from eta = G r and q = |eta| (0 < q < kSupport) already at hand.
  Vec<D> grad_at(const Mat<D>& G, double det_G, const Vec<D>& eta, double q) const {
    return (det_G * base_.dW(q) / q) * (G.transpose() * eta);
  }
  // P-II eqs. 16-17: the pair's symmetrised kernel and its gradient with respect to r_i, r_ij =
  // r_i - r_j.
  double W_pair(const Mat<D>& Gi, double det_i, const Mat<D>& Gj, double det_j,
                const Vec<D>& r_ij) const {
    return 0.5 * (W(Gi, det_i, r_ij) + W(Gj, det_j, r_ij));
  }
  Vec<D> grad_pair(const Mat<D>& Gi, double det_i, const Mat<D>& Gj, double det_j,
                   const Vec<D>& r_ij) const {
    return 0.5 * (grad(Gi, det_i, r_ij) + grad(Gj, det_j, r_ij));
  }
  // Whether the pair's kernel can be nonzero: r_ij inside either particle's support.
  bool in_support(const Mat<D>& Gi, const Mat<D>& Gj, const Vec<D>& r_ij) const {
    const double s2 = kSupport * kSupport;
    return (Gi * r_ij).squaredNorm() < s2 || (Gj * r_ij).squaredNorm() < s2;
  }

 private:
  K base_;
};

}  // namespace sph
