// Kernel properties: unit integral, compact support, gradient consistency and dW = W'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "solver/core/kernel.h"
#include "solver/core/types.h"

namespace sph {
namespace {

// Sum of W over a fine lattice approximates the integral of W (spacing h/20).
template <int D, class K>
double lattice_integral(const K& k, double h) {
  const double s = h / 20.0;
  const int n = static_cast<int>(std::ceil(k.support_radius() / s)) + 1;
  double sum = 0;
  if constexpr (D == 2) {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) sum += k.W(std::hypot(i * s, j * s));
    return sum * s * s;
  } else {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j)
        for (int l = -n; l <= n; ++l) sum += k.W(std::sqrt(double(i * i + j * j + l * l)) * s);
    return sum * s * s * s;
  }
}

// On a regular lattice of spacing dx = h, sum_j V_j (x_j - x_i) (x) grad_i W_ij = I
// (first-order consistency of the gradient; exact up to lattice quadrature error).
template <int D, class K>
double gradient_consistency_error(const K& k, double h) {
  const int n = static_cast<int>(std::ceil(k.support_radius() / h)) + 1;
  Eigen::Matrix<double, D, D> m = Eigen::Matrix<double, D, D>::Zero();
  const double vol = std::pow(h, D);
  auto add = [&](const Vec<D>& xj) {
    const double r = xj.norm();
    if (r == 0) return;
    const Vec<D> grad = k.dW(r) / r * (-xj);  // grad_i W(x_i - x_j) with x_i = 0
    m += vol * xj * grad.transpose();
  };
  if constexpr (D == 2) {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) add(Vec<D>(i * h, j * h));
  } else {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j)
        for (int l = -n; l <= n; ++l) add(Vec<D>(i * h, j * h, l * h));
  }
  return (m - Eigen::Matrix<double, D, D>::Identity()).cwiseAbs().maxCoeff();
}

template <class K>
double max_derivative_error(const K& k, double h) {
  double worst = 0;
  for (double r = 0.01 * h; r < k.support_radius(); r += 0.01 * h) {
    const double e = 1e-6 * h;
    const double fd = (k.W(r + e) - k.W(r - e)) / (2 * e);
    worst = std::max(worst, std::abs(fd - k.dW(r)) / std::abs(k.W(0) / h));
  }
  return worst;
}

TEST(Kernel, QuinticSplineIsNormalised) {
  const double h = 0.7;
  EXPECT_NEAR(lattice_integral<2>(QuinticSpline<2>(h), h), 1.0, 1e-6);
  EXPECT_NEAR(lattice_integral<3>(QuinticSpline<3>(h), h), 1.0, 1e-5);
}

TEST(Kernel, WendlandC2IsNormalised) {
  const double h = 1.3;
  EXPECT_NEAR(lattice_integral<2>(WendlandC2<2>(h), h), 1.0, 1e-6);
  EXPECT_NEAR(lattice_integral<3>(WendlandC2<3>(h), h), 1.0, 1e-5);
}

TEST(Kernel, CompactSupportAndDerivative) {
  const double h = 0.5;
  QuinticSpline<2> q(h);
  WendlandC2<3> w(h);
  EXPECT_DOUBLE_EQ(q.support_radius(), 3 * h);
  EXPECT_DOUBLE_EQ(w.support_radius(), 2 * h);
  EXPECT_EQ(q.W(3 * h), 0.0);
  EXPECT_EQ(q.dW(3 * h + 1e-12), 0.0);
  EXPECT_EQ(w.W(2 * h), 0.0);
  EXPECT_LT(max_derivative_error(q, h), 1e-7);
  EXPECT_LT(max_derivative_error(w, h), 1e-7);
  EXPECT_LE(q.dW(0.5 * h), 0.0);
}

// The branch-free bulk evaluation (what the pair table uses) gives W and dW to the bit, on
// every piece of the kernels, at the joints, at and beyond the support, and at r = 0.
template <class K>
int bulk_mismatches(const K& k) {
  std::vector<double> r;
  const double rc = k.support_radius(), h = rc / K::kSupport;
  for (int e = 0; e <= 4000; ++e) r.push_back(1.1 * rc * e / 4000.0);
  for (double joint : {h, 2 * h, rc})
    for (double d : {-1e-15, -1e-16, 0.0, 1e-16, 1e-15}) r.push_back(joint * (1 + d));
  std::vector<double> w(r.size()), dw(r.size());
  k.evaluate(r.size(), r.data(), w.data(), dw.data());
  int bad = 0;
  for (std::size_t e = 0; e < r.size(); ++e) {
    const double w1 = k.W(r[e]), d1 = k.dW(r[e]);
    bad += std::memcmp(&w1, &w[e], sizeof w1) != 0 || std::memcmp(&d1, &dw[e], sizeof d1) != 0;
  }
  return bad;
}

