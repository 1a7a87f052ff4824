// The hyperelastic laws of the elastic solid (solver/elastic/elastic_law.h) against analytic
// stresses: moduli, uniaxial and biaxial states, rotation invariance, P = dPsi/dF by finite
// differences, neo-Hookean -> Saint Venant-Kirchhoff at small strain, plane strain as the 3D
// state with F_zz = 1, and Kelvin-Voigt damping that leaves rigid rotation alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Geometry>

#include "solver/elastic/elastic_law.h"

namespace sph {
namespace {

constexpr ElasticLawKind kSvk = ElasticLawKind::kSaintVenantKirchhoff;
constexpr ElasticLawKind kNeo = ElasticLawKind::kNeoHookean;

// The oscillating plate of the thesis (digest sec. 8.4): E = 2 MPa, nu = 0.3975, rho 1000.
ElasticConstants plate(ElasticLawKind law, double damping = 0) {
  return ElasticConstants::from(2.0e6, 0.3975, 1000.0, law, damping);
}

template <int D>
Mat<D> rotation(double angle) {
  Mat<D> R = Mat<D>::Identity();
  if constexpr (D == 2) {
    R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  } else {
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
    R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  }
  return R;
}

template <int D>
Mat<D> random_near_identity(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Mat<D> F = Mat<D>::Identity();
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) F(r, c) += u(rng);
  return F;
}

TEST(ElasticLaw, ModuliOfThePlateBenchmark) {
  const ElasticConstants c = plate(kSvk);
  // E = 2 G (1 + nu) = 3 K (1 - 2 nu) (thesis eq. 2.6).
  const double E_from_mu = 2.0 * c.mu * (1.0 + 0.3975);
  const double E_from_K = 3.0 * c.bulk * (1.0 - 2.0 * 0.3975);
  // The digest's derived values: K = 3.252 MPa, c_s = 57.03 m/s (sec. 8.4).
  std::printf("mu %.6g lambda %.6g K %.6g c_s %.6g; E from mu %.3e, from K %.3e off\n", c.mu,
              c.lambda, c.bulk, c.sound_speed, E_from_mu / 2.0e6 - 1.0, E_from_K / 2.0e6 - 1.0);
  EXPECT_NEAR(E_from_mu / 2.0e6, 1.0, 1e-14);
  EXPECT_NEAR(E_from_K / 2.0e6, 1.0, 1e-14);
  EXPECT_NEAR(c.bulk, 3.252e6, 0.001e6);
  EXPECT_NEAR(c.sound_speed, 57.03, 0.01);
  EXPECT_DOUBLE_EQ(c.sound_speed * c.sound_speed * c.rho0, c.bulk);
}

// Uniaxial stress: Green-Lagrange E_xx = e with the lateral strain that makes the lateral
// stresses vanish. 3D: E_yy = E_zz = -nu e gives S = diag(E e, 0, 0) exactly (Young's modulus);
// plane strain: E_yy = -lambda / (lambda + 2 mu) e gives S_xx = E / (1 - nu^2) e.
TEST(ElasticLaw, SaintVenantKirchhoffUniaxialStress) {
  const ElasticConstants c = plate(kSvk);
  const double young = 2.0e6, nu = 0.3975, e = 0.05;
  {
    Mat<3> F = Mat<3>::Zero();
    F(0, 0) = std::sqrt(1.0 + 2.0 * e);
    F(1, 1) = F(2, 2) = std::sqrt(1.0 - 2.0 * nu * e);
    const Mat<3> S = second_piola<3>(c, F, Mat<3>::Zero());
    Mat<3> expect = Mat<3>::Zero();
    expect(0, 0) = young * e;
    const double err = (S - expect).norm() / (young * e);
    std::printf("3D uniaxial stress: S_xx %.9g (E e = %.9g), relative error %.2e\n", S(0, 0),
                young * e, err);
    EXPECT_LT(err, 1e-12);
    // P = F S: the nominal stress.
    const Mat<3> P = first_piola<3>(c, F, Mat<3>::Zero());
    EXPECT_NEAR(P(0, 0), F(0, 0) * young * e, 1e-12 * young * e);
  }
  {
    Mat<2> F = Mat<2>::Zero();
    const double lateral = -c.lambda / (c.lambda + 2.0 * c.mu) * e;
    F(0, 0) = std::sqrt(1.0 + 2.0 * e);
    F(1, 1) = std::sqrt(1.0 + 2.0 * lateral);
    const Mat<2> S = second_piola<2>(c, F, Mat<2>::Zero());
    const double expect = young / (1.0 - nu * nu) * e;
    const double err = std::hypot(S(0, 0) - expect, S(1, 1)) / expect;
    std::printf("plane-strain uniaxial stress: S_xx %.9g (E/(1-nu^2) e = %.9g), error %.2e\n",
                S(0, 0), expect, err);
    EXPECT_LT(err, 1e-12);
  }
}

// Biaxial stretch F = diag(f_i): S_ii = lambda tr E + 2 mu E_ii (SVK) and
// S_ii = mu (1 - f_i^-2) + lambda ln(J) f_i^-2 (neo-Hookean), off-diagonals zero.
template <int D>
void biaxial(ElasticLawKind law) {
  const ElasticConstants c = plate(law);
  const double f[3] = {1.3, 0.8, 1.1};
  Mat<D> F = Mat<D>::Zero();
  double J = 1, trE = 0;
  for (int i = 0; i < D; ++i) {
    F(i, i) = f[i];
    J *= f[i];
    trE += 0.5 * (f[i] * f[i] - 1.0);
  }
  const Mat<D> S = second_piola<D>(c, F, Mat<D>::Zero());
  Mat<D> expect = Mat<D>::Zero();
  for (int i = 0; i < D; ++i)
    expect(i, i) =
        law == kSvk ? c.lambda * trE + c.mu * (f[i] * f[i] - 1.0)
                    : c.mu * (1.0 - 1.0 / (f[i] * f[i])) + c.lambda * std::log(J) / (f[i] * f[i]);
  const double err = (S - expect).norm() / expect.norm();
  std::printf("%dD %s biaxial stretch: relative error of S %.2e\n", D,
              law == kSvk ? "SVK" : "neo-Hookean", err);
  EXPECT_LT(err, 1e-14);
}

TEST(ElasticLaw, BiaxialStretch) {
  biaxial<2>(kSvk);
  biaxial<3>(kSvk);
  biaxial<2>(kNeo);
  biaxial<3>(kNeo);
}

// Objectivity: a rigid rotation gives no stress and no energy; F = R U gives the S of U and
// P = R P(U).
template <int D>
void rotation_invariance(ElasticLawKind law) {
  const ElasticConstants c = plate(law);
  const Mat<D> R = rotation<D>(0.7);
  const Mat<D> S_rigid = second_piola<D>(c, R, Mat<D>::Zero());
  const double psi_rigid = strain_energy_density<D>(c, R);
  std::mt19937 rng(7);
  Mat<D> U = random_near_identity<D>(rng, 0.2);
  U = 0.5 * (U + U.transpose()).eval();  // a stretch
  const Mat<D> S_u = second_piola<D>(c, U, Mat<D>::Zero());
  const Mat<D> S_ru = second_piola<D>(c, R * U, Mat<D>::Zero());
  const Mat<D> P_u = first_piola<D>(c, U, Mat<D>::Zero());
  const Mat<D> P_ru = first_piola<D>(c, R * U, Mat<D>::Zero());
  const double scale = c.mu;
  std::printf(
      "%dD %s: |S(R)|/mu %.2e, Psi(R)/mu %.2e, |S(RU) - S(U)|/|S(U)| %.2e, "
      "|P(RU) - R P(U)|/|P(U)| %.2e\n",
      D, law == kSvk ? "SVK" : "neo-Hookean", S_rigid.norm() / scale, psi_rigid / scale,
      (S_ru - S_u).norm() / S_u.norm(), (P_ru - R * P_u).norm() / P_u.norm());
  EXPECT_LT(S_rigid.norm(), 1e-14 * scale);
  EXPECT_LT(std::abs(psi_rigid), 1e-14 * scale);
  EXPECT_LT((S_ru - S_u).norm(), 1e-13 * S_u.norm());
  EXPECT_LT((P_ru - R * P_u).norm(), 1e-13 * P_u.norm());
}

TEST(ElasticLaw, RigidRotationGivesNoStress) {
  rotation_invariance<2>(kSvk);
  rotation_invariance<3>(kSvk);
  rotation_invariance<2>(kNeo);
  rotation_invariance<3>(kNeo);
}

// P = dPsi/dF, by central differences of Psi in each entry of F (step 1e-6; the truncation
// error is O(step^2) of the stress, the rounding error about eps Psi / step).
template <int D>
void piola_is_energy_derivative(ElasticLawKind law) {
  const ElasticConstants c = plate(law);
  std::mt19937 rng(11);
  double worst = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const Mat<D> F = random_near_identity<D>(rng, 0.3);
    ASSERT_GT(F.determinant(), 0.0);
    const Mat<D> P = first_piola<D>(c, F, Mat<D>::Zero());
    Mat<D> dpsi;
    const double step = 1e-6;
    for (int r = 0; r < D; ++r)
      for (int s = 0; s < D; ++s) {
        Mat<D> Fp = F, Fm = F;
        Fp(r, s) += step;
        Fm(r, s) -= step;
        dpsi(r, s) =
            (strain_energy_density<D>(c, Fp) - strain_energy_density<D>(c, Fm)) / (2.0 * step);
      }
    worst = std::max(worst, (P - dpsi).norm() / P.norm());
  }
  std::printf("%dD %s: |P - dPsi/dF| / |P| up to %.2e over 5 deformations\n", D,
              law == kSvk ? "SVK" : "neo-Hookean", worst);
  EXPECT_LT(worst, 1e-7);
}

