#pragma once
// What a convergence study says: the observed order (error against dx), what accuracy costs
// (error against wall time), and the resolution and cost for target errors, all from
// least-squares power laws over the levels with an error (analysis/order_fit.h).
#include <vector>

#include "analysis/order_fit.h"
#include "study/level_result.h"

namespace sph::study {

struct TargetResolution {
  double error = 0;        // target, e.g. 0.01
  bool reachable = false;  // false: some level misses it and the error does not fall with dx
  double dx = 0;
  double particles = 0;
  double core_seconds_per_simulated_second = 0;
  // Every level is within the target: the coarsest level's own dx, particles and cost. (A
  // coarser dx may do too, but extrapolating a power law towards a handful of particles
  // across the geometry says nothing reliable.)
  bool met_by_every_level = false;
  // Otherwise dx, particles and cost come from the fitted power laws: interpolated within the
  // measured errors, or extrapolated beyond the finest level (less certain the further).
  bool extrapolated = false;
};

struct StudySummary {
  analysis::PowerFit error_vs_dx;    // slope: the observed order
  analysis::PowerFit error_vs_wall;  // slope: error ~ wall^slope
  analysis::PowerFit cost_vs_dx;     // core-seconds per simulated second against dx
  analysis::PowerFit particles_vs_dx;
  double error_min = 0, error_max = 0;  // over the fitted levels
  std::vector<TargetResolution> targets;
};

constexpr double kTargetErrors[] = {0.01, 0.05, 0.10};

StudySummary summarize_study(const std::vector<LevelResult>& levels);

}  // namespace sph::study
