// Normal mode n of a viscous 2D (cylindrical) drop of radius R in a second viscous fluid,
// linear theory: the 2D counterpart of Miller & Scriven 1968 / Prosperetti 1980 (3D), derived
// for the oscillating-drop validation (docs/surface_tension.md).
//
// Time dependence e^{st}, s = -gamma + i omega. In each fluid u = grad phi + curl(psi e_z) with
// phi harmonic, p = -rho s phi, and psi obeying lap psi = k^2 psi, k^2 = s / nu (Re k > 0):
//   inside  phi = A r^n cos n th,  psi = B I_n(k1 r) / I_n(k1 R) sin n th,
//   outside phi = C r^-n cos n th, psi = D K_n(k2 r) / K_n(k2 R) sin n th.
// At r = R: u_r and u_th continuous, the shear stress mu (r d(u_th/r)/dr + du_r/(r dth))
// continuous, and the normal stress jumps by the capillary pressure of the displacement eta,
// s eta = u_r: (p - 2 mu du_r/dr)_in - (p - 2 mu du_r/dr)_out = sigma (n^2 - 1) eta / R^2.
// The mode is the root of the 4 x 4 determinant near Lamb's i omega_0, omega_0^2 =
// n (n^2 - 1) sigma / ((rho_in + rho_out) R^3). For small viscosity the root tends to
// s = i omega_0 - (1 + i) n / (2 R) sqrt(nu omega_0 / 2) (equal fluids): the two potential flows
// slip at the interface and the shear layer that removes the slip both damps the mode and
// lowers its frequency. Checked against an independent mpmath solution
// (tests/validation/surface_tension/viscous_drop_mode.py) in SurfaceTension.ViscousDropModeTheory.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <utility>

namespace sph::test {

struct DropMode {
  double omega = 0, gamma = 0;  // angular frequency, amplitude decay rate
};

namespace viscous_drop_detail {

using cplx = std::complex<double>;

// I_{n+1}(z) / I_n(z) by the backward recurrence of the continued fraction
// r_m = 1 / (2 (m + 1) / z + r_{m+1}) (Gauss; converges for every z != 0).
inline cplx bessel_i_ratio(int n, cplx z) {
  const int top = n + 60 + static_cast<int>(4 * std::abs(z));
  cplx r = 0;
  for (int m = top; m >= n; --m) r = 1.0 / (2.0 * (m + 1) / z + r);
  return r;
}

// K_nu(z) sqrt(2 z / pi) e^z by its asymptotic series (Abramowitz & Stegun 9.7.2), summed to
// its smallest term; for |z| >= 5 and Re z > 0 the relative error is below about e^{-2|z|}.
inline cplx bessel_k_scaled(int nu, cplx z) {
  cplx sum = 1, term = 1;
  double last = 1;
  for (int k = 1; k < 200; ++k) {
    term *= (4.0 * nu * nu - (2.0 * k - 1) * (2.0 * k - 1)) / (8.0 * k * z);
    if (std::abs(term) > last) break;
    last = std::abs(term);
    sum += term;
  }
  return sum;
}

inline cplx det4(std::array<std::array<cplx, 4>, 4> m) {
  cplx d = 1;
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (p != c) {
      std::swap(m[p], m[c]);
      d = -d;
    }
    if (m[c][c] == 0.0) return 0;
    d *= m[c][c];
    for (int r = c + 1; r < 4; ++r) {
      const cplx f = m[r][c] / m[c][c];
      for (int j = c; j < 4; ++j) m[r][j] -= f * m[c][j];
    }
  }
  return d;
}

// The determinant of the interface conditions (rows) on A, B, C, D (columns).
inline cplx interface_determinant(cplx s, int n, double R, double rho1, double rho2, double mu1,
                                  double mu2, double sigma) {
  const cplx k1 = std::sqrt(s * rho1 / mu1), k2 = std::sqrt(s * rho2 / mu2);
  const cplx z1 = k1 * R, z2 = k2 * R;
  // Logarithmic derivatives w'(z) / w(z): I_n' = I_{n+1} + n I_n / z, K_n' = -K_{n-1} - n K_n / z.
  const cplx di = bessel_i_ratio(n, z1) + double(n) / z1;
  const cplx dk = -bessel_k_scaled(n - 1, z2) / bessel_k_scaled(n, z2) - double(n) / z2;
  // w'' / w = 1 + n^2 / z^2 - (w' / w) / z (the modified Bessel equation).
  const cplx ddi = 1.0 + double(n * n) / (z1 * z1) - di / z1;
  const cplx ddk = 1.0 + double(n * n) / (z2 * z2) - dk / z2;
  const double Rn = std::pow(R, n), dn = n;
  // Radial profiles at r = R: U_r, dU_r/dr, U_th, dU_th/dr of u_r = U_r cos, u_th = U_th sin.
  struct Column {
    cplx ur, dur, ut, dut, p;
    double mu, sign;
  };
  const Column col[4] = {
      {n * Rn / R, n * (n - 1.0) * Rn / (R * R), -n * Rn / R, -n * (n - 1.0) * Rn / (R * R),
       -rho1 * s * Rn, mu1, 1},
      {n / R, dn * k1 * di / R - dn / (R * R), -k1 * di, -k1 * k1 * ddi, 0, mu1, 1},
      {-n / (Rn * R), n * (n + 1.0) / (Rn * R * R), -n / (Rn * R), n * (n + 1.0) / (Rn * R * R),
       -rho2 * s / Rn, mu2, -1},
      {n / R, dn * k2 * dk / R - dn / (R * R), -k2 * dk, -k2 * k2 * ddk, 0, mu2, -1},
  };
  std::array<std::array<cplx, 4>, 4> m;
  for (int j = 0; j < 4; ++j) {
    const Column& c = col[j];
    m[0][j] = c.sign * c.ur;
    m[1][j] = c.sign * c.ut;
    m[2][j] = c.sign * c.mu * (c.dut - c.ut / R - double(n) * c.ur / R);
    m[3][j] = c.sign * (c.p - 2.0 * c.mu * c.dur);
    if (j < 2) m[3][j] -= sigma * (n * n - 1.0) / (R * R) * c.ur / s;
  }
  return det4(m);
}

// A free drop (void outside): the inside columns (A, B) and the two stress conditions at
// r = R, zero shear stress and p - 2 mu du_r/dr = sigma (n^2 - 1) eta / R^2 with s eta = u_r.
inline cplx free_surface_determinant(cplx s, int n, double R, double rho, double mu, double sigma) {
  const cplx k = std::sqrt(s * rho / mu), z = k * R;
  const cplx di = bessel_i_ratio(n, z) + double(n) / z;
  const cplx ddi = 1.0 + double(n * n) / (z * z) - di / z;
  const double Rn = std::pow(R, n), dn = n;
  const cplx ur[2] = {n * Rn / R, n / R};
  const cplx dur[2] = {n * (n - 1.0) * Rn / (R * R), dn * k * di / R - dn / (R * R)};
  const cplx ut[2] = {-n * Rn / R, -k * di};
  const cplx dut[2] = {-n * (n - 1.0) * Rn / (R * R), -k * k * ddi};
  const cplx p[2] = {-rho * s * Rn, 0.0};
  cplx m[2][2];
  for (int j = 0; j < 2; ++j) {
    m[0][j] = mu * (dut[j] - ut[j] / R - dn * ur[j] / R);
    m[1][j] = p[j] - 2.0 * mu * dur[j] - sigma * (n * n - 1.0) / (R * R) * ur[j] / s;
  }
  return m[0][0] * m[1][1] - m[0][1] * m[1][0];
}

}  // namespace viscous_drop_detail

