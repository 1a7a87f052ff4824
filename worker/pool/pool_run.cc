#include "worker/pool/pool_run.h"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>

#include "case/load.h"
#include "case/validate.h"
#include "common/auth_token.h"
#include "common/log.h"
#include "solver/run/run_case.h"
#include "worker/local_run.h"
#include "worker/pool/attempt_reporter.h"
#include "worker/pool/pool_command.h"
#include "worker/pool/pool_options.h"
#include "worker/pool/result_manifest.h"
#include "worker/pool/server_link.h"
#include "worker/pool/study_attempt.h"

namespace sph::worker::pool {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) {
  g_stop.store(true);
}

void install_signal_handlers() {
  struct sigaction sa = {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGTERM, SIGINT, SIGUSR1}) sigaction(sig, &sa, nullptr);
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown-host";
  return buf;
}

// Sleeps, but returns early when the pool is told to stop.
void pause_for(milliseconds d) {
  const auto until = Clock::now() + d;
  while (!g_stop.load() && Clock::now() < until)
    std::this_thread::sleep_for(std::min<Clock::duration>(milliseconds(100), until - Clock::now()));
}

milliseconds with_jitter(milliseconds d) {
  static std::mt19937 rng(std::random_device{}());
  std::uniform_real_distribution<double> f(0.8, 1.2);
  return milliseconds(static_cast<long long>(static_cast<double>(d.count()) * f(rng)));
}

// Rank 0: the next job, or nullopt when the pool should exit (idle too long, told to stop, or
// a problem retrying cannot fix, reported through `fatal`).
std::optional<v1::ClaimResponse> next_claim(ServerLink& link, const PoolOptions& o, bool& fatal) {
  const auto idle_since = Clock::now();
  auto backoff = milliseconds(200);
  bool away = false;
  while (!g_stop.load()) {
    double wait = 2.0;  // short long-polls keep SIGTERM handling prompt
    if (o.idle_exit_seconds > 0) {
      const double idle = std::chrono::duration<double>(Clock::now() - idle_since).count();
      if (idle >= o.idle_exit_seconds) {
        service::log_line("no work for %.0f s; exiting (--idle-exit)", idle);
        return std::nullopt;
      }
      wait = std::min(wait, o.idle_exit_seconds - idle);
    }
    v1::ClaimResponse resp;
    const grpc::Status status = link.claim(wait, &resp);
    if (status.ok()) {
      if (away) service::log_line("connected to %s", link.address().c_str());
      away = false;
      backoff = milliseconds(200);
      if (!resp.job_id().empty()) return resp;
      continue;
    }
    const auto code = status.error_code();
    if (code == grpc::StatusCode::UNAUTHENTICATED || code == grpc::StatusCode::INVALID_ARGUMENT ||
        code == grpc::StatusCode::PERMISSION_DENIED || code == grpc::StatusCode::UNIMPLEMENTED) {
      service::log_line("the server refuses this pool: %s", status.error_message().c_str());
      fatal = true;
      return std::nullopt;
    }
    if (!away)
      service::log_line("cannot reach %s (%s); retrying with backoff", link.address().c_str(),
                        status.error_message().c_str());
    away = true;
    pause_for(with_jitter(backoff));
    backoff = std::min(backoff * 2, milliseconds(5000));
  }
  return std::nullopt;
}

v1::AttemptOutcome outcome_for(RunStatus s) {
  switch (s) {
    case RunStatus::kCompleted:
      return v1::ATTEMPT_COMPLETED;
    case RunStatus::kCancelled:
      return v1::ATTEMPT_CANCELLED;
    case RunStatus::kInterrupted:
      return v1::ATTEMPT_INTERRUPTED;
    default:
      return v1::ATTEMPT_FAILED;
  }
}

std::string summary(const RunOutcome& r, int ranks) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s after %lld steps, t = %.6g s, %.1f s wall on %d ranks",
                to_string(r.status), static_cast<long long>(r.steps), r.time, r.wall_seconds,
                ranks);
  return buf;
}

