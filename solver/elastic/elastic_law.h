#pragma once
// Hyperelastic laws of the elastic solid (total Lagrangian SPH, X. Tang's thesis sec. 2.1,
// digest sec. 3.1), written in the reference configuration:
//
//   F = dx/dX (eq. 2.1), C = F^T F, J = det F, E = (C - I)/2 (Green-Lagrange strain; the thesis'
//   eq. 2.5 prints F F^T, transposed: erratum 2 of the digest, sec. 11),
//   P = F S (eq. 2.3), the first Piola-Kirchhoff stress from the second one, S = dPsi/dE.
//
//   Saint Venant-Kirchhoff (eq. 2.4):  S = lambda tr(E) I + 2 mu E,
//                                      Psi = lambda/2 tr(E)^2 + mu E:E.
//   Compressible neo-Hookean (Bonet & Wood 2008 eqs. 6.27-6.28; the thesis names it for the
//   plates of P-II without a formula, erratum 11):
//                                      S = mu (I - C^-1) + lambda ln(J) C^-1,
//                                      Psi = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2.
//   Kelvin-Voigt damping (the case's Material.elastic_damping eta_d): S += eta_d dE/dt with
//   dE/dt = sym(F^T dF/dt), which vanishes for any rigid motion (F = R, dF/dt = W R with W
//   skew makes F^T dF/dt = R^T W R skew), so it dissipates deformation only.
//
// Moduli from Young's modulus E and Poisson's ratio nu (eq. 2.6): mu = G = E / (2 (1 + nu)),
// lambda = E nu / ((1 + nu)(1 - 2 nu)), K = lambda + 2 mu / 3 = E / (3 (1 - 2 nu)), and the
// solid's artificial sound speed c_s = sqrt(K / rho0) (digest sec. 3.1) for the time step.
//
// Two dimensions are plane strain: the 2x2 tensors are the in-plane part of a 3D state with
// F_zz = 1, F_xz = F_yz = 0 and the same lambda and mu, so E_zz = 0 and every formula above
// holds with I the 2x2 identity (tr C - 3 over 3D is tr C - 2 over the plane). The out-of-plane
// stress that this leaves, S_zz = lambda tr(E) (SVK) or lambda ln J (neo-Hookean), enters the
// von Mises stress of the output.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include "solver/core/types.h"

namespace sph {

enum class ElasticLawKind { kSaintVenantKirchhoff, kNeoHookean };

// The constants of one elastic material.
struct ElasticConstants {
  ElasticLawKind law = ElasticLawKind::kSaintVenantKirchhoff;
  double lambda = 0, mu = 0;  // Lame constants [Pa]
  double bulk = 0;            // K = lambda + 2 mu / 3 [Pa]
  double rho0 = 1;            // reference density [kg/m^3]
  double sound_speed = 0;     // c_s = sqrt(K / rho0) [m/s]
  double damping = 0;         // Kelvin-Voigt viscosity eta_d [Pa s]

