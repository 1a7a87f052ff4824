#include "analysis/hydrostatic.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sph::analysis {

Measurement hydrostatic_error(const Snapshot& s, const v1::HydrostaticReference& r, double rho0,
                              double gravity, double dx) {
  double fluid_mass = 0, p = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] == 0) fluid_mass += s.mass[i];
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    if (s.kind[i] == 1 && x > r.x_min() && x < r.x_max() && y < r.bottom() && y > r.bottom() - dx) {
      p += s.pressure[i];
      ++n;
    }
  }
  if (n == 0)
    throw std::runtime_error(
        "reference.hydrostatic: no wall particles in the first layer under the bottom between "
        "x_min and x_max");
  p /= n;
  const double depth = fluid_mass / (rho0 * r.width());
  const double expected = rho0 * gravity * (depth + 0.5 * dx);
  Measurement m;
  m.quantity = p;
  m.error = std::abs(p / expected - 1);
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "bottom pressure %.5g vs rho g (H + dx/2) = %.5g (H = %.4g, %d wall particles) at "
                "t = %g: %.3f%%",
                p, expected, depth, n, s.time, 100 * m.error);
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
