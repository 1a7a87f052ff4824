#include "case/study_ladder.h"

#include "case/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace sph {
namespace {

std::string num(double v) {
  return number_text(v);
}

// The requested spacings, before snapping, coarsest first.
std::vector<double> requested_dx(const v1::Case& c, const v1::StudySpec& spec) {
  std::vector<double> dx;
  if (spec.dx_size() > 0) {
    dx.assign(spec.dx().begin(), spec.dx().end());
    std::sort(dx.begin(), dx.end(), std::greater<>());
    return dx;
  }
  const double ratio = spec.has_ratio() ? spec.ratio() : kDefaultStudyRatio;
  for (int k = 0; k < spec.refine(); ++k) dx.push_back(c.dx() / std::pow(ratio, k));
  return dx;
}

// Which field the ladder came from, for error messages.
std::string ladder_field(const v1::StudySpec& spec) {
  return spec.dx_size() > 0 ? "study.dx" : "study.refine";
}

}  // namespace

double snap_dx(const v1::Case& c, double dx) {
  if (!c.has_reference() || !c.reference().has_lattice_period()) return dx;
  const double period = c.reference().lattice_period();
  const double n = std::max(1.0, std::round(period / dx));
  return period / n;
}

v1::Case level_case(const v1::Case& c, double dx) {
  v1::Case level = c;
  level.set_dx(dx);
  return level;
}

std::vector<double> study_ladder(const v1::Case& c, const v1::StudySpec& spec) {
  std::vector<double> dx = requested_dx(c, spec);
  for (double& d : dx) d = snap_dx(c, d);
  return dx;
}

std::vector<FieldError> validate_study(const v1::Case& c, const v1::StudySpec& spec,
                                       const ValidationLimits& limits) {
  std::vector<FieldError> errors;
  auto error = [&](const std::string& field, const std::string& msg) {
    errors.push_back({field, msg});
  };
  if (!c.has_reference()) {
    error("reference",
          "a convergence study needs the case's reference { } (an analytic solution, reference "
          "data or Richardson extrapolation; see proto/sph/v1/case.proto)");
    return errors;
  }
  const bool has_list = spec.dx_size() > 0;
  if (has_list && (spec.refine() != 0 || spec.has_ratio())) {
    error("study", "give either refine (with ratio) or dx, not both");
    return errors;
  }
  if (has_list) {
    if (spec.dx_size() < 2) error("study.dx", "needs at least two spacings");
    if (spec.dx_size() > kMaxStudyLevels)
      error("study.dx", "at most " + std::to_string(kMaxStudyLevels) + " levels");
    for (int i = 0; i < spec.dx_size(); ++i)
      if (!std::isfinite(spec.dx(i)) || spec.dx(i) <= 0)
        error("study.dx[" + std::to_string(i) + "]", "must be > 0 (got " + num(spec.dx(i)) + ")");
  } else {
    if (spec.refine() < 2 || spec.refine() > kMaxStudyLevels)
      error("study.refine", "must be in [2, " + std::to_string(kMaxStudyLevels) + "] levels (got " +
                                std::to_string(spec.refine()) + ")");
    if (spec.has_ratio() && (!std::isfinite(spec.ratio()) || spec.ratio() <= 1 || spec.ratio() > 4))
      error("study.ratio", "must be in (1, 4] (got " + num(spec.ratio()) + ")");
  }
  if (!errors.empty()) return errors;

  const std::string field = ladder_field(spec);
  const std::vector<double> dx = study_ladder(c, spec);
  for (std::size_t k = 1; k < dx.size(); ++k)
    if (!(dx[k] < dx[k - 1])) {
      error(has_list ? field : "study.ratio",
            "levels " + std::to_string(k) + " and " + std::to_string(k + 1) +
                " have the same dx = " + num(dx[k]) +
                (c.reference().has_lattice_period()
                     ? " after snapping to reference.lattice_period = " +
                           num(c.reference().lattice_period()) + "; use a larger ratio"
                     : ""));
      return errors;
    }
  const auto& ref = c.reference();
  if (ref.has_richardson() && !ref.richardson().has_order() && dx.size() < 3)
    error(field,
          "a richardson reference without an order needs at least 3 levels (the order "
          "is estimated from the three finest)");
  // Each level must be a valid case on its own (particle limit at the finest, dx-dependent
  // parameters at the coarsest). Report the first level that is not.
  for (std::size_t k = 0; k < dx.size(); ++k) {
    const auto level_errors = validate_case(level_case(c, dx[k]), limits);
    if (level_errors.empty()) continue;
    for (const auto& e : level_errors)
      error(field,
            "level " + std::to_string(k + 1) + " (dx = " + num(dx[k]) + "): " + e.to_string());
    break;
  }
  return errors;
}

}  // namespace sph
