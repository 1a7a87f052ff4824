#include "analysis/conduction.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sph::analysis {

double conduction_profile(const v1::ConductionReference& r, double x, double t) {
  const double xi = x - r.boundary();
  if (t <= 0) return xi > 0 ? r.initial_value() : r.boundary_value();
  return r.boundary_value() + (r.initial_value() - r.boundary_value()) *
                                  std::erf(xi / (2 * std::sqrt(r.diffusivity() * t)));
}

Measurement conduction_error(const Snapshot& s, const std::vector<double>& values,
                             const v1::ConductionReference& r) {
  if (values.size() != s.size())
    throw std::runtime_error("conduction: the field has " + std::to_string(values.size()) +
                             " values for " + std::to_string(s.size()) + " particles");
  double worst = 0, where = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s.position[3 * i];
    if (s.kind[i] == 1 || x < r.boundary() || (r.has_x_max() && x > r.x_max())) continue;
    const double e = std::abs(values[i] - conduction_profile(r, x, s.time));
    if (e > worst) worst = e, where = x;
    ++n;
  }
  if (n == 0) throw std::runtime_error("conduction: no fluid or rigid particles to compare");
  Measurement m;
  m.error = worst / std::abs(r.boundary_value() - r.initial_value());
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "max |T - T_exact| = %.3e (at x = %.4g) over %d particles at t = %g", worst, where,
                n, s.time);
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