// Rank 0: Finish, retried while the server is away. A refusal for a stale attempt drops the
// result (another attempt owns the job); a rejected manifest is reported as a failure.
// Returns whether the server accepted it.
bool send_finish(ServerLink& link, v1::FinishRequest req) {
  // Once told to stop, the process may be killed soon: do not wait long.
  const auto give_up =
      Clock::now() + (g_stop.load() ? std::chrono::seconds(20) : std::chrono::seconds(600));
  auto backoff = milliseconds(200);
  while (true) {
    v1::FinishResponse resp;
    const grpc::Status status = link.finish(req, &resp);
    if (status.ok()) {
      service::log_line("%s attempt %d finished: %s", req.job_id().c_str(), req.attempt(),
                        v1::JobState_Name(resp.state()).c_str());
      return true;
    }
    if (attempt_lost(status)) {
      service::log_line("%s attempt %d: the server no longer accepts it (%s); result dropped",
                        req.job_id().c_str(), req.attempt(), status.error_message().c_str());
      return false;
    }
    if (status.error_code() == grpc::StatusCode::INVALID_ARGUMENT && req.files_size() > 0) {
      service::log_line("%s: result manifest rejected: %s", req.job_id().c_str(),
                        status.error_message().c_str());
      req.clear_files();
      req.set_outcome(v1::ATTEMPT_FAILED);
      req.set_message("result manifest rejected by the server: " + status.error_message());
      continue;
    }
    if (status.error_code() != grpc::StatusCode::UNAVAILABLE &&
        status.error_code() != grpc::StatusCode::DEADLINE_EXCEEDED &&
        status.error_code() != grpc::StatusCode::INTERNAL) {
      service::log_line("%s: finish refused: %s", req.job_id().c_str(),
                        status.error_message().c_str());
      return false;
    }
    if (Clock::now() >= give_up) {
      service::log_line(
          "%s: cannot reach the server to finish (%s); giving up, the job will run again "
          "after its lease expires",
          req.job_id().c_str(), status.error_message().c_str());
      return false;
    }
    std::this_thread::sleep_for(with_jitter(backoff));
    backoff = std::min(backoff * 2, milliseconds(5000));
  }
}

// Collective: every rank runs the claimed attempt; rank 0 reports and finishes it.
void run_attempt(const v1::ClaimResponse& claim, const PoolOptions& o, ServerLink* link,
                 const std::string& pool_id, int rank, int ranks) {
  v1::FinishRequest finish;
  finish.set_job_id(claim.job_id());
  finish.set_attempt(claim.attempt());

  // The server validated the case; checking again costs little and protects against a pool
  // built from different sources than the server.
  v1::Case c;
  std::string invalid;
  try {
    c = parse_case_text(claim.case_text());
    invalid = join_errors(validate_case(c));
  } catch (const CaseLoadError& e) {
    invalid = e.what();
  }
  if (!invalid.empty()) {
    if (rank == 0) {
      service::log_line("%s: invalid case: %s", claim.job_id().c_str(), invalid.c_str());
      finish.set_outcome(v1::ATTEMPT_FAILED);
      finish.set_message("invalid case: " + invalid);
      send_finish(*link, finish);
    }
    return;
  }
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(claim.output_dir(), ec);
    service::log_line("%s attempt %d: %s, output %s%s%s", claim.job_id().c_str(), claim.attempt(),
                      c.name().c_str(), claim.output_dir().c_str(),
                      claim.resume_from().empty() ? "" : ", resuming from ",
                      claim.resume_from().c_str());
  }
  MPI_Barrier(MPI_COMM_WORLD);  // the directory exists before any rank opens files in it

  std::unique_ptr<AttemptReporter> reporter;
  const double report_interval =
      claim.report_interval_seconds() > 0 ? claim.report_interval_seconds() : 1.0;
  if (rank == 0) {
    reporter = std::make_unique<AttemptReporter>(*link, claim.job_id(), claim.attempt(),
                                                 report_interval, o.stall_timeout_seconds);
    // The attempt's log lines go to the server too (sphctl logs): this pool's log lines from
    // here to the Finish, and a progress line with each report.
    reporter->log(c.name() + ", output " + claim.output_dir() +
                  (claim.resume_from().empty() ? "" : ", resuming from " + claim.resume_from()));
    service::set_log_sink([r = reporter.get()](const std::string& line) { r->log(line); });
  }
  // Removes the sink before the reporter goes, however this function is left.
  struct LogSinkReset {
    ~LogSinkReset() { service::set_log_sink({}); }
  } log_sink_reset;

  RunOptions opt;
  opt.output_dir = claim.output_dir();
  opt.resume_from = claim.resume_from();
  if (!claim.resume_from().empty()) opt.previous_result = claim.previous_result();
  opt.case_text = claim.case_text();
  opt.metadata["mode"] = "pool";
  opt.metadata["job_id"] = claim.job_id();
  opt.metadata["attempt"] = std::to_string(claim.attempt());
  // Metadata goes into result.h5 collectively: it must be the same on every rank.
  opt.metadata["pool"] = pool_id;
  opt.progress_interval_seconds = std::min(1.0, report_interval);
  opt.interrupt = &g_stop;
  opt.quiet = !o.verbose;
  // The reporter deletes old checkpoints once the server knows of newer ones: a pool cut off
  // from the server must not delete the one the job's next attempt resumes from.
  opt.prune_checkpoints = false;
  auto last_checkpoint = Clock::now();
  if (rank == 0) {
    opt.on_progress = [&](const Progress& p) { reporter->on_progress(p); };
    opt.cancel_requested = [&] { return reporter->should_stop(); };
    opt.on_checkpoint = [&](const std::string& path, std::int64_t step, double time) {
      last_checkpoint = Clock::now();
      reporter->on_checkpoint(path, step, time);
    };
    if (o.checkpoint_interval_seconds > 0)
      opt.checkpoint_requested = [&] {
        return Clock::now() - last_checkpoint >=
               std::chrono::duration<double>(o.checkpoint_interval_seconds);
      };
  }
  // A study job runs the case's ladder; its outcome reads like a single run's.
  const RunOutcome r = claim.has_study() ? run_study_attempt(c, claim, opt, reporter.get())
                                         : run_case(c, MPI_COMM_WORLD, opt);
  if (rank != 0) return;

  // The reporter renews the lease until the Finish is ready: hashing large result files can
  // take longer than a lease, and an expired lease would throw the finished run away.
  reporter->log_progress();
  service::log_line("%s attempt %d: %s%s%s", claim.job_id().c_str(), claim.attempt(),
                    summary(r, ranks).c_str(), r.message.empty() ? "" : ": ", r.message.c_str());
  finish.set_outcome(outcome_for(r.status));
  finish.set_message(r.message.empty() ? summary(r, ranks) : r.message);
  try {
    for (auto& f : build_manifest(r.files, claim.output_dir())) *finish.add_files() = std::move(f);
  } catch (const std::exception& e) {
    finish.clear_files();
    finish.set_outcome(v1::ATTEMPT_FAILED);
    finish.set_message(std::string("cannot read the result files: ") + e.what());
  }
  reporter->stop();
  service::set_log_sink({});
  if (reporter->lost()) return;  // another attempt owns the job now
  for (auto& l : reporter->take_log()) *finish.add_log() = std::move(l);
  if (auto p = reporter->last_progress()) *finish.mutable_progress() = *p;
  if (auto cp = reporter->last_checkpoint()) *finish.mutable_checkpoint() = *cp;
  if (!r.last_checkpoint.empty() && finish.checkpoint().path() != r.last_checkpoint) {
    finish.mutable_checkpoint()->set_path(r.last_checkpoint);
    finish.mutable_checkpoint()->set_step(r.steps);
    finish.mutable_checkpoint()->set_time(r.time);
  }
  for (const auto& [unit, seconds] : r.unit_seconds)
    (*finish.mutable_unit_seconds())[unit] = seconds;
  if (send_finish(*link, finish) && !finish.checkpoint().path().empty())
    reporter->finish_acknowledged(finish.checkpoint().path());
}

}  // namespace