TEST(Kernel, BulkEvaluationEqualsPointwiseToTheBit) {
  EXPECT_EQ(bulk_mismatches(QuinticSpline<2>(0.37)), 0);
  EXPECT_EQ(bulk_mismatches(QuinticSpline<3>(1.3e-6)), 0);
  EXPECT_EQ(bulk_mismatches(WendlandC2<2>(0.37)), 0);
  EXPECT_EQ(bulk_mismatches(WendlandC2<3>(2.1)), 0);
}

// The compact table's evaluation (W and (dW/dr) / r from the squared distance, rounded to
// single precision in the same loop) against W(r) and dW(r) / r rounded once: the largest
// difference in units of the float nearest to the exact value. The quintic divides as the
// table does (0 ulp); the Wendland kernel's polynomial (dW/dr) / r without a division may round
// the other way (at most 1 ulp). At r = 0 (dW/dr) / r is 0.
template <class K>
double compact_ulps(const K& k) {
  std::vector<double> r2;
  const double rc = k.support_radius(), h = rc / K::kSupport;
  for (int e = 0; e <= 4000; ++e) r2.push_back(std::pow(1.1 * rc * e / 4000.0, 2));
  for (double joint : {h, 2 * h, rc})
    for (double d : {-1e-15, 0.0, 1e-15}) r2.push_back(std::pow(joint * (1 + d), 2));
  std::vector<float> w(r2.size()), dwr(r2.size());
  k.evaluate_over_r(r2.size(), r2.data(), w.data(), dwr.data());
  double worst = 0;
  for (std::size_t e = 0; e < r2.size(); ++e) {
    const double r = std::sqrt(r2[e]);
    const auto w1 = static_cast<float>(k.W(r));
    const auto d1 = static_cast<float>(r > 0 ? k.dW(r) / r : 0.0);
    for (const auto& [got, want] : {std::pair{w[e], w1}, std::pair{dwr[e], d1}}) {
      if (got == want) continue;
      const float a = std::abs(want);
      const double ulp =
          static_cast<double>(std::nextafter(a, std::numeric_limits<float>::infinity())) -
          static_cast<double>(a);
      worst = std::max(worst, std::abs(static_cast<double>(got) - static_cast<double>(want)) / ulp);
    }
  }
  return worst;
}

TEST(Kernel, CompactEvaluationIsTheValueRoundedToSinglePrecision) {
  const double ulps[] = {compact_ulps(QuinticSpline<2>(0.37)),
                         compact_ulps(QuinticSpline<3>(1.3e-6)), compact_ulps(WendlandC2<2>(0.37)),
                         compact_ulps(WendlandC2<3>(2.1))};
  std::printf(
      "compact evaluation, ulps of single precision from W and dW/dr / r: quintic 2D %.0f 3D "
      "%.0f, Wendland 2D %.0f 3D %.0f\n",
      ulps[0], ulps[1], ulps[2], ulps[3]);
  EXPECT_EQ(ulps[0], 0.0);
  EXPECT_EQ(ulps[1], 0.0);
  EXPECT_LE(ulps[2], 1.0);
  EXPECT_LE(ulps[3], 1.0);
}

TEST(Kernel, GradientIsFirstOrderConsistentOnTheLattice) {
  // The lattice sum with dx = h is a quadrature of the continuous identity; its error is
  // about 1e-3 for the quintic spline and 2.5e-2 for Wendland C2 (fewer neighbours), and it
  // falls quickly as h/dx grows.
  EXPECT_LT(gradient_consistency_error<2>(QuinticSpline<2>(1.0), 1.0), 1.5e-3);
  EXPECT_LT(gradient_consistency_error<3>(QuinticSpline<3>(1.0), 1.0), 1.5e-3);
  EXPECT_LT(gradient_consistency_error<2>(WendlandC2<2>(1.0), 1.0), 3e-2);
  EXPECT_LT(gradient_consistency_error<2>(QuinticSpline<2>(1.0), 0.5), 1e-5);
}

}  // namespace
}  // namespace sph
