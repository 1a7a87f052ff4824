#pragma once
// Finite-strain J2 plasticity with nonlinear isotropic hardening at one material point (X.
// Tang's thesis sec. 5 / P-III Appendix A, digest sec. 4; Simo 1992, CMAME 99; Simo & Hughes
// 1998, Computational Inelasticity, Box 9.1), for the elastic solid's particles
// (solver/elastic/elastic_solid.h).
//
//   F = F^e F^p (eq. 29), det F^p = 1, b^e = F C^p^-1 F^T (eq. 31),
//   W = K/2 [ (J^2 - 1)/2 - ln J ] + mu/2 [ tr(bbar^e) - 3 ]          (eqs. 32-34, D = 3)
//   tau = K/2 (J^2 - 1) I + mu dev(bbar^e)                                       (eq. 36)
//   f = ||dev tau|| - sqrt(2/3) k(alpha)                                          (eq. 39)
//   k(alpha) = sigma_0 + (sigma_inf - sigma_0)(1 - exp(-delta alpha)) + H alpha  (eq. 40)
//
// with Tbar = det(T)^-1/3 T and dev T = T - tr(T)/3 I (eqs. 37-38), K the bulk modulus (the
// thesis' kappa in eq. 36; erratum 8 of the digest, sec. 11) and mu the shear modulus.
//
// The return mapping (thesis Algorithm 1, with erratum 8 resolved):
//  - Step 1 prints F_{n+1} = dt dF/dt, without F_n. Here F_{n+1} is not integrated at all: the
//    solid computes it from the positions every step (thesis eq. 3.10), so the step starts from
//    that F and the stored plastic state of the previous step, (Cbar^p_n)^-1 and alpha_n.
//  - Two dimensions: the thesis applies the 3D exponents (-1/3, 1/3) to 2x2 tensors, which is
//    neither plane strain nor plane stress. Here 2D is plane strain: the 2x2 F is the in-plane
//    part of a 3D F with F_zz = 1 (as the elastic laws, solver/elastic/elastic_law.h), and the
//    algorithm runs on the 3x3 tensors, so the 3D exponents are the right ones and the
//    out-of-plane stress tau_zz is that of the 3D state. Plane strain keeps b^e_xz = b^e_yz = 0.
//  - Step 11 updates bbar^e = s / mu + tr(bbar^e_trial)/3 I, whose determinant is not exactly 1
//    (Simo & Hughes 1998 sec. 9.3.2), so the plastic flow would not be isochoric. Here the
//    spherical part I_e/3 is instead the root near tr(bbar^e_trial)/3 of det(s/mu + I_e/3 I) = 1:
//    the deviator s, and with it f = 0, stays as returned and det Cbar^p = 1 holds to round-off
//    at every step (tests/unit/j2_plasticity_test.cc).
//  - The stored state is (Cbar^p)^-1 = Fbar^-1 bbar^e Fbar^-T (the thesis' step 11 writes it
//    Cbar^p), symmetric with det 1, and the equivalent plastic strain alpha.
//  - The scalar consistency equation (step 9) is solved by Newton's method: g(dgamma) =
//    ||s_trial|| - sqrt(2/3) k(alpha_n + sqrt(2/3) dgamma) - 2 mubar dgamma is convex and
//    decreasing (k is concave plus linear), so Newton from dgamma = 0 increases monotonically to
//    the root.
// An elastic step (f_trial <= 0) leaves the state untouched to the bit.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include "solver/core/types.h"

namespace sph {

// Hardening law of eq. 40 (Table 5.1 form); stresses in Pa.
struct J2Hardening {
  double sigma0 = 0;     // initial flow stress sigma_0 [Pa]
  double sigma_inf = 0;  // saturation flow stress sigma_inf [Pa]
  double delta = 0;      // saturation exponent delta [-]
  double linear = 0;     // linear hardening H [Pa]

  // k(alpha), eq. 40.
  double flow_stress(double alpha) const {
    return sigma0 + (sigma_inf - sigma0) * (1.0 - std::exp(-delta * alpha)) + linear * alpha;
  }
  // dk/dalpha.
  double slope(double alpha) const {
    return (sigma_inf - sigma0) * delta * std::exp(-delta * alpha) + linear;
  }
};

// The constants of a J2 material: moduli and hardening.
struct J2Constants {
  double bulk = 0;   // K [Pa]
  double shear = 0;  // mu [Pa]
  J2Hardening hardening;
};

// The persistent state of one particle: (Cbar^p)^-1 as its six symmetric components (xx, yy,
// zz, xy, yz, xz), the identity in the virgin state, and alpha (0 there).
struct PlasticMetric {
  double cp_inv[6] = {1, 1, 1, 0, 0, 0};