TEST(ElasticLaw, PiolaStressIsTheEnergyDerivative) {
  piola_is_energy_derivative<2>(kSvk);
  piola_is_energy_derivative<3>(kSvk);
  piola_is_energy_derivative<2>(kNeo);
  piola_is_energy_derivative<3>(kNeo);
}

// Both laws linearise to lambda tr(eps) I + 2 mu eps: their difference is second order in the
// strain, so relative to the stress it falls linearly with the strain amplitude.
template <int D>
void neo_hookean_to_svk() {
  const ElasticConstants svk = plate(kSvk), neo = plate(kNeo);
  std::mt19937 rng(3);
  const Mat<D> G = random_near_identity<D>(rng, 1.0) - Mat<D>::Identity();
  double previous = 0;
  for (const double eps : {1e-2, 1e-3, 1e-4}) {
    const Mat<D> F = Mat<D>::Identity() + eps * G;
    const Mat<D> a = second_piola<D>(svk, F, Mat<D>::Zero());
    const Mat<D> b = second_piola<D>(neo, F, Mat<D>::Zero());
    const double rel = (a - b).norm() / a.norm();
    std::printf("%dD strain %.0e: |S_neo - S_svk| / |S_svk| = %.3e\n", D, eps, rel);
    EXPECT_LT(rel, 10.0 * eps);
    if (previous > 0) {
      EXPECT_NEAR(previous / rel, 10.0, 1.0);  // first order in eps
    }
    previous = rel;
  }
}

