#include "server/api/worker_service.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/job_state.h"
#include "common/log.h"
#include "common/message_limits.h"
#include "common/shortened_text.h"
#include "server/api/errors.h"
#include "server/clock.h"
#include "server/store/job_ids.h"

namespace sph::server::api {
namespace {
constexpr int kMaxLogLinesPerCall = 1000;  // service.proto ReportRequest.log
}  // namespace
namespace {

// A long poll is capped so that a pool notices a lost server within a reasonable time.
constexpr double kMaxClaimWaitSeconds = 20;
constexpr std::chrono::milliseconds kClaimPoll{500};
// A result is a handful of files (result.h5, result.xmf, a study's levels); the manifest comes
// back in every listing of the job.
constexpr int kMaxResultFiles = 1000;

bool is_sha256_hex(const std::string& s) {
  return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char ch) {
           return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f');
         });
}

}  // namespace

grpc::Status WorkerServiceImpl::check_checkpoint(const std::string& job_id,
                                                 const v1::Checkpoint& cp,
                                                 const std::string& field) const {
  if (!layout_.inside_job(job_id, cp.path()))
    return invalid_argument(
        field + ".path", "'" + cp.path() + "' is not inside " + layout_.job_dir(job_id).string());
  return grpc::Status::OK;
}

grpc::Status WorkerServiceImpl::Claim(grpc::ServerContext* context, const v1::ClaimRequest* request,
                                      v1::ClaimResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  if (request->pool_id().empty()) return invalid_argument("pool_id", "is required");
  if (request->ranks() < 1) return invalid_argument("ranks", "must be >= 1");
  // Found by the RPC fuzzer: NaN passed the clamp below and became an undefined conversion.
  if (!std::isfinite(request->wait_seconds()))
    return invalid_argument("wait_seconds", "must be a finite number of seconds");
  const double wait = std::clamp(request->wait_seconds(), 0.0, kMaxClaimWaitSeconds);
  const auto deadline =
      EventFeed::Clock::now() +
      std::chrono::duration_cast<EventFeed::Clock::duration>(std::chrono::duration<double>(wait));
  return guarded([&] {
    const store::ClaimInfo who{request->pool_id(), request->hostname(), request->ranks()};
    while (true) {
      // Read the generation before looking, so a submit in between still wakes us.
      const auto generation = feed_.queue_generation();
      // A pool that gave up waiting (deadline, cancel, server shutdown) would never learn of
      // a claim committed for it now: the job would wait out a whole lease and count it lost.
      if (context->IsCancelled() || feed_.shutting_down()) return grpc::Status::OK;
      if (auto grant = store_.claim(who, now_unix_ms())) {
        *response = std::move(*grant);
        const double lease = response->lease_seconds();
        response->set_report_interval_seconds(std::min(2.0, lease / 4));
        std::error_code ec;
        std::filesystem::create_directories(response->output_dir(), ec);
        if (ec)
          service::log_line("cannot create %s: %s (the pool will try)",
                            response->output_dir().c_str(), ec.message().c_str());
        service::log_line("%s attempt %d claimed by %s (%d ranks)%s%s", response->job_id().c_str(),
                          response->attempt(), request->pool_id().c_str(), request->ranks(),
                          response->resume_from().empty() ? "" : ", resuming from ",
                          response->resume_from().c_str());
        return grpc::Status::OK;
      }
      if (EventFeed::Clock::now() >= deadline || feed_.shutting_down() || context->IsCancelled())
        return grpc::Status::OK;  // no job: an empty reply
      feed_.wait_for_queue(generation, std::min(deadline, EventFeed::Clock::now() + kClaimPoll));
    }
  });
}

grpc::Status WorkerServiceImpl::Report(grpc::ServerContext* context,
                                       const v1::ReportRequest* request,
                                       v1::ReportResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  const auto id = store::parse_job_id(request->job_id());
  if (!id)
    return invalid_argument("job_id", "'" + request->job_id() + "' is not a job id (job-<n>)");
  if (request->log_size() > kMaxLogLinesPerCall)
    return invalid_argument("log", "at most " + std::to_string(kMaxLogLinesPerCall) +
                                       " lines per call, not " +
                                       std::to_string(request->log_size()));
  return guarded([&] {
    // The job is resolved in the database before any path is built from its id.
    const std::string job_id = store_.get(*id, false).id();
    for (int i = 0; i < request->checkpoints_size(); ++i)
      if (auto s = check_checkpoint(job_id, request->checkpoints(i),
                                    "checkpoints[" + std::to_string(i) + "]");
          !s.ok())
        return s;
    *response = store_.report(*request, now_unix_ms());
    return grpc::Status::OK;
  });
}