// The mode by the secant method from Lamb's frequency and the small-viscosity estimate.
// Valid where |k R| = R sqrt(omega rho / mu) >= 5 on both sides (the K_n series).
inline DropMode viscous_cylinder_drop_mode(int n, double R, double rho_in, double rho_out,
                                           double mu_in, double mu_out, double sigma) {
  using viscous_drop_detail::cplx;
  const double w0 = std::sqrt(n * (n * n - 1.0) * sigma / ((rho_in + rho_out) * R * R * R));
  const double nu = (mu_in + mu_out) / (rho_in + rho_out);
  auto f = [&](cplx s) {
    return viscous_drop_detail::interface_determinant(s, n, R, rho_in, rho_out, mu_in, mu_out,
                                                      sigma);
  };
  cplx s0(0, w0), s1 = s0 - cplx(1, 1) * (n / (2 * R)) * std::sqrt(nu * w0 / 2);
  cplx f0 = f(s0), f1 = f(s1);
  for (int it = 0; it < 100 && std::abs(s1 - s0) > 1e-14 * w0; ++it) {
    const cplx s2 = s1 - f1 * (s1 - s0) / (f1 - f0);
    s0 = s1;
    f0 = f1;
    s1 = s2;
    f1 = f(s1);
  }
  return {s1.imag(), -s1.real()};
}

// The mode of a free 2D drop (void outside) by the secant method from Lamb's omega_0^2 =
// n (n^2 - 1) sigma / (rho R^3) and the decay rate of the irrotational flow's dissipation,
// gamma = 2 n (n - 1) nu / R^2 (Lamb 1932 sec. 355, 2D), its small-viscosity limit.
inline DropMode free_cylinder_drop_mode(int n, double R, double rho, double mu, double sigma) {
  using viscous_drop_detail::cplx;
  const double w0 = std::sqrt(n * (n * n - 1.0) * sigma / (rho * R * R * R));
  auto f = [&](cplx s) {
    return viscous_drop_detail::free_surface_determinant(s, n, R, rho, mu, sigma);
  };
  cplx s0(0, w0), s1(-2.0 * n * (n - 1.0) * mu / (rho * R * R), w0);
  cplx f0 = f(s0), f1 = f(s1);
  for (int it = 0; it < 100 && std::abs(s1 - s0) > 1e-14 * w0; ++it) {
    const cplx s2 = s1 - f1 * (s1 - s0) / (f1 - f0);
    s0 = s1;
    f0 = f1;
    s1 = s2;
    f1 = f(s1);
  }
  return {s1.imag(), -s1.real()};
}

}  // namespace sph::test
