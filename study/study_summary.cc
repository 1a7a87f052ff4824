#include "study/study_summary.h"

#include <algorithm>
#include <cmath>

namespace sph::study {

StudySummary summarize_study(const std::vector<LevelResult>& levels) {
  StudySummary s;
  std::vector<double> dx, err, wall, cost, particles;
  for (const auto& l : levels) {
    if (!l.completed() || !std::isfinite(l.measurement.error) || !(l.measurement.error > 0))
      continue;
    dx.push_back(l.dx);
    err.push_back(l.measurement.error);
    wall.push_back(l.wall_seconds);
    cost.push_back(l.core_seconds_per_simulated_second());
    particles.push_back(l.particles);
  }
  s.error_vs_dx = analysis::fit_power_law(dx, err);
  s.error_vs_wall = analysis::fit_power_law(wall, err);
  s.cost_vs_dx = analysis::fit_power_law(dx, cost);
  s.particles_vs_dx = analysis::fit_power_law(dx, particles);
  if (!err.empty()) {
    s.error_min = *std::min_element(err.begin(), err.end());
    s.error_max = *std::max_element(err.begin(), err.end());
  }
  // The coarsest level with an error, for targets that every level meets.
  const LevelResult* coarsest = nullptr;
  for (const auto& l : levels)
    if (l.completed() && std::isfinite(l.measurement.error) && l.measurement.error > 0 &&
        (coarsest == nullptr || l.dx > coarsest->dx))
      coarsest = &l;
  for (double target : kTargetErrors) {
    TargetResolution t;
    t.error = target;
    // Only an error that falls with dx (positive order) can be bought with resolution.
    const bool falls = s.error_vs_dx.ok && s.error_vs_dx.slope > 0;
    if (coarsest != nullptr && target >= s.error_max) {
      t.reachable = true;
      t.met_by_every_level = true;
      t.dx = coarsest->dx;
      t.particles = coarsest->particles;
      t.core_seconds_per_simulated_second = coarsest->core_seconds_per_simulated_second();
    } else if (falls) {
      t.reachable = true;
      t.dx = s.error_vs_dx.x_for(target);
      t.extrapolated = target < s.error_min;
      if (s.particles_vs_dx.ok) t.particles = s.particles_vs_dx.value_at(t.dx);
      if (s.cost_vs_dx.ok) t.core_seconds_per_simulated_second = s.cost_vs_dx.value_at(t.dx);
    }
    s.targets.push_back(t);
  }
  return s;
}

}  // namespace sph::study
