#pragma once
// Richardson extrapolation for cases without an exact answer: a quantity q(dx) = q* + C dx^p
// measured on a ladder of resolutions gives q* from the finest levels, and so an error
// estimate |q - q*| for every level. With the order p unknown it is solved from the three
// finest levels, (q1 - q2) / (q2 - q3) = (dx1^p - dx2^p) / (dx2^p - dx3^p), which needs
// monotone convergence there; the estimate is then exact for those three by construction, so
// a report states which order was assumed or estimated.
#include <optional>
#include <string>
#include <vector>

namespace sph::analysis {

struct RichardsonEstimate {
  bool ok = false;
  std::string problem;      // why not, when !ok
  double extrapolated = 0;  // q*
  double order = 0;         // p used
  bool order_estimated = false;
  std::vector<double> errors;  // |q_k - q*| / scale per level
};

// dx: coarsest first, q: the quantity per level (all finite). scale: default |q*|.
RichardsonEstimate richardson_extrapolate(const std::vector<double>& dx,
                                          const std::vector<double>& q, std::optional<double> order,
                                          std::optional<double> scale);

}  // namespace sph::analysis
