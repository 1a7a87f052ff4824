#include "analysis/richardson.h"
#include "case/number_text.h"

#include <cmath>
#include <cstdio>

namespace sph::analysis {
namespace {

// Solves (h1^p - h2^p) / (h2^p - h3^p) = ratio for p by bisection (the left side grows
// monotonically with p for h1 > h2 > h3).
std::optional<double> solve_order(double h1, double h2, double h3, double ratio) {
  auto f = [&](double p) {
    return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)) - ratio;
  };
  double lo = 0.05, hi = 12;
  if (f(lo) > 0 || f(hi) < 0) return std::nullopt;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

RichardsonEstimate richardson_extrapolate(const std::vector<double>& dx,
                                          const std::vector<double>& q, std::optional<double> order,
                                          std::optional<double> scale) {
  RichardsonEstimate out;
  const std::size_t n = dx.size();
  if (n != q.size() || n < 2 || (!order && n < 3)) {
    out.problem = order ? "needs two levels" : "needs three levels to estimate the order";
    return out;
  }
  const double hc = dx[n - 2], hf = dx[n - 1], qc = q[n - 2], qf = q[n - 1];
  double p = 0;
  if (order) {
    p = *order;
  } else {
    const double q1 = q[n - 3], d12 = q1 - qc, d23 = qc - qf;
    if (d23 == 0 || d12 / d23 <= 0) {
      out.problem =
          "the three finest levels do not converge monotonically (q = " + number_text(q1) + ", " +
          number_text(qc) + ", " + number_text(qf) + "); give reference.richardson.order";
      return out;
    }
    const auto solved = solve_order(dx[n - 3], hc, hf, d12 / d23);
    if (!solved) {
      out.problem = "no order in (0.05, 12) fits the three finest levels (q = " + number_text(q1) +
                    ", " + number_text(qc) + ", " + number_text(qf) +
                    "); give reference.richardson.order";
      return out;
    }
    p = *solved;
    out.order_estimated = true;
  }
  out.order = p;
  out.extrapolated = qf + (qf - qc) / (std::pow(hc / hf, p) - 1);
  const double s = scale ? *scale : std::abs(out.extrapolated);
  if (!(s > 0)) {
    out.problem = "the extrapolated value is 0: give reference.richardson.scale";
    return out;
  }
  for (double v : q) out.errors.push_back(std::abs(v - out.extrapolated) / s);
  out.ok = true;
  return out;
}

}  // namespace sph::analysis
