#pragma once
// Body force per unit mass on fluid particles: gravity ramped up by
// zeta(t) = 0.5 [sin((-0.5 + t/t_damp) pi) + 1] for t <= t_damp (Adami 2012 eq. 13), plus a
// constant driving force (e.g. for Poiseuille flow).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/core/types.h"

namespace sph {

template <int D>
class BodyForce {
 public:
  BodyForce(const Vec<D>& gravity, double damping_time, const Vec<D>& constant)
      : g_(gravity), t_damp_(damping_time), f_(constant) {}
  static double damping_factor(double t, double t_damp) {
    if (t_damp <= 0.0 || t >= t_damp) return 1.0;
    return 0.5 * (std::sin((-0.5 + t / t_damp) * std::numbers::pi) + 1.0);
  }
  Vec<D> at(double t) const { return damping_factor(t, t_damp_) * g_ + f_; }
  // Largest magnitude over the run (for the time-step bound 0.25 sqrt(h/|b|)).
  // max over zeta in [0, 1] of |zeta g + f|: the norm is convex along the ramp.
  double max_magnitude() const { return std::max((g_ + f_).norm(), f_.norm()); }
  bool zero() const { return g_.isZero() && f_.isZero(); }

 private:
  Vec<D> g_;
  double t_damp_;
  Vec<D> f_;
};

}  // namespace sph