TEST(ElasticLaw, NeoHookeanApproachesSaintVenantKirchhoffAtSmallStrain) {
  neo_hookean_to_svk<2>();
  neo_hookean_to_svk<3>();
}

// Plane strain is the 3D state with F_zz = 1: the 2D S is the in-plane block of the 3D one,
// the out-of-plane S_zz is the 3D S_zz, and Psi is the same.
template <ElasticLawKind kLaw>
void plane_strain_is_embedded_3d() {
  const ElasticConstants c = plate(kLaw);
  Mat<2> F2;
  F2 << 1.1, 0.2, -0.1, 0.9;
  Mat<3> F3 = Mat<3>::Identity();
  F3.topLeftCorner<2, 2>() = F2;
  const Mat<2> S2 = second_piola<2>(c, F2, Mat<2>::Zero());
  const Mat<3> S3 = second_piola<3>(c, F3, Mat<3>::Zero());
  const double err_s = (S2 - S3.topLeftCorner<2, 2>()).norm() / S2.norm();
  const double err_zz = std::abs(out_of_plane_second_piola<2>(c, F2) - S3(2, 2)) / S2.norm();
  const double err_psi =
      std::abs(strain_energy_density<2>(c, F2) - strain_energy_density<3>(c, F3)) /
      std::abs(strain_energy_density<3>(c, F3));
  const double err_vm =
      std::abs(von_mises(cauchy_stress<2>(c, F2, S2)) - von_mises(cauchy_stress<3>(c, F3, S3))) /
      von_mises(cauchy_stress<3>(c, F3, S3));
  std::printf("%s plane strain vs 3D: S %.2e, S_zz %.2e, Psi %.2e, von Mises %.2e\n",
              kLaw == kSvk ? "SVK" : "neo-Hookean", err_s, err_zz, err_psi, err_vm);
  EXPECT_LT(err_s, 1e-14);
  EXPECT_LT(err_zz, 1e-14);
  EXPECT_LT(err_psi, 1e-14);
  EXPECT_LT(err_vm, 1e-14);
}

