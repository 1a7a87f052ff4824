#pragma once
// The convergence-study runner: one case run at every level of a ladder of particle spacings,
// each level in OUTPUT/level_<k>/ (the case with dx replaced, everything else unchanged),
// each measured against the case's reference for error, wall time, particle-steps, peak
// memory and ranks; then OUTPUT/study.csv, study.md and study.png. Used by sph-worker's local
// mode and by worker pools (study jobs); knows nothing of gRPC or SQLite.
//
// Resuming: a level that is over has level_<k>/level.txt. Running the study again into the
// same directory skips such levels, and a pool's later attempt takes them (copied) from the
// earlier attempts' directories. An interrupted level continues from its newest checkpoint
// when the checkpoint's level case is the same (level_<k>/case.textproto).
#include <mpi.h>

#include <atomic>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "solver/run/run_case.h"
#include "sph/v1/case.pb.h"
#include "study/level_result.h"
#include "study/study_summary.h"

namespace sph::study {

struct StudyProgress {
  int level = 0;  // 1-based
  int levels = 0;
  double dx = 0;
  // Share of the whole ladder's work done (levels weighted by estimated particle-steps) and
  // the wall-clock estimate to the end of the ladder (-1 unknown).
  double fraction = 0;
  double eta_seconds = -1;
  Progress run;  // the level now running
};

struct StudyOptions {
  std::string output_dir;
  // Output directories of earlier attempts of the same study (newest first): their completed
  // levels are copied instead of run again.
  std::vector<std::string> previous_dirs;
  // A checkpoint to continue from (a pool's claim): used for the level whose directory holds
  // it, when that level's case is unchanged.
  std::string resume_from;
  // How the ladder was asked for, for the report ("--refine 4 (ratio 1.41421)").
  std::string ladder_description;
  std::map<std::string, std::string> metadata;  // into every level's result.h5

  double progress_interval_seconds = 1.0;
  // Rank 0 only, like RunOptions: progress of the running level and the ladder.
  std::function<void(const StudyProgress&)> on_progress;
  std::function<bool()> cancel_requested;
  std::function<void(const std::string& path, std::int64_t step, double time)> on_checkpoint;
  const std::atomic<bool>* interrupt = nullptr;
  std::function<bool()> checkpoint_requested;
  bool prune_checkpoints = true;  // as RunOptions::prune_checkpoints, for every level
  // Rank 0 only: one line per finished level (local mode prints it).
  std::function<void(const LevelResult&)> on_level;
  bool quiet = false;  // no per-step progress lines of the solver
  bool plot = true;    // make study.png
  std::string python;  // interpreter for the plot; default study::default_python()
};

struct StudyOutcome {
  // kCompleted when at least two levels have an error (an order can be fitted); kCancelled,
  // kInterrupted and kError as for run_case (kError also when the ladder gave no order).
  RunStatus status = RunStatus::kError;
  std::string message;             // one line
  std::vector<std::string> files;  // absolute paths: study.{csv,md,png}, level_<k>/result.*
  std::string last_checkpoint;
  std::vector<LevelResult> levels;
  StudySummary summary;
  std::string plot_problem;  // why study.png is missing, or ""
};

// Collective over comm. The case must be valid with a reference; `ladder` holds the dx of
// each level, coarsest first (case/study_ladder.h). Strings of the options come from rank 0,
// callbacks run on rank 0. The outcome is complete on rank 0 (status is shared by all ranks).
StudyOutcome run_study(const v1::Case& c, const std::vector<double>& ladder, MPI_Comm comm,
                       const StudyOptions& options);

}  // namespace sph::study
