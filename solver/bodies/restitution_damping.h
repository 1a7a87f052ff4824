#pragma once
// The damping ratio at which the spring-dashpot of Fuchs 2021 eq. 27 restitutes a requested
// coefficient e. With the tension cut-off a contact ends when the force k x + d v reaches zero,
// before the overlap x does (Schwager & Poeschel 2007, Granular Matter 9:465), so e is not the
// linear oscillator's exp(-pi zeta / sqrt(1 - zeta^2)): at zeta = 0.3 the law gives 0.451, the
// linear formula 0.372. In units of the undamped frequency sqrt(k/m_eff), x'' + 2 zeta x' + x
// = 0 from x = 0, x' = 1 until x + 2 zeta x' = 0 at t_c, and there -x' = exp(-zeta t_c)
// exactly (the oscillating factor is -1 at t_c), with
//   zeta < 1:  t_c = (pi - atan2(2 zeta w, 1 - 2 zeta^2)) / w,  w = sqrt(1 - zeta^2),
//   zeta = 1:  t_c = 2,
//   zeta > 1:  t_c = 2 ln(zeta + W) / W,                        W = sqrt(zeta^2 - 1).
#include <cmath>
#include <numbers>

namespace sph {

// e of the cut-off law at damping ratio zeta = d / (2 sqrt(k m_eff)) >= 0; decreases from 1
// at zeta = 0 towards 0 (about 1 / (4 zeta^2)) as zeta grows.
inline double cutoff_restitution(double zeta) {
  if (zeta <= 0) return 1.0;
  double t = 2.0;
  if (zeta < 1) {
    const double w = std::sqrt(1 - zeta * zeta);
    t = (std::numbers::pi - std::atan2(2 * zeta * w, 1 - 2 * zeta * zeta)) / w;
  } else if (zeta > 1) {
    const double W = std::sqrt(zeta * zeta - 1);
    t = 2 * std::log(zeta + W) / W;
  }
  return std::exp(-zeta * t);
}

// The zeta with cutoff_restitution(zeta) = e, for e in (0, 1] (bisection in log zeta; e = 0
// needs an infinite dashpot).
inline double damping_ratio_for_restitution(double e) {
  if (e >= 1) return 0;
  double lo = 1e-12, hi = 1e12;
  for (int k = 0; k < 200; ++k) {
    const double mid = std::sqrt(lo * hi);
    (cutoff_restitution(mid) > e ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace sph
