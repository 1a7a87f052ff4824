#pragma once
// What an error evaluator reports about one run.
#include <limits>
#include <string>

namespace sph::analysis {

struct Measurement {
  // Relative error against the reference (non-dimensional). NaN when it is not known yet: a
  // Richardson reference needs the whole ladder (analysis/richardson.h).
  double error = std::numeric_limits<double>::quiet_NaN();
  // The measured quantity itself (decay rate, bottom pressure, settling speed, the value
  // Richardson extrapolates), NaN when the error is not of one quantity.
  double quantity = std::numeric_limits<double>::quiet_NaN();
  std::string detail;  // one line for logs and reports: what was measured
};

}  // namespace sph::analysis
