#include "worker/pool/attempt_reporter.h"

#include <cstdio>

#include "common/log.h"

namespace sph::worker::pool {

v1::ProgressInfo to_proto(const Progress& p) {
  v1::ProgressInfo out;
  out.set_step(p.step);
  out.set_time(p.time);
  out.set_end_time(p.end_time);
  out.set_dt(p.dt);
  out.set_particles(p.particles);
  out.set_particle_steps_per_second(p.particle_steps_per_second);
  out.set_eta_seconds(p.eta_seconds);
  out.set_wall_seconds(p.wall_seconds);
  out.set_ranks(p.ranks);
  out.set_imbalance(p.imbalance);
  return out;
}

AttemptReporter::AttemptReporter(ServerLink& link, std::string job_id, int attempt,
                                 double interval_seconds, double stall_seconds)
    : link_(link),
      job_id_(std::move(job_id)),
      attempt_(attempt),
      interval_(static_cast<long long>(interval_seconds * 1000)),
      stall_(static_cast<long long>(stall_seconds * 1000)),
      heartbeat_(std::chrono::steady_clock::now().time_since_epoch().count()),
      thread_([this] { run(); }) {}

bool AttemptReporter::should_stop() {
  heartbeat_.store(std::chrono::steady_clock::now().time_since_epoch().count());
  return cancel_requested_.load() || lost_.load();
}

AttemptReporter::~AttemptReporter() {
  stop();
}

void AttemptReporter::on_progress(const Progress& p) {
  on_progress(to_proto(p));
}

namespace {
// The lines a pool holds for the server while it cannot report (ReportRequest.log's limit).
constexpr std::size_t kMaxPendingLogLines = 1000;

std::int64_t unix_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string progress_line(const v1::ProgressInfo& p) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "progress step %lld t = %.6g of %.6g s, dt %.3g s, %lld particles, %.3g "
                "particle-steps/s, %.1f s wall",
                static_cast<long long>(p.step()), p.time(), p.end_time(), p.dt(),
                static_cast<long long>(p.particles()), p.particle_steps_per_second(),
                p.wall_seconds());
  std::string out = buf;
  if (p.has_study()) {
    std::snprintf(buf, sizeof buf, " (study level %d of %d, dx = %.6g)", p.study().level(),
                  p.study().levels(), p.study().dx());
    out += buf;
  }
  return out;
}
}  // namespace

void AttemptReporter::log(const std::string& text) {
  std::lock_guard lock(mu_);
  if (pending_log_.size() >= kMaxPendingLogLines) {
    pending_log_.erase(pending_log_.begin());  // the newest lines matter most (a diagnosis)
    ++log_dropped_;
  }
  v1::LogLine& l = pending_log_.emplace_back();
  l.set_attempt(attempt_);
  l.set_time_unix_ms(unix_ms());
  l.set_text(text);
}

std::vector<v1::LogLine> AttemptReporter::take_log() {
  std::lock_guard lock(mu_);
  std::vector<v1::LogLine> out;
  out.swap(pending_log_);
  return out;
}

void AttemptReporter::on_progress(const v1::ProgressInfo& p) {
  std::lock_guard lock(mu_);
  progress_ = p;
  progress_sent_ = false;
}

void AttemptReporter::on_checkpoint(const std::string& path, std::int64_t step, double time) {
  v1::Checkpoint cp;
  cp.set_path(path);
  cp.set_step(step);
  cp.set_time(time);
  cp.set_attempt(attempt_);
  {
    std::lock_guard lock(mu_);
    pending_checkpoints_.push_back(cp);
    last_checkpoint_ = cp;
    urgent_ = true;
  }
  // Report it now: the server can only resume from checkpoints it has heard of.
  cv_.notify_all();
}

std::optional<v1::ProgressInfo> AttemptReporter::last_progress() const {
  std::lock_guard lock(mu_);
  return progress_;
}

std::optional<v1::Checkpoint> AttemptReporter::last_checkpoint() const {
  std::lock_guard lock(mu_);
  return last_checkpoint_;
}