  Eigen::Matrix3d inverse_plastic_metric() const {
    Eigen::Matrix3d m;
    m << cp_inv[0], cp_inv[3], cp_inv[5], cp_inv[3], cp_inv[1], cp_inv[4], cp_inv[5], cp_inv[4],
        cp_inv[2];
    return m;
  }
  void set_inverse_plastic_metric(const Eigen::Matrix3d& m) {
    cp_inv[0] = m(0, 0);
    cp_inv[1] = m(1, 1);
    cp_inv[2] = m(2, 2);
    cp_inv[3] = 0.5 * (m(0, 1) + m(1, 0));
    cp_inv[4] = 0.5 * (m(1, 2) + m(2, 1));
    cp_inv[5] = 0.5 * (m(0, 2) + m(2, 0));
  }
};

// The 3x3 F of a D x D one (plane strain in 2D: F_zz = 1).
template <int D>
Eigen::Matrix3d embed_3d(const Mat<D>& F) {
  Eigen::Matrix3d F3 = Eigen::Matrix3d::Identity();
  F3.template topLeftCorner<D, D>() = F;
  return F3;
}

// What one return mapping gives.
struct J2Result {
  Eigen::Matrix3d tau;  // Kirchhoff stress (eq. 36)
  bool plastic = false;
  int iterations = 0;  // Newton iterations of the consistency equation
};

inline Eigen::Matrix3d deviator(const Eigen::Matrix3d& T) {
  return T - (T.trace() / 3.0) * Eigen::Matrix3d::Identity();
}

// One step of Algorithm 1 at the deformation gradient F (3x3, det F > 0): returns tau and
// updates the plastic state, (Cbar^p)^-1 and alpha, from the previous step's to this step's.
inline J2Result j2_return_map(const J2Constants& c, const Eigen::Matrix3d& F, PlasticMetric& state,
                              double& alpha) {
  constexpr double kSqrt23 = 0.816496580927726;  // sqrt(2/3)
  constexpr int kMaxNewton = 50;
  J2Result out;
  const double J = F.determinant();
  const Eigen::Matrix3d Fbar = std::cbrt(1.0 / J) * F;  // eq. 37
  const Eigen::Matrix3d cp_inv = state.inverse_plastic_metric();
  const Eigen::Matrix3d be_trial = Fbar * cp_inv * Fbar.transpose();  // step 2
  const Eigen::Matrix3d s_trial = c.shear * deviator(be_trial);
  const double s_norm = s_trial.norm();  // Frobenius
  const double pressure_part = 0.5 * c.bulk * (J * J - 1.0);
  const double f_trial = s_norm - kSqrt23 * c.hardening.flow_stress(alpha);  // step 3
  if (!(f_trial > 0.0)) {
    out.tau = pressure_part * Eigen::Matrix3d::Identity() + s_trial;  // steps 4, 10
    return out;
  }
  // Step 9: the consistency equation by Newton's method.
  const double Ie3 = be_trial.trace() / 3.0;
  const double mubar = c.shear * Ie3;
  double dgamma = 0;
  const double tol = 1e-12 * (s_norm + c.hardening.sigma0);
  for (int it = 0; it < kMaxNewton; ++it) {
    const double a = alpha + kSqrt23 * dgamma;
    const double g = s_norm - kSqrt23 * c.hardening.flow_stress(a) - 2.0 * mubar * dgamma;
    out.iterations = it + 1;
    if (std::abs(g) <= tol) break;
    const double dg = -(2.0 / 3.0) * c.hardening.slope(a) - 2.0 * mubar;
    dgamma -= g / dg;
  }
  const Eigen::Matrix3d s = (1.0 - 2.0 * mubar * dgamma / s_norm) * s_trial;
  alpha += kSqrt23 * dgamma;
  // Step 11 with det bbar^e = 1: I_e/3 = x solves x^3 - (||d||^2 / 2) x + det d - 1 = 0, d =
  // s / mu traceless (the characteristic polynomial of -d at -x), by Newton from tr/3 of the
  // trial state.
  const Eigen::Matrix3d d = s / c.shear;
  const double d2 = 0.5 * d.squaredNorm(), d3 = d.determinant() - 1.0;
  double x = Ie3;
  for (int it = 0; it < kMaxNewton; ++it) {
    const double r = x * x * x - d2 * x + d3;
    const double step = r / (3.0 * x * x - d2);
    x -= step;
    if (std::abs(step) <= 1e-15 * x) break;
  }
  const Eigen::Matrix3d be = d + x * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d Fbar_inv = Fbar.inverse();
  state.set_inverse_plastic_metric(Fbar_inv * be * Fbar_inv.transpose());
  out.tau = pressure_part * Eigen::Matrix3d::Identity() + s;  // step 10
  out.plastic = true;
  return out;
}

// The strain energy per unit reference volume of the elastic part, eqs. 33-34 with D = 3 (the
// plastic work is not in it).
inline double j2_elastic_energy(const J2Constants& c, const Eigen::Matrix3d& F,
                                const PlasticMetric& state) {
  const double J = F.determinant();
  const Eigen::Matrix3d Fbar = std::cbrt(1.0 / J) * F;
  const double tr = (Fbar * state.inverse_plastic_metric() * Fbar.transpose()).trace();
  return 0.5 * c.bulk * (0.5 * (J * J - 1.0) - std::log(J)) + 0.5 * c.shear * (tr - 3.0);
}

}  // namespace sph
