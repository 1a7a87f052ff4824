#pragma once
// Time-step bound of Fuchs 2021 eq. (41) (Adami 2012 eqs. 19-21): the minimum of
//   0.25 h/(c + |u_max|),  0.125 h^2/nu,  0.25 sqrt(h/|b_max|)
// scaled by a user factor. Artificial viscosity counts as nu = alpha h c/(2(d+2)) (Adami 2012
// eq. 12). The contact and conduction bounds join when those units exist.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sph {

class TimeStepBound {
 public:
  TimeStepBound(double h, double factor, double c_max, double nu_max, double body_max)
      : h_(h), f_(factor), c_(c_max) {
    constant_ = std::numeric_limits<double>::infinity();
    if (nu_max > 0) constant_ = std::min(constant_, 0.125 * h * h / nu_max);
    if (body_max > 0) constant_ = std::min(constant_, 0.25 * std::sqrt(h / body_max));
  }
  // A further bound that does not depend on the flow (conduction 0.1 rho c_p h^2/kappa,
  // Fuchs 2021 eq. 41).
  void add_limit(double dt) {
    if (dt > 0) constant_ = std::min(constant_, dt);
  }
  // dt for the current largest speed and largest particle acceleration. Eq. 41 bounds the
  // body force, 0.25 sqrt(h/|b|); the same bound with the largest particle acceleration
  // (Monaghan 1992 uses |f_i|) also catches a particle squeezed between a body and a wall,
  // whose pressure force can exceed the body force by orders of magnitude for a few steps.
  double dt(double u_max, double a_max = 0) const {
    double bound = std::min(0.25 * h_ / (c_ + u_max), constant_);
    if (a_max > 0) bound = std::min(bound, 0.25 * std::sqrt(h_ / a_max));
    return f_ * bound;
  }

 private:
  double h_, f_, c_, constant_;
};

}  // namespace sph