  // From E [Pa], nu (in [0, 0.5)) and rho0 (thesis eq. 2.6).
  static ElasticConstants from(double youngs_modulus, double poisson_ratio, double rho0,
                               ElasticLawKind law, double damping = 0) {
    ElasticConstants c;
    c.law = law;
    const double E = youngs_modulus, nu = poisson_ratio;
    c.mu = E / (2.0 * (1.0 + nu));
    c.lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    c.bulk = c.lambda + 2.0 * c.mu / 3.0;
    c.rho0 = rho0;
    c.sound_speed = std::sqrt(c.bulk / rho0);
    c.damping = damping;
    return c;
  }
};

// E = (F^T F - I) / 2 (Green-Lagrange; erratum 2).
template <int D>
Mat<D> green_lagrange_strain(const Mat<D>& F) {
  return 0.5 * (F.transpose() * F - Mat<D>::Identity());
}

// dE/dt = sym(F^T dF/dt), the time derivative of the Green-Lagrange strain.
template <int D>
Mat<D> green_lagrange_rate(const Mat<D>& F, const Mat<D>& dFdt) {
  const Mat<D> g = F.transpose() * dFdt;
  return 0.5 * (g + g.transpose());
}

// S of the law alone (no damping).
template <int D>
Mat<D> elastic_second_piola(const ElasticConstants& c, const Mat<D>& F) {
  if (c.law == ElasticLawKind::kNeoHookean) {
    const Mat<D> C = F.transpose() * F;
    const Mat<D> Cinv = C.inverse();
    const double lnJ = std::log(F.determinant());
    return c.mu * (Mat<D>::Identity() - Cinv) + (c.lambda * lnJ) * Cinv;
  }
  const Mat<D> E = green_lagrange_strain<D>(F);
  return (c.lambda * E.trace()) * Mat<D>::Identity() + (2.0 * c.mu) * E;
}

// S = S_law(F) + eta_d dE/dt.
template <int D>
Mat<D> second_piola(const ElasticConstants& c, const Mat<D>& F, const Mat<D>& dFdt) {
  Mat<D> S = elastic_second_piola<D>(c, F);
  if (c.damping != 0.0) S += c.damping * green_lagrange_rate<D>(F, dFdt);
  return S;
}

// P = F S (eq. 2.3).
template <int D>
Mat<D> first_piola(const ElasticConstants& c, const Mat<D>& F, const Mat<D>& dFdt) {
  return F * second_piola<D>(c, F, dFdt);
}

// Psi(F), strain energy per unit reference volume [J/m^3].
template <int D>
double strain_energy_density(const ElasticConstants& c, const Mat<D>& F) {
  if (c.law == ElasticLawKind::kNeoHookean) {
    const double lnJ = std::log(F.determinant());
    const double trC = (F.transpose() * F).trace();
    return 0.5 * c.mu * (trC - D) - c.mu * lnJ + 0.5 * c.lambda * lnJ * lnJ;
  }
  const Mat<D> E = green_lagrange_strain<D>(F);
  const double trE = E.trace();
  return 0.5 * c.lambda * trE * trE + c.mu * E.squaredNorm();
}

// S_zz of plane strain (2D; E_zz = 0 and dE_zz/dt = 0, so damping adds nothing).
template <int D>
double out_of_plane_second_piola(const ElasticConstants& c, const Mat<D>& F) {
  if (c.law == ElasticLawKind::kNeoHookean) return c.lambda * std::log(F.determinant());
  return c.lambda * green_lagrange_strain<D>(F).trace();
}

// The full 3x3 Cauchy stress sigma = F S F^T / J, from F and S = second_piola(); in 2D the
// plane-strain state with sigma_zz = S_zz / J (F_zz = 1).
template <int D>
Eigen::Matrix3d cauchy_stress(const ElasticConstants& c, const Mat<D>& F, const Mat<D>& S) {
  const double J = F.determinant();
  const Mat<D> sigma = F * S * F.transpose() / J;
  Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
  out.template topLeftCorner<D, D>() = sigma;
  if constexpr (D == 2) out(2, 2) = out_of_plane_second_piola<D>(c, F) / J;
  return out;
}

// sqrt(3/2 s:s), s the deviatoric part of sigma.
inline double von_mises(const Eigen::Matrix3d& sigma) {
  const Eigen::Matrix3d s = sigma - (sigma.trace() / 3.0) * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * s.squaredNorm());
}

// Equivalent (von Mises) strain sqrt(2/3 e:e), e the deviatoric part of the Green-Lagrange
// strain as a 3D tensor (E_zz = 0 in plane strain): the axial strain of an incompressible
// uniaxial stretch at small strain.
template <int D>
double equivalent_strain(const Mat<D>& F) {
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E.template topLeftCorner<D, D>() = green_lagrange_strain<D>(F);
  const Eigen::Matrix3d e = E - (E.trace() / 3.0) * Eigen::Matrix3d::Identity();
  return std::sqrt(2.0 / 3.0 * e.squaredNorm());
}

}  // namespace sph
