#pragma once
// Rank 0's reporting thread for one attempt. The solver's callbacks only store what they have
// (progress, new checkpoints) and read flags; this thread makes the Report calls, so a slow
// or absent server never stalls a time step. Each Report renews the lease and brings back a
// cancel request; an ABORTED reply means the lease was lost and the attempt must stop.
// It also deletes old checkpoints once the server has acknowledged newer ones
// (CheckpointPruner): the solver of a pool keeps them all.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "solver/run/run_case.h"
#include "sph/v1/service.pb.h"
#include "worker/pool/checkpoint_pruner.h"
#include "worker/pool/server_link.h"

namespace sph::worker::pool {

v1::ProgressInfo to_proto(const Progress& p);

class AttemptReporter {
 public:
  // stall_seconds > 0: stop renewing the lease when the solver has not called back for that
  // long (a hung run must not hold its job forever; the server then gives it to another pool).
  AttemptReporter(ServerLink& link, std::string job_id, int attempt, double interval_seconds,
                  double stall_seconds);
  ~AttemptReporter();
  AttemptReporter(const AttemptReporter&) = delete;
  AttemptReporter& operator=(const AttemptReporter&) = delete;

  // Solver callbacks (rank 0's solver thread).
  void on_progress(const Progress& p);
  void on_progress(const v1::ProgressInfo& p);  // e.g. with a study's ladder progress
  void on_checkpoint(const std::string& path, std::int64_t step, double time);
  // A line for the attempt's log on the server (sphctl logs): sent with the next report, or
  // with the Finish (take_log). Any thread.
  void log(const std::string& text);
  // Adds a line for the newest progress unless one was logged for its step: a run shorter
  // than a report interval ends with one too.
  void log_progress();
  // After stop(): the lines no report carried, for the Finish.
  std::vector<v1::LogLine> take_log();
  // Polled by the solver once per step; doubles as its heartbeat.
  bool should_stop();

  // Stops the thread without a last report: the Finish that follows carries the newest
  // progress and checkpoint (last_progress, last_checkpoint).
  void stop();

  // After stop(): the Finish carrying `path`, the attempt's newest checkpoint, was accepted.
  // The server now resumes the job (if ever) from it, so the checkpoints written before it
  // that no report carried (written while the server was away, or just before the end) count
  // as acknowledged too, in order: without that a pool that finished before its first report
  // after an outage left every checkpoint of the outage on disk.
  void finish_acknowledged(const std::string& path);

  bool lost() const { return lost_.load(); }
  bool cancel_requested() const { return cancel_requested_.load(); }
  std::optional<v1::ProgressInfo> last_progress() const;
  std::optional<v1::Checkpoint> last_checkpoint() const;

 private:
  void run();
  void send();                                          // one Report with whatever is pending
  void log_progress_locked(const v1::ProgressInfo& p);  // mu_ held

  ServerLink& link_;
  const std::string job_id_;
  const int attempt_;
  const std::chrono::milliseconds interval_;
  const std::chrono::milliseconds stall_;
  std::atomic<std::chrono::steady_clock::rep> heartbeat_;
  bool stalled_ = false;  // only the reporting thread uses it
  mutable std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  bool urgent_ = false;  // a checkpoint waits to be reported
  std::optional<v1::ProgressInfo> progress_;
  bool progress_sent_ = true;
  std::vector<v1::Checkpoint> pending_checkpoints_;
  std::optional<v1::Checkpoint> last_checkpoint_;
  std::vector<v1::LogLine> pending_log_;
  std::int64_t logged_step_ = -1;  // step of the newest progress line
  std::int64_t log_dropped_ = 0;   // lines dropped while the server was away too long
  std::atomic<bool> cancel_requested_{false};
  std::atomic<bool> lost_{false};
  bool server_away_ = false;  // only the reporting thread uses it
  CheckpointPruner pruner_;   // the reporting thread's until stop(), then the caller's
  std::thread thread_;
};

}  // namespace sph::worker::pool
