#pragma once
// The plane-strain steel bar of tests/support/plastic_bar.h against the homogeneous analytic
// curve (tests/validation/plasticity_test.cc, tests/validation/quasi_static_test.cc). While the
// bar deforms homogeneously (before necking), the force per unit thickness that the grips hold
// is F = tau_xx(lambda) W0 / lambda, tau_xx of plane-strain tension with tau_yy = 0 at the gauge
// stretch lambda (an incompressible plastic flow narrows the bar to W0 / lambda and J ~ 1; the
// material-point return mapping gives tau_xx, itself checked against closed forms in
// tests/unit/j2_plasticity_test.cc), and the equivalent plastic strain in the middle follows the
// homogeneous alpha(lambda).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/elastic/j2_plasticity.h"
#include "tests/support/plastic_bar.h"
#include "tests/support/result_reader.h"

namespace sph::test {

constexpr double kPlasticBarWidth = 0.010;

// Homogeneous plane-strain tension (F = diag(lambda, l_y, 1), tau_yy = 0) to each stretch in
// `lambdas` (increasing), in fine increments: tau_xx and alpha.
struct HomogeneousTension {
  std::vector<double> tau, alpha;
};

inline HomogeneousTension homogeneous_tension(const std::vector<double>& lambdas) {
  J2Constants c;
  c.shear = kPlasticBarShear;
  c.bulk = kPlasticBarBulk;
  c.hardening = {4.5e8, 7.15e8, 16.93, 1.2924e8};
  PlasticMetric m;
  double alpha = 0, ly = 1, lx = 1;
  HomogeneousTension out;
  for (double target : lambdas) {
    while (lx < target) {
      lx = std::min(target, lx + 1e-4);
      for (int it = 0; it < 50; ++it) {  // tau_yy(ly) = 0 by Newton (state unchanged)
        auto tyy = [&](double l) {
          PlasticMetric mm = m;
          double aa = alpha;
          return j2_return_map(c, Eigen::Vector3d(lx, l, 1).asDiagonal().toDenseMatrix(), mm, aa)
              .tau(1, 1);
        };
        const double r = tyy(ly), e = 1e-7;
        const double step = r * e / (tyy(ly + e) - r);
        ly -= step;
        if (std::abs(step) < 1e-15) break;
      }
      j2_return_map(c, Eigen::Vector3d(lx, ly, 1).asDiagonal().toDenseMatrix(), m, alpha);
    }
    PlasticMetric mm = m;
    double aa = alpha;
    out.tau.push_back(
        j2_return_map(c, Eigen::Vector3d(lx, ly, 1).asDiagonal().toDenseMatrix(), mm, aa)
            .tau(0, 0));
    out.alpha.push_back(alpha);
  }
  return out;
}

// A bar's run against the homogeneous curve: the worst relative force errors in the elastic
// and plastic ranges, how far the two grips' forces are from cancelling, the last gauge stretch,
// and alpha at the centre at the end against the homogeneous value (each printed).
struct BarComparison {
  double worst_elastic = 0, worst_plastic = 0, worst_balance = 0;
  double last_lambda = 0, alpha_centre = 0, alpha_homogeneous = 0;
  std::size_t samples = 0;
};

inline BarComparison compare_with_homogeneous(const std::string& result_path) {
  BarComparison c;
  ResultReader rr(result_path);
  const auto t = rr.series("diagnostics/time");
  const auto d = rr.series("elastic/bar/displacement");      // 2 points x 2
  const auto f = rr.series("elastic/bar/constraint_force");  // 2 constraints x 2
  EXPECT_EQ(d.size(), 4 * t.size());
  EXPECT_EQ(f.size(), 4 * t.size());
  if (d.size() != 4 * t.size() || f.size() != 4 * t.size()) return c;
  std::vector<double> lambdas;
  std::vector<std::size_t> rows;
  const double gauge = 0.021;  // between the observed particles
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double lambda = 1 + (d[4 * k + 2] - d[4 * k + 0]) / gauge;
    if (lambda > 1.0005 && (lambdas.empty() || lambda > lambdas.back())) {
      lambdas.push_back(lambda);
      rows.push_back(k);
    }
  }
  c.samples = rows.size();
  if (lambdas.empty()) return c;
  const HomogeneousTension h = homogeneous_tension(lambdas);
  for (std::size_t n = 0; n < rows.size(); ++n) {
    const std::size_t k = rows[n];
    const double right = f[4 * k + 2], left = f[4 * k + 0];
    const double expected = h.tau[n] * kPlasticBarWidth / lambdas[n];
    const double err = std::abs(right - expected) / expected;
    double& worst = h.alpha[n] > 0 ? c.worst_plastic : c.worst_elastic;
    worst = std::max(worst, err);
    c.worst_balance = std::max(c.worst_balance, std::abs(right + left) / expected);
    if (n % 5 == 0 || n + 1 == rows.size())
      std::printf(
          "t %.3e  lambda %.5f  F %.5g N/m  homogeneous %.5g N/m  (%+.2f %%)  alpha_h %.4f\n", t[k],
          lambdas[n], right, expected, 100 * (right - expected) / expected, h.alpha[n]);
  }
  // The equivalent plastic strain at the centre of the bar at the end.
  const Snapshot s = rr.last();
  const std::size_t last = rr.snapshot_count() - 1;
  const auto alpha = rr.snapshot_field(last, "equivalent_plastic_strain");
  const auto ux = rr.snapshot_field(last, "elastic_displacement_x");
  double centre = 0;
  int count = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (std::abs(s.position[3 * i] - ux[i]) < 0.003) {
      centre += alpha[i];
      ++count;
    }
  }
  c.last_lambda = lambdas.back();
  c.alpha_centre = centre / count;
  c.alpha_homogeneous = h.alpha.back();
  std::printf(
      "plastic bar: worst force error %.2f %% elastic, %.2f %% plastic (%zu samples to lambda "
      "%.4f), |F_left + F_right| / F <= %.2f %%, alpha at the centre %.4f vs homogeneous %.4f\n",
      100 * c.worst_elastic, 100 * c.worst_plastic, rows.size(), c.last_lambda,
      100 * c.worst_balance, c.alpha_centre, c.alpha_homogeneous);
  return c;
}

}  // namespace sph::test
