#pragma once
// Observed orders: least-squares power laws y = C x^slope fitted in log-log space (error
// against dx gives the order of convergence, error against wall time what accuracy costs),
// and the x at which a fitted law reaches a target.
#include <vector>

namespace sph::analysis {

struct PowerFit {
  bool ok = false;
  double slope = 0;
  double intercept = 0;  // log y = intercept + slope log x
  int points = 0;
  double x_min = 0, x_max = 0;      // range of the fitted x
  double value_at(double x) const;  // C x^slope
  double x_for(double y) const;     // the x with value_at(x) = y (needs slope != 0)
};

// Pairs with a non-positive or non-finite x or y are skipped; needs two points.
PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace sph::analysis
