#pragma once
// Smoothing kernels W(r, h) with compact support r_c = kappa h.
//  - Quintic spline (Morris, Fox, Zhu 1997), kappa = 3: the kernel of Adami 2012 sec. 3 and
//    Fuchs 2021 Remark 7.
//  - Wendland C2 (Wendland 1995), kappa = 2.
// Both are normalised to unit integral in D dimensions. dW(r) is dW/dr (<= 0).
// evaluate() gives W and dW of many distances at once without branches, so that the loop
// vectorises; each piece beyond its range adds an exact zero, so the values equal W() and dW()
// to the bit (tests/unit/kernel_test.cc checks it).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace sph {

template <int D>
class QuinticSpline {
 public:
  static constexpr double kSupport = 3.0;
  explicit QuinticSpline(double h) : inv_h_(1.0 / h), sigma_(norm() * ipow(1.0 / h)) {}
  double support_radius() const { return kSupport / inv_h_; }
  double W(double r) const {
    const double q = r * inv_h_;
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, b = 2.0 - q, c = 1.0 - q;
    double w = a * a * a * a * a;
    if (q < 2.0) w -= 6.0 * b * b * b * b * b;
    if (q < 1.0) w += 15.0 * c * c * c * c * c;
    return sigma_ * w;
  }
  double dW(double r) const {
    const double q = r * inv_h_;
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, b = 2.0 - q, c = 1.0 - q;
    double w = -5.0 * a * a * a * a;
    if (q < 2.0) w += 30.0 * b * b * b * b;
    if (q < 1.0) w -= 75.0 * c * c * c * c;
    return sigma_ * inv_h_ * w;
  }
  void evaluate(std::size_t n, const double* r, double* w_out, double* dw_out) const {
    const double sw = sigma_, sd = sigma_ * inv_h_, inv_h = inv_h_;
    for (std::size_t k = 0; k < n; ++k) {
      const double q = r[k] * inv_h;
      double w, d;
      pieces(q, w, d);
      w_out[k] = sw * w;
      dw_out[k] = sd * d;
    }
  }
  // W and (dW/dr) / r of n squared distances, rounded to Out (the compact pair table,
  // solver/core/pair_kernel.h) in the same loop. The values before rounding are those of
  // evaluate() at r = sqrt(r2), (dW/dr) / r divided as the table's dW/dr / r; 0 at r = 0,
  // where dW/dr vanishes.
  template <class Out>
  void evaluate_over_r(std::size_t n, const double* __restrict r2, Out* __restrict w_out,
                       Out* __restrict dwr_out) const {
    const double sw = sigma_, sd = sigma_ * inv_h_, inv_h = inv_h_;
    for (std::size_t k = 0; k < n; ++k) {
      const double r = std::sqrt(r2[k]), q = r * inv_h;
      double w, d;
      pieces(q, w, d);
      w_out[k] = static_cast<Out>(sw * w);
      dwr_out[k] = static_cast<Out>(sd * d / (r > 0.0 ? r : 1.0));
    }
  }

 private:
  // The polynomials of W and dW/dr (before sigma and sigma / h) at q = r / h, without
  // branches: each piece beyond its range adds an exact zero.
  static void pieces(double q, double& w, double& d) {
    const double a = std::max(3.0 - q, 0.0), b = std::max(2.0 - q, 0.0), c = std::max(1.0 - q, 0.0);
    w = a * a * a * a * a;
    w -= 6.0 * b * b * b * b * b;
    w += 15.0 * c * c * c * c * c;
    d = -5.0 * a * a * a * a;
    d += 30.0 * b * b * b * b;
    d -= 75.0 * c * c * c * c;
  }
  static constexpr double norm() {
    // 1 / integral of the polynomial: 120 (1D), 478 pi / 7 (2D), 120 pi (3D); the 3D value
    // 3/(359 pi) found in some texts is 0.3% off.
    if constexpr (D == 1) return 1.0 / 120.0;
    if constexpr (D == 2) return 7.0 / (478.0 * std::numbers::pi);
    return 1.0 / (120.0 * std::numbers::pi);
  }
  static double ipow(double x) {
    double r = 1.0;
    for (int i = 0; i < D; ++i) r *= x;
    return r;
  }
  double inv_h_, sigma_;
};

template <int D>
class WendlandC2 {
 public:
  static constexpr double kSupport = 2.0;
  explicit WendlandC2(double h) : inv_h_(1.0 / h), sigma_(norm() * ipow(1.0 / h)) {}
  double support_radius() const { return kSupport / inv_h_; }
  double W(double r) const {
    const double q = r * inv_h_;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return sigma_ * a * a * a * a * (2.0 * q + 1.0);
  }
  double dW(double r) const {
    const double q = r * inv_h_;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return sigma_ * inv_h_ * (-5.0 * q) * a * a * a;
  }
  void evaluate(std::size_t n, const double* r, double* w_out, double* dw_out) const {
    const double sw = sigma_, sd = sigma_ * inv_h_, inv_h = inv_h_;
    for (std::size_t k = 0; k < n; ++k) {
      const double q = r[k] * inv_h;
      const double a = std::max(1.0 - 0.5 * q, 0.0);
      const double w = sw * a * a * a * a * (2.0 * q + 1.0), d = sd * (-5.0 * q) * a * a * a;
      // Selects, not branches; beyond the support d is -0 where dW() returns +0.
      w_out[k] = q < 2.0 ? w : 0.0;
      dw_out[k] = q < 2.0 ? d : 0.0;
    }
  }
  // W and (dW/dr) / r of n squared distances, rounded to Out (the compact pair table,
  // solver/core/pair_kernel.h) in the same loop. dW/dr = sigma/h (-5 q) a^3 with q = r/h, so
  // (dW/dr) / r = -5 sigma/h^2 a^3: no division, and W is evaluate()'s at r = sqrt(r2).
  // (dW/dr) / r is set to 0 at r = 0, where dW/dr vanishes (the passes take a zero as a
  // coincident pair, solver/core/pair_access.h).
  template <class Out>
  void evaluate_over_r(std::size_t n, const double* __restrict r2, Out* __restrict w_out,
                       Out* __restrict dwr_out) const {
    const double sw = sigma_, sdr = -5.0 * sigma_ * inv_h_ * inv_h_, inv_h = inv_h_;
    for (std::size_t k = 0; k < n; ++k) {
      const double q = std::sqrt(r2[k]) * inv_h;
      const double a = std::max(1.0 - 0.5 * q, 0.0);
      const double w = sw * a * a * a * a * (2.0 * q + 1.0), dwr = sdr * a * a * a;
      w_out[k] = static_cast<Out>(q < 2.0 ? w : 0.0);
      dwr_out[k] = static_cast<Out>(q < 2.0 && r2[k] > 0.0 ? dwr : 0.0);
    }
  }

 private:
  static constexpr double norm() {
    if constexpr (D == 1) return 3.0 / 4.0;  // Wendland C2 in 1D differs in form; unused
    if constexpr (D == 2) return 7.0 / (4.0 * std::numbers::pi);
    return 21.0 / (16.0 * std::numbers::pi);
  }
  static double ipow(double x) {
    double r = 1.0;
    for (int i = 0; i < D; ++i) r *= x;
    return r;
  }
  double inv_h_, sigma_;
};

}  // namespace sph
