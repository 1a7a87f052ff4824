#pragma once
// The body force of the manufactured torsion of a ring (ElasticBodyForceField.manufactured_torsion;
// thesis P-III sec. 5.5.1, digest sec. 8.10, after Wang et al. 2019): the force per unit mass that
// holds a neo-Hookean ring at rest with every circle of reference radius R turned by
//   alpha(R, t) = g(t) h(R),  h = (1 - s^2)^2,  s = 2 (R - R_m) / w,  g = alpha0 min(t, t0) / t0,
// w = R_o - R_i, R_m the mid radius. The deformation is isochoric (J = 1), so the neo-Hookean
// first Piola-Kirchhoff stress is mu (F - F^-T), and Div P + rho0 b = 0 gives, in the polar frame
// turned by alpha (the current one),
//   b_r = mu / rho0 R g^2 h'^2,   b_theta = -mu / rho0 g (3 h' + R h'')
// (the thesis' eqs. 26-27 with its undefined A = 2; for R_m = 1, w = 0.5 they are its
// polynomials, digest sec. 8.10). A function of the reference position and time, as a
// manufactured solution's source is.
#include <algorithm>
#include <cmath>

#include "solver/core/types.h"

namespace sph {

template <int D>
struct ManufacturedTorsion {
  Vec<D> center = Vec<D>::Zero();
  double inner = 0, outer = 1, angle = 0, ramp = 1;
  double mu_over_rho0 = 0;

  double turn(double t) const { return angle * std::min(std::max(t, 0.0), ramp) / ramp; }
  // The turn alpha(R, t) of the circle of reference radius R.
  double alpha(double R, double t) const {
    const double s = 2 * (R - 0.5 * (inner + outer)) / (outer - inner);
    return turn(t) * (1 - s * s) * (1 - s * s);
  }
  // The exact displacement of the particle at reference position X.
  Vec<D> displacement(const Vec<D>& X, double t) const {
    const Vec<D> r = X - center;
    const double a = alpha(r.norm(), t), c = std::cos(a), sn = std::sin(a);
    Vec<D> u = Vec<D>::Zero();
    u[0] = (c - 1) * r[0] - sn * r[1];
    u[1] = sn * r[0] + (c - 1) * r[1];
    return u;
  }
  // The body force per unit mass on the particle at reference position X.
  Vec<D> force(const Vec<D>& X, double t) const {
    Vec<D> b = Vec<D>::Zero();
    const double dx = X[0] - center[0], dy = X[1] - center[1];
    const double R = std::hypot(dx, dy);
    if (!(R > 0)) return b;
    const double w = outer - inner, s = 2 * (R - 0.5 * (inner + outer)) / w;
    const double h = (1 - s * s) * (1 - s * s);
    const double h1 = -8 * s * (1 - s * s) / w;         // dh/dR
    const double h2 = -16 * (1 - 3 * s * s) / (w * w);  // d2h/dR2
    const double g = turn(t);
    const double br = mu_over_rho0 * R * g * g * h1 * h1;
    const double bt = -mu_over_rho0 * g * (3 * h1 + R * h2);
    const double phi = std::atan2(dy, dx) + g * h;  // the turned frame
    const double c = std::cos(phi), sn = std::sin(phi);
    b[0] = br * c - bt * sn;
    b[1] = br * sn + bt * c;
    return b;
  }
};

}  // namespace sph
