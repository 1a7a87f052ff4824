#include "analysis/taylor_green.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace sph::analysis {

double log_slope(const std::vector<double>& t, const std::vector<double>& v, double t_start) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t k = 0; k < t.size() && k < v.size(); ++k) {
    if (t[k] < t_start || !(v[k] > 0)) continue;
    const double y = std::log(v[k]);
    sx += t[k];
    sy += y;
    sxx += t[k] * t[k];
    sxy += t[k] * y;
    ++n;
  }
  const double det = n * sxx - sx * sx;
  if (n < 2 || !(det > 0))
    throw std::runtime_error("fewer than two samples after the fit start to fit a decay rate");
  return (n * sxy - sx * sy) / det;
}

double taylor_green_decay_rate(const v1::TaylorGreenReference& r) {
  const double k = 2 * std::numbers::pi / r.wavelength();
  return -2 * r.kinematic_viscosity() * k * k;
}

Measurement taylor_green_error(const std::vector<double>& t, const std::vector<double>& max_speed,
                               const v1::TaylorGreenReference& r) {
  const double rate = log_slope(t, max_speed, r.fit_start());
  const double exact = taylor_green_decay_rate(r);
  Measurement m;
  m.quantity = rate;
  m.error = std::abs(rate / exact - 1);
  char buf[160];
  std::snprintf(buf, sizeof buf, "decay rate %.5f vs exact %.5f (fit over t >= %g): %.3f%%", rate,
                exact, r.fit_start(), 100 * m.error);
  m.detail = buf;
  return m;
}

Measurement taylor_green_field_error(const Snapshot& s, const v1::TaylorGreenReference& r,
                                     double decay_rate) {
  const double k = 2 * std::numbers::pi / r.wavelength();
  const double amplitude = r.amplitude() * std::exp(taylor_green_decay_rate(r) * s.time);
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    const double ue = -amplitude * std::cos(k * x) * std::sin(k * y);
    const double ve = amplitude * std::sin(k * x) * std::cos(k * y);
    sum += std::hypot(s.velocity[3 * i] - ue, s.velocity[3 * i + 1] - ve);
    ++n;
  }
  if (n == 0) throw std::runtime_error("taylor_green: the snapshot has no fluid particles");
  Measurement m;
  m.error = sum / n / amplitude;
  m.quantity = decay_rate;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "mean |u - u_exact| = %.3e (%.3f%% of the amplitude %.4g) over %d particles at t = "
                "%g; decay rate %.5f vs exact %.5f",
                sum / n, 100 * m.error, amplitude, n, s.time, decay_rate,
                taylor_green_decay_rate(r));
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