TEST(ElasticLaw, PlaneStrainIsTheThreeDimensionalStateWithoutOutOfPlaneStretch) {
  plane_strain_is_embedded_3d<kSvk>();
  plane_strain_is_embedded_3d<kNeo>();
}

// Kelvin-Voigt: S += eta_d sym(F^T dF/dt). A rigid rotation rate (dF/dt = W F, W skew) adds
// nothing; a stretching rate at F = I adds eta_d times it.
template <int D>
void damping() {
  const double eta = 50.0;
  const ElasticConstants damped = plate(kSvk, eta), undamped = plate(kSvk);
  const Mat<D> F = rotation<D>(0.4) * (Mat<D>::Identity() + 0.05 * Mat<D>::Ones());
  Mat<D> W = Mat<D>::Zero();
  W(0, 1) = 3.0;
  W(1, 0) = -3.0;
  if constexpr (D == 3) {
    W(0, 2) = -1.5;
    W(2, 0) = 1.5;
  }
  const Mat<D> spin = W * F;
  const double err_spin =
      (second_piola<D>(damped, F, spin) - second_piola<D>(undamped, F, spin)).norm();
  Mat<D> rate = Mat<D>::Zero();
  rate(0, 0) = 2.0;
  rate(1, 1) = -1.0;
  rate(0, 1) = rate(1, 0) = 0.5;
  const Mat<D> added = second_piola<D>(damped, Mat<D>::Identity(), rate) -
                       second_piola<D>(undamped, Mat<D>::Identity(), rate);
  const double err_rate = (added - eta * rate).norm() / (eta * rate.norm());
  std::printf("%dD damping: |S_d| under a rotation rate %.2e Pa; stretching rate error %.2e\n", D,
              err_spin, err_rate);
  EXPECT_LT(err_spin, 1e-12 * eta * 3.0);
  EXPECT_LT(err_rate, 1e-15);
}

TEST(ElasticLaw, KelvinVoigtDampingLeavesRigidRotationAlone) {
  damping<2>();
  damping<3>();
}

TEST(ElasticLaw, VonMisesStressAndEquivalentStrain) {
  Eigen::Matrix3d uniaxial = Eigen::Matrix3d::Zero();
  uniaxial(0, 0) = -7.0;
  Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
  shear(0, 1) = shear(1, 0) = 2.0;
  const Eigen::Matrix3d hydro = 5.0 * Eigen::Matrix3d::Identity();
  std::printf("von Mises: uniaxial %.15g (7), shear %.15g (2 sqrt 3), hydrostatic %.3g (0)\n",
              von_mises(uniaxial), von_mises(shear), von_mises(hydro));
  EXPECT_NEAR(von_mises(uniaxial), 7.0, 1e-14);
  EXPECT_NEAR(von_mises(shear), 2.0 * std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(von_mises(hydro), 0.0, 1e-14);
  // An isochoric uniaxial Green-Lagrange strain diag(e, -e/2, -e/2) has equivalent strain e.
  const double e = 0.02;
  Mat<3> F = Mat<3>::Zero();
  F(0, 0) = std::sqrt(1.0 + 2.0 * e);
  F(1, 1) = F(2, 2) = std::sqrt(1.0 - e);
  std::printf("equivalent strain %.15g (%.15g)\n", equivalent_strain<3>(F), e);
  EXPECT_NEAR(equivalent_strain<3>(F), e, 1e-15);
  EXPECT_NEAR(equivalent_strain<3>(rotation<3>(1.0)), 0.0, 1e-15);
}

}  // namespace
}  // namespace sph
