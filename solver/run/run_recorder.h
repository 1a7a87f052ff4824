#pragma once
// What a run leaves behind and tells its caller, apart from the physics: the result file
// (snapshots and series, solver/io/result_file.h), checkpoint files and their pruning,
// progress reports with throughput and ETA, and the metadata of the result. The step loop
// decides when; the recorder knows how. Collective where it writes files.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/core/checkpoint_state.h"
#include "solver/core/particle_store.h"
#include "solver/io/checkpoint.h"
#include "solver/io/result_file.h"
#include "solver/parallel/comm.h"
#include "solver/run/run_case.h"

namespace sph {

class RunRecorder {
 public:
  RunRecorder(const Comm& comm, const RunOptions& opt);
  ResultFile& result() { return result_; }
  const ResultFile& result() const { return result_; }

  // Wall-clock start of this run (or resume): progress and the wall-time limits count from it.
  void start_clock();
  double wall_seconds() const;

  template <int D>
  void write_snapshot(const ParticleStore<D>& s, double t, std::int64_t step) {
    result_.write_snapshot(s, t, step);
  }

  // Whether rank 0 is asked for a checkpoint now (a request, or checkpoint_wall_interval
  // seconds since the last one; 0: never by time).
  bool checkpoint_due(double wall_interval) const;
  // Writes checkpoints/ckpt_<step>.h5 with the particles and `state` after flushing the
  // series, keeps the two newest when the options say so, and tells the caller. Returns the
  // path.
  template <int D>
  std::string write_checkpoint(const ParticleStore<D>& s, const CheckpointState& state,
                               std::int64_t step, double t) {
    result_.flush();  // the result file holds every sample up to the checkpoint
    const std::string path = checkpoint_path(step);
    sph::write_checkpoint(comm_, path, s, state);
    after_checkpoint(path, step, t);
    return path;
  }
  const std::string& last_checkpoint() const { return last_checkpoint_; }

  // Progress on rank 0, at most every progress_interval_seconds unless forced: a line on
  // stdout (unless quiet) and the caller's callback.
  void report_progress(Progress p, bool force);

  // The metadata every result carries: the caller's, the case text, code version, ranks,
  // dimension, resolution, kernel and the active units.
  std::map<std::string, std::string> metadata(const std::string& case_text, int dimension,
                                              double dx, double h, double skin, const char* kernel,
                                              const std::vector<std::string>& units) const;
  // Closes the run: status, message and what each unit cost (seconds on rank 0, bytes summed
  // over the ranks), written into /meta. Returns the bytes per unit. Collective.
  std::map<std::string, double> finish(const std::string& status, const std::string& message,
                                       const std::map<std::string, double>& unit_seconds,
                                       const std::map<std::string, std::size_t>& local_bytes,
                                       std::int64_t neighbor_searches);

 private:
  std::string checkpoint_path(std::int64_t step) const;
  void after_checkpoint(const std::string& path, std::int64_t step, double t);

  Comm comm_;
  const RunOptions& opt_;
  ResultFile result_;
  double wall_start_ = 0, last_checkpoint_wall_ = 0;
  double last_progress_wall_ = -1e300, last_progress_time_ = 0;
  std::int64_t last_progress_step_ = 0;
  std::string last_checkpoint_;
};

}  // namespace sph