grpc::Status WorkerServiceImpl::Finish(grpc::ServerContext* context,
                                       const v1::FinishRequest* request,
                                       v1::FinishResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  const auto id = store::parse_job_id(request->job_id());
  if (!id)
    return invalid_argument("job_id", "'" + request->job_id() + "' is not a job id (job-<n>)");
  if (request->log_size() > kMaxLogLinesPerCall)
    return invalid_argument("log", "at most " + std::to_string(kMaxLogLinesPerCall) +
                                       " lines per call, not " +
                                       std::to_string(request->log_size()));
  switch (request->outcome()) {
    case v1::ATTEMPT_COMPLETED:
    case v1::ATTEMPT_FAILED:
    case v1::ATTEMPT_CANCELLED:
    case v1::ATTEMPT_INTERRUPTED:
      break;
    default:
      return invalid_argument("outcome", "must be COMPLETED, FAILED, CANCELLED or INTERRUPTED");
  }
  if (request->files_size() > kMaxResultFiles)
    return invalid_argument("files", std::to_string(request->files_size()) +
                                         " files; the limit is " + std::to_string(kMaxResultFiles));
  return guarded([&] {
    // The job and the attempt are resolved in the database before any path is built: a file
    // check of an attempt that is not this job's would answer about folders it does not own.
    const v1::Job job = store_.get(*id, false);
    if (request->attempt() < 1 || request->attempt() > job.attempt())
      return grpc::Status(
          grpc::StatusCode::ABORTED,
          "attempt " + std::to_string(request->attempt()) + " of " + job.id() + " does not exist");
    if (request->has_checkpoint() && !request->checkpoint().path().empty())
      if (auto s = check_checkpoint(job.id(), request->checkpoint(), "checkpoint"); !s.ok())
        return s;
    // The manifest is what FetchResult will serve: every entry must be a file of this
    // attempt, with the size the pool says it has.
    for (int i = 0; i < request->files_size(); ++i) {
      const auto& f = request->files(i);
      const std::string field = "files[" + std::to_string(i) + "]";
      if (auto problem = layout_.check_result_name(job.id(), request->attempt(), f.name()))
        return invalid_argument(field + ".name", "'" + f.name() + "' " + *problem);
      std::error_code ec;
      const auto size = std::filesystem::file_size(
          layout_.attempt_dir(job.id(), request->attempt()) / f.name(), ec);
      if (ec)
        return invalid_argument(field + ".name", "'" + f.name() + "' cannot be read in attempt " +
                                                     std::to_string(request->attempt()) +
                                                     "'s folder");
      if (static_cast<std::int64_t>(size) != f.size())
        return invalid_argument(field + ".size", std::to_string(f.size()) +
                                                     " does not match the file on disk (" +
                                                     std::to_string(size) + " bytes)");
      if (!is_sha256_hex(f.sha256()))
        return invalid_argument(field + ".sha256", "must be 64 lowercase hex digits");
    }
    // A pool's diagnosis becomes the job's reason, shown in every listing: a long one is cut
    // rather than refused, so that the attempt still ends.
    const v1::FinishRequest* finish = request;
    v1::FinishRequest shortened;
    if (request->message().size() > service::kMaxFinishMessageBytes) {
      shortened = *request;
      service::shorten_text(*shortened.mutable_message(), service::kMaxFinishMessageBytes);
      finish = &shortened;
    }
    const v1::JobState state = store_.finish(*finish, now_unix_ms());
    response->set_state(state);
    service::log_line("%s attempt %d finished %s -> %s%s%s", job.id().c_str(), request->attempt(),
                      service::outcome_name(request->outcome()), service::state_name(state),
                      finish->message().empty() ? "" : ": ", finish->message().c_str());
    return grpc::Status::OK;
  });
}

}  // namespace sph::server::api