void AttemptReporter::stop() {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void AttemptReporter::log_progress() {
  std::lock_guard lock(mu_);
  if (progress_) log_progress_locked(*progress_);
}

void AttemptReporter::log_progress_locked(const v1::ProgressInfo& p) {
  if (p.step() == logged_step_) return;
  logged_step_ = p.step();
  if (pending_log_.size() >= kMaxPendingLogLines) {
    pending_log_.erase(pending_log_.begin());
    ++log_dropped_;
  }
  v1::LogLine& l = pending_log_.emplace_back();
  l.set_attempt(attempt_);
  l.set_time_unix_ms(unix_ms());
  l.set_text(progress_line(p));
}

void AttemptReporter::finish_acknowledged(const std::string& path) {
  std::vector<v1::Checkpoint> pending;
  {
    std::lock_guard lock(mu_);
    pending.swap(pending_checkpoints_);
  }
  for (const auto& cp : pending)
    if (cp.path() != path) pruner_.acknowledged(cp.path());
  pruner_.acknowledged(path);
}

void AttemptReporter::run() {
  std::unique_lock lock(mu_);
  while (!stop_) {
    cv_.wait_for(lock, interval_, [this] { return stop_ || urgent_; });
    if (stop_) break;
    lock.unlock();
    send();
    lock.lock();
  }
}

void AttemptReporter::send() {
  if (lost_.load()) return;
  if (stall_.count() > 0) {
    const auto now = std::chrono::steady_clock::now();
    const auto beat = std::chrono::steady_clock::time_point(
        std::chrono::steady_clock::duration(heartbeat_.load()));
    const bool stalled = now - beat > stall_;
    if (stalled && !stalled_)
      service::log_line(
          "%s: the solver has not advanced for %lld s; no longer renewing the lease so "
          "that the job can run elsewhere",
          job_id_.c_str(),
          static_cast<long long>(
              std::chrono::duration_cast<std::chrono::seconds>(now - beat).count()));
    stalled_ = stalled;
    if (stalled) return;
  }
  v1::ReportRequest req;
  req.set_job_id(job_id_);
  req.set_attempt(attempt_);
  {
    std::lock_guard lock(mu_);
    if (progress_ && !progress_sent_) *req.mutable_progress() = *progress_;
    for (const auto& cp : pending_checkpoints_) *req.add_checkpoints() = cp;
    urgent_ = false;
    // One progress line per report, queued like any other line.
    if (req.has_progress()) log_progress_locked(req.progress());
    for (const auto& l : pending_log_) *req.add_log() = l;
  }
  v1::ReportResponse resp;
  const grpc::Status status = link_.report(req, &resp);
  if (status.ok()) {
    {
      std::lock_guard lock(mu_);
      // Only what this call carried is done; checkpoints written meanwhile stay pending.
      pending_checkpoints_.erase(pending_checkpoints_.begin(),
                                 pending_checkpoints_.begin() + req.checkpoints_size());
      if (req.has_progress() && progress_ && progress_->step() == req.progress().step())
        progress_sent_ = true;
      // Lines logged meanwhile stay pending. (Lines dropped while the server was away were
      // the oldest; the count of those is in the pool's own log.)
      const auto sent =
          std::min<std::size_t>(pending_log_.size(), static_cast<std::size_t>(req.log_size()));
      pending_log_.erase(pending_log_.begin(),
                         pending_log_.begin() + static_cast<std::ptrdiff_t>(sent));
    }
    for (const auto& cp : req.checkpoints()) pruner_.acknowledged(cp.path());
  }
  if (status.ok()) {
    if (server_away_) service::log_line("%s: server is back", job_id_.c_str());
    server_away_ = false;
    if (resp.cancel_requested() && !cancel_requested_.exchange(true))
      service::log_line("%s: cancel requested; stopping at the next step boundary",
                        job_id_.c_str());
  } else if (attempt_lost(status)) {
    lost_.store(true);
    service::log_line("%s attempt %d is no longer ours (%s); stopping without finishing",
                      job_id_.c_str(), attempt_, status.error_message().c_str());
  } else if (!server_away_) {
    // Keep computing: the lease allows for outages, and a restarted server extends it.
    server_away_ = true;
    service::log_line("%s: cannot report (%s); the run goes on, retrying", job_id_.c_str(),
                      status.error_message().c_str());
  }
}

}  // namespace sph::worker::pool
