// J2 plasticity at one material point (solver/elastic/j2_plasticity.h) against closed forms,
// with the steel of the thesis' necking bar (Table 5.1, digest sec. 8.11):
//  - uniaxial tension, lateral stresses zero: consistency f = 0 after every plastic return,
//    det Cbar^p = 1 (isochoric flow), tau_xx = k(alpha), and the curve tau(ln lambda) against the
//    1D law tau = k(ln lambda - tau / E) of logarithmic strain split into elastic and plastic;
//  - plane-strain tension (F_zz = 1, tau_yy = 0): tau_xx against the rigid-plastic plane-strain
//    value 2/sqrt(3) k(alpha), tau_zz -> tau_xx / 2;
//  - elastic unloading from the plastic state: slope E, state untouched;
//  - objectivity: a rotation of the current configuration rotates tau and leaves alpha alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "solver/elastic/j2_plasticity.h"

namespace sph {
namespace {

constexpr double kSqrt23 = 0.816496580927726;

// Table 5.1: mu = 80.1938 GPa, K = 164.21 GPa, sigma_0 = 450 MPa, sigma_inf = 715 MPa, delta =
// 16.93, H = 129.24 MPa.
J2Constants steel() {
  J2Constants c;
  c.shear = 80.1938e9;
  c.bulk = 164.21e9;
  c.hardening = {450e6, 715e6, 16.93, 129.24e6};
  return c;
}

// A material point: the plastic state a particle keeps.
struct Point {
  PlasticMetric m;
  double alpha = 0;
};

J2Result map_point(const J2Constants& c, const Eigen::Matrix3d& F, Point& p) {
  return j2_return_map(c, F, p.m, p.alpha);
}

double youngs(const J2Constants& c) {
  return 9 * c.bulk * c.shear / (3 * c.bulk + c.shear);
}

// tau for F = diag(l1, l2, l3) from the state, the state left unchanged.
Eigen::Matrix3d trial_tau(const J2Constants& c, double l1, double l2, double l3, const Point& s) {
  Point copy = s;
  return map_point(c, Eigen::Vector3d(l1, l2, l3).asDiagonal().toDenseMatrix(), copy).tau;
}

// The lateral stretch that makes tau_yy (and, with `both`, tau_zz = tau_yy by symmetry) zero.
double free_lateral(const J2Constants& c, double lx, double guess, const Point& s, bool both) {
  double l = guess;
  for (int it = 0; it < 60; ++it) {
    const double lz = both ? l : 1.0;
    const double r = trial_tau(c, lx, l, lz, s)(1, 1);
    const double e = 1e-7 * l;
    const double r2 = trial_tau(c, lx, l + e, both ? l + e : 1.0, s)(1, 1);
    const double step = r * e / (r2 - r);
    l -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return l;
}

// The 1D law: tau = k(eps - tau / E) at logarithmic strain eps, by Newton.
double one_dimensional_stress(const J2Constants& c, double eps) {
  const double E = youngs(c);
  if (E * eps <= c.hardening.sigma0) return E * eps;
  double tau = c.hardening.sigma0;
  for (int it = 0; it < 100; ++it) {
    const double a = eps - tau / E;
    const double r = tau - c.hardening.flow_stress(a);
    tau -= r / (1 + c.hardening.slope(a) / E);
    if (std::abs(r) < 1e-6) break;
  }
  return tau;
}

TEST(J2Plasticity, UniaxialTensionFollowsTheHardeningLaw) {
  const J2Constants c = steel();
  Point s;
  double lat = 1.0, worst_f = 0, worst_det = 0, worst_curve = 0, worst_k = 0;
  int plastic_steps = 0, max_newton = 0;
  const int n = 2000;
  const double lambda_end = 1.3;
  for (int k = 1; k <= n; ++k) {
    const double lx = 1.0 + (lambda_end - 1.0) * k / n;
    lat = free_lateral(c, lx, lat, s, true);
    const J2Result r = map_point(c, Eigen::Vector3d(lx, lat, lat).asDiagonal().toDenseMatrix(), s);
    ASSERT_LT(std::abs(r.tau(1, 1)), 1e-3 * c.hardening.sigma0);
    const double kflow = c.hardening.flow_stress(s.alpha);
    if (r.plastic) {
      ++plastic_steps;
      max_newton = std::max(max_newton, r.iterations);
      worst_f = std::max(worst_f, std::abs(deviator(r.tau).norm() - kSqrt23 * kflow) / kflow);
      worst_k = std::max(worst_k, std::abs(r.tau(0, 0) - r.tau(1, 1) - kflow) / kflow);
    }
    worst_det = std::max(worst_det, std::abs(s.m.inverse_plastic_metric().determinant() - 1.0));
    const double tau1d = one_dimensional_stress(c, std::log(lx));
    worst_curve = std::max(worst_curve, std::abs(r.tau(0, 0) - tau1d) / c.hardening.sigma0);
  }
  std::printf(
      "uniaxial to lambda %.2f in %d steps (%d plastic, <= %d Newton iterations): |f| / k <= "
      "%.2e, |det Cp - 1| <= %.2e, |tau_xx - tau_yy - k| / k <= %.2e, |tau - tau_1D| / sigma0 "
      "<= %.2e, alpha %.4f (ln lambda %.4f)\n",
      lambda_end, n, plastic_steps, max_newton, worst_f, worst_det, worst_k, worst_curve, s.alpha,
      std::log(lambda_end));
  EXPECT_GT(plastic_steps, n * 9 / 10);
  EXPECT_LT(worst_f, 1e-10);
  EXPECT_LT(worst_det, 1e-12);
  EXPECT_LT(worst_k, 1e-10);
  // The elastic part is neo-Hookean-type, the 1D law Hencky: they differ at O(eps_e^2), eps_e
  // about 3e-3; the b^e update is first order in the increment.
  EXPECT_LT(worst_curve, 2e-3);
}

TEST(J2Plasticity, PlaneStrainTensionApproachesTheRigidPlasticState) {
  const J2Constants c = steel();
  Point s;
  double ly = 1.0;
  const int n = 1000;
  J2Result r;
  double worst_det = 0;
  for (int k = 1; k <= n; ++k) {
    const double lx = 1.0 + 0.2 * k / n;
    ly = free_lateral(c, lx, ly, s, false);
    r = map_point(c, Eigen::Vector3d(lx, ly, 1.0).asDiagonal().toDenseMatrix(), s);
    worst_det = std::max(worst_det, std::abs(s.m.inverse_plastic_metric().determinant() - 1.0));
  }
  const double kflow = c.hardening.flow_stress(s.alpha);
  const double f = deviator(r.tau).norm() - kSqrt23 * kflow;
  const double ratio = r.tau(0, 0) / (2.0 / std::sqrt(3.0) * kflow);
  std::printf(
      "plane strain to lambda 1.2: alpha %.4f, tau_xx / (2/sqrt3 k) = %.5f, tau_zz / tau_xx = "
      "%.5f, |f| / k = %.2e, |det Cp - 1| <= %.2e\n",
      s.alpha, ratio, r.tau(2, 2) / r.tau(0, 0), std::abs(f) / kflow, worst_det);
  EXPECT_LT(std::abs(f) / kflow, 1e-10);
  EXPECT_LT(worst_det, 1e-12);
  // The elastic strain in the flow direction keeps tau_zz a little off tau_xx / 2.
  EXPECT_NEAR(ratio, 1.0, 2e-3);
  EXPECT_NEAR(r.tau(2, 2) / r.tau(0, 0), 0.5, 5e-3);
  // Rigid-plastic plane strain: alpha = 2/sqrt(3) ln lambda_p, lambda_p about lambda.
  EXPECT_NEAR(s.alpha, 2.0 / std::sqrt(3.0) * std::log(1.2), 0.01);
}

TEST(J2Plasticity, UnloadingIsElasticWithYoungsModulus) {
  const J2Constants c = steel();
  Point s;
  double lat = 1.0;
  double lx = 1.0;
  for (int k = 1; k <= 500; ++k) {
    lx = 1.0 + 0.1 * k / 500;
    lat = free_lateral(c, lx, lat, s, true);
    map_point(c, Eigen::Vector3d(lx, lat, lat).asDiagonal().toDenseMatrix(), s);
  }
  const Point loaded = s;
  const double tau0 = trial_tau(c, lx, lat, lat, s)(0, 0);
  // Unload by a strain increment of 1e-4 (the elastic range is about 4e-3 here).
  const double l1 = lx * std::exp(-1e-4);
  const double lat1 = free_lateral(c, l1, lat, s, true);
  const J2Result r = map_point(c, Eigen::Vector3d(l1, lat1, lat1).asDiagonal().toDenseMatrix(), s);
  const double slope = (tau0 - r.tau(0, 0)) / 1e-4;
  std::printf("unloading from alpha %.4f: slope %.5g Pa, E = %.5g Pa (ratio %.5f)\n", s.alpha,
              slope, youngs(c), slope / youngs(c));
  EXPECT_FALSE(r.plastic);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(s.m.cp_inv[k], loaded.m.cp_inv[k]);
  EXPECT_EQ(s.alpha, loaded.alpha);
  EXPECT_NEAR(slope / youngs(c), 1.0, 0.01);
}

TEST(J2Plasticity, RotationRotatesTheStressAndLeavesThePlasticStrain) {
  const J2Constants c = steel();
  Eigen::Matrix3d F;
  F << 1.08, 0.05, 0.01, -0.02, 0.97, 0.03, 0.0, 0.01, 0.99;
  Point a, b;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const J2Result ra = map_point(c, F, a);
  const J2Result rb = map_point(c, R * F, b);
  const double dtau = (R * ra.tau * R.transpose() - rb.tau).norm() / ra.tau.norm();
  std::printf("rotated: |R tau R^T - tau(RF)| / |tau| = %.2e, alpha %.5f vs %.5f\n", dtau, a.alpha,
              b.alpha);
  ASSERT_TRUE(ra.plastic);
  EXPECT_LT(dtau, 1e-12);
  EXPECT_NEAR(a.alpha, b.alpha, 1e-14);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(a.m.cp_inv[k], b.m.cp_inv[k], 1e-13);
}

}  // namespace
}  // namespace sph
