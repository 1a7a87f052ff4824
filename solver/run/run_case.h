#pragma once
// The solver's entry point: run one case on the ranks of an MPI communicator. This is the
// whole interface the worker (local mode and pool mode) uses; the solver knows nothing of
// gRPC or SQLite.
#include <mpi.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

struct Progress {
  std::int64_t step = 0;
  double time = 0;                       // simulated time [s]
  double end_time = 0;                   // [s]
  double dt = 0;                         // current time step [s]
  std::int64_t particles = 0;            // owned particles over all ranks
  double particle_steps_per_second = 0;  // throughput since the previous report
  double eta_seconds = -1;               // wall-clock estimate to end_time (-1 unknown)
  double wall_seconds = 0;               // since the run (or resume) started
  double imbalance = 1;                  // max/mean owned particles per rank
  int ranks = 1;
};

enum class RunStatus {
  kCompleted,    // reached end_time or a stop criterion
  kCancelled,    // cancel_requested returned true; the last state was written
  kInterrupted,  // interrupt flag (e.g. SIGTERM) set; a checkpoint was written
  kUnstable,     // a stability guard tripped; `message` is the diagnosis, bad state not written
  kError,        // invalid case, I/O failure, ...
};

const char* to_string(RunStatus s);

struct RunOutcome {
  RunStatus status = RunStatus::kError;
  std::string message;             // one line; for kUnstable: criterion, particle, position, step
  std::vector<std::string> files;  // result files written (absolute paths): result.h5, result.xmf
  std::string last_checkpoint;     // newest checkpoint written, if any
  std::int64_t steps = 0;
  double time = 0;
  double wall_seconds = 0;
  // Active physics units and their share of the step time (name -> seconds, rank 0).
  std::map<std::string, double> unit_seconds;
  // Per-particle storage (and neighbour lists) by the unit that owns it, all ranks [bytes].
  std::map<std::string, double> unit_bytes;
  // Fresh neighbour searches since t = 0 (every step without a Verlet skin; the steps between
  // keep the candidates of the last one).
  std::int64_t neighbor_searches = 0;
};

struct RunOptions {
  std::string output_dir;  // result.h5 + result.xmf; checkpoints/ below it
  // Resume from this checkpoint file (empty: start at t = 0). Snapshots and time series up to
  // the checkpoint are carried over from `previous_result` when that file is readable.
  std::string resume_from;
  std::string previous_result;
  // Extra metadata written into result.h5 (job id, attempt, ...).
  std::map<std::string, std::string> metadata;
  std::string case_text;  // stored verbatim in the result; default: the canonical text form

  double progress_interval_seconds = 1.0;
  // Rank 0 only. Called every progress_interval_seconds and once at the end.
  std::function<void(const Progress&)> on_progress;
  // Rank 0 only, polled once per step; returning true stops the run at this step boundary
  // (status kCancelled). The decision is shared with all ranks.
  std::function<bool()> cancel_requested;
  // Rank 0 only: called after a checkpoint file has been written and renamed into place.
  std::function<void(const std::string& path, std::int64_t step, double time)> on_checkpoint;
  // Any rank may set this (e.g. from a signal handler); at the next step boundary all ranks
  // write a checkpoint and return kInterrupted.
  const std::atomic<bool>* interrupt = nullptr;
  // Rank 0 only, polled once per step; returning true writes a checkpoint and continues.
  std::function<bool()> checkpoint_requested;
  // Keep only the two newest files in checkpoints/ (false: keep all; a pool deletes them
  // itself once the server has heard of newer ones, see worker/pool/checkpoint_pruner.h).
  bool prune_checkpoints = true;
  bool quiet = false;  // no progress lines on stdout (rank 0)
  // Balance ranks by a fixed work per particle kind instead of by each particle's pairs
  // (solver/parallel/load_balance.h); for benchmarks that compare the two.
  bool balance_by_kind = false;
};

// Runs a validated case. Collective over `comm`: every rank calls it with the same case.
// The strings of the options (output_dir, case_text, metadata) are taken from rank 0;
// callbacks are used on rank 0 only. Never throws; errors come back as kError.
RunOutcome run_case(const v1::Case& c, MPI_Comm comm, const RunOptions& options);

}  // namespace sph