int run_pool(int argc, char** argv) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  service::set_log_name("sph-worker pool");
  const auto options = parse_pool_options(argc, argv, rank);
  if (!options) return kExitError;
  install_signal_handlers();

  bool fatal = false;
  std::unique_ptr<ServerLink> link;
  if (rank == 0) {
    try {
      const std::string token =
          options->token_file.empty() ? "" : service::read_token_file(options->token_file);
      const std::string host = host_name();
      const std::string pool_id =
          options->pool_name.empty() ? host + ":" + std::to_string(getpid()) : options->pool_name;
      link = std::make_unique<ServerLink>(options->server, token, pool_id, host, ranks);
      service::log_line("pool %s with %d ranks serving %s", pool_id.c_str(), ranks,
                        options->server.c_str());
    } catch (const std::exception& e) {
      service::log_line("%s", e.what());
      fatal = true;
    }
  }
  // Every rank needs the pool id (it goes into the result metadata).
  std::string pool_id = link ? link->pool_id() : "";
  std::int64_t id_size = static_cast<std::int64_t>(pool_id.size());
  MPI_Bcast(&id_size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  pool_id.resize(static_cast<size_t>(id_size));
  MPI_Bcast(pool_id.data(), static_cast<int>(id_size), MPI_CHAR, 0, MPI_COMM_WORLD);

  int jobs_done = 0;
  while (true) {
    std::optional<v1::ClaimResponse> claim;
    if (rank == 0 && !fatal && !g_stop.load() &&
        (options->max_jobs == 0 || jobs_done < options->max_jobs))
      claim = next_claim(*link, *options, fatal);
    claim = share_command(claim, MPI_COMM_WORLD);
    if (!claim) break;
    run_attempt(*claim, *options, link.get(), pool_id, rank, ranks);
    ++jobs_done;
  }
  if (rank == 0)
    service::log_line("exiting after %d job(s)%s", jobs_done, g_stop.load() ? " (signal)" : "");
  return fatal ? kExitError : kExitOk;
}

}  // namespace sph::worker::pool
