#pragma once
// One level of a convergence study: what it cost and how accurate it was. Stored as
// level_<k>/level.txt once the level is over, so an interrupted study (a killed local run, a
// pool that lost its job) skips it when it resumes.
#include <cstdint>
#include <optional>
#include <string>

#include "analysis/measurement.h"

namespace sph::study {

struct LevelResult {
  int level = 0;  // 1-based, coarsest first
  double dx = 0;
  // "completed", "unstable" (a stability guard stopped it), "error", "cancelled",
  // "interrupted", or "not run" (the study stopped before it).
  std::string status = "not run";
  std::string message;
  double simulated_time = 0;  // [s] reached
  std::int64_t steps = 0;
  double particles = 0;
  double particle_steps = 0;  // steps x particles
  double wall_seconds = 0;    // including earlier attempts when resumed from a checkpoint
  // Processor time (user + system) summed over ranks, this run only: unlike the wall time it
  // does not count time spent waiting for a busy machine's cores. 0 when unknown.
  double cpu_seconds = 0;
  double peak_rss_bytes = 0;  // max over ranks
  int ranks = 0;
  bool reused = false;   // taken from an earlier run of the same level (not run here)
  bool resumed = false;  // continued from a checkpoint
  analysis::Measurement measurement;

  bool completed() const { return status == "completed"; }
  // What the level costs on one core per unit of simulated time: processor seconds (summed
  // over ranks) per simulated second, or wall time x ranks where the processor time is not
  // known (a level resumed from a checkpoint counts its earlier attempts' wall time).
  double core_seconds_per_simulated_second() const;
};

// level.txt in `dir` (written to a temporary file and renamed, so it is there only when the
// level is over). The measurement is not stored: it is evaluated again from result.h5.
void save_level_record(const std::string& dir, const LevelResult& r);
std::optional<LevelResult> load_level_record(const std::string& dir);

}  // namespace sph::study
