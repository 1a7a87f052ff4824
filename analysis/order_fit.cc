#include "analysis/order_fit.h"

#include <algorithm>
#include <cmath>

namespace sph::analysis {

double PowerFit::value_at(double x) const {
  return std::exp(intercept + slope * std::log(x));
}

double PowerFit::x_for(double y) const {
  return std::exp((std::log(y) - intercept) / slope);
}

PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y) {
  PowerFit f;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    if (!(x[k] > 0) || !(y[k] > 0) || !std::isfinite(x[k]) || !std::isfinite(y[k])) continue;
    const double lx = std::log(x[k]), ly = std::log(y[k]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    f.x_min = f.points == 0 ? x[k] : std::min(f.x_min, x[k]);
    f.x_max = f.points == 0 ? x[k] : std::max(f.x_max, x[k]);
    ++f.points;
  }
  const double n = f.points, det = n * sxx - sx * sx;
  if (f.points < 2 || !(det > 1e-300)) return f;
  f.slope = (n * sxy - sx * sy) / det;
  f.intercept = (sy - f.slope * sx) / n;
  f.ok = true;
  return f;
}

}  // namespace sph::analysis
