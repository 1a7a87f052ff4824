#include "server/api/job_service.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "common/job_state.h"
#include "common/log.h"
#include "common/message_limits.h"
#include "common/shortened_text.h"
#include "common/time_text.h"
#include "server/api/errors.h"
#include "server/api/fetch_result_reactor.h"
#include "server/api/refused_stream.h"
#include "server/api/watch_job_reactor.h"
#include "server/clock.h"
#include "server/results/job_files_removal.h"
#include "server/store/job_ids.h"

namespace sph::server::api {
namespace {

constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
constexpr std::size_t kMaxListPageBytes = 4 << 20;

grpc::Status parse_id(const std::string& text, std::int64_t& id) {
  const auto parsed = store::parse_job_id(text);
  if (!parsed)
    return invalid_argument("job_id", "'" + text + "' is not a job id (expected job-<n>)");
  id = *parsed;
  return grpc::Status::OK;
}

// Jobs stored before names and reasons were bounded may carry megabytes of either; a listing
// shows their beginning (GetJob still shows them whole).
void shorten_for_listing(v1::Job& j) {
  service::shorten_text(*j.mutable_name(), service::kMaxListedTextBytes);
  service::shorten_text(*j.mutable_reason(), service::kMaxListedTextBytes);
}

}  // namespace

grpc::ServerUnaryReactor* JobServiceImpl::Submit(grpc::CallbackServerContext* context,
                                                 const v1::SubmitRequest* request,
                                                 v1::SubmitResponse* response) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  // A submit costs a few hundred microseconds of CPU (parse, validate, estimate, the stored
  // text) and a durable commit: they run on a fixed pool in arrival order instead of on a
  // thread per call, so that a hundred concurrent callers take turns rather than contend for
  // the cores, and the pool's threads share commits (store/group_commit.h).
  submit_work_.post([this, context, request, response, reactor] {
    reactor->Finish(accept_submission(submission_, *context, *request, *response));
  });
  return reactor;
}

grpc::Status JobServiceImpl::GetJob(grpc::ServerContext* context, const v1::GetJobRequest* request,
                                    v1::Job* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  return guarded([&] {
    *response = store_.get(id, request->include_case());
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::GetJobLogs(grpc::ServerContext* context,
                                        const v1::GetJobLogsRequest* request,
                                        v1::GetJobLogsResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  if (request->attempt() < 0) return invalid_argument("attempt", "must be >= 0 (0: every attempt)");
  if (request->after_sequence() < 0) return invalid_argument("after_sequence", "must be >= 0");
  if (request->limit() < 0) return invalid_argument("limit", "must be >= 0");
  constexpr int kMaxLines = 1000;
  const int limit = request->limit() == 0 ? kMaxLines : std::min(request->limit(), kMaxLines);
  return guarded([&] {
    auto page = store_.logs(id, request->attempt(), request->after_sequence(), limit);
    for (auto& l : page.lines) *response->add_lines() = std::move(l);
    response->set_state(page.state);
    response->set_dropped_lines(page.dropped_lines);
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::ListJobs(grpc::ServerContext* context,
                                      const v1::ListJobsRequest* request,
                                      v1::ListJobsResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  if (request->page_size() < 0) return invalid_argument("page_size", "must be >= 0");
  const int page_size =
      request->page_size() == 0 ? kDefaultPageSize : std::min(request->page_size(), kMaxPageSize);
  std::int64_t before = 0;
  if (!request->page_token().empty()) {
    const auto parsed = store::parse_page_token(request->page_token());
    if (!parsed) return invalid_argument("page_token", "is not a token from ListJobs");
    before = *parsed;
  }
  std::vector<v1::JobState> states;
  for (int i = 0; i < request->states_size(); ++i) {
    const auto s = request->states(i);
    if (s == v1::JOB_STATE_UNSPECIFIED || !v1::JobState_IsValid(s))
      return invalid_argument("states[" + std::to_string(i) + "]", "is not a job state");
    states.push_back(s);
  }
  return guarded([&] {
    auto page = store_.list(states, page_size, before);
    // A page is bounded in bytes as well as in jobs, so that no stored job can make listing
    // fail for everyone: the page ends early and the token continues below its last job.
    std::size_t bytes = 0;
    for (auto& j : page.jobs) {
      shorten_for_listing(j);
      const std::size_t size = j.ByteSizeLong();
      if (response->jobs_size() > 0 && bytes + size > kMaxListPageBytes) {
        page.next_before =
            store::parse_job_id(response->jobs(response->jobs_size() - 1).id()).value_or(0);
        break;
      }
      bytes += size;
      *response->add_jobs() = std::move(j);
    }
    if (page.next_before > 0) response->set_next_page_token(std::to_string(page.next_before));
    return grpc::Status::OK;
  });
}

grpc::ServerWriteReactor<v1::JobEvent>* JobServiceImpl::WatchJob(
    grpc::CallbackServerContext* context, const v1::WatchJobRequest* request) {
  using Refused = RefusedStream<v1::JobEvent>;
  if (auto s = auth_.check(*context); !s.ok()) return new Refused(s);
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return new Refused(s);
  if (request->after_sequence() < 0)
    return new Refused(invalid_argument("after_sequence", "must be >= 0"));
  StreamLimiter::Slot slot;
  if (auto s = streams_.acquire("WatchJob", stream_client(*context), slot); !s.ok())
    return new Refused(s);
  return new WatchJobReactor(store_, feed_, stream_work_, std::move(slot), id,
                             request->after_sequence());
}

grpc::Status JobServiceImpl::CancelJob(grpc::ServerContext* context,
                                       const v1::CancelJobRequest* request, v1::Job* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  if (request->reason().size() > service::kMaxCancelReasonBytes)
    return invalid_argument("reason", "is " + std::to_string(request->reason().size()) +
                                          " bytes; the limit is " +
                                          std::to_string(service::kMaxCancelReasonBytes));
  return guarded([&] {
    *response = store_.cancel(id, request->reason(), now_unix_ms());
    service::log_line("%s: cancel requested, now %s", response->id().c_str(),
                      service::state_name(response->state()));
    return grpc::Status::OK;
  });
}

grpc::ServerWriteReactor<v1::FileChunk>* JobServiceImpl::FetchResult(
    grpc::CallbackServerContext* context, const v1::FetchResultRequest* request) {
  using Refused = RefusedStream<v1::FileChunk>;
  if (auto s = auth_.check(*context); !s.ok()) return new Refused(s);
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return new Refused(s);
  if (request->offset() < 0) return new Refused(invalid_argument("offset", "must be >= 0"));
  if (request->offset() > 0 && request->file().empty())
    return new Refused(invalid_argument("offset", "needs a single file"));
  StreamLimiter::Slot slot;
  if (auto s = streams_.acquire("FetchResult", stream_client(*context), slot); !s.ok())
    return new Refused(s);
  return new FetchResultReactor(store_, feed_, layout_, std::move(slot), id, request->file(),
                                request->offset());
}

grpc::Status JobServiceImpl::DeleteJobFiles(grpc::ServerContext* context,
                                            const v1::DeleteJobFilesRequest* request,
                                            v1::DeleteJobFilesResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  return guarded([&] {
    std::lock_guard lock(delete_mu_);
    // A finished job never runs again, so nothing of ours writes into its directory while it
    // is removed. The deletion is recorded before the files go, so that a fetch starting
    // after this point is refused as "deleted" rather than finding files missing; a removal
    // that fails half way (permissions) is reported, and calling again finishes it. Every
    // call removes the directory, also after the first: a pool cut off from the server may
    // still write there until it learns that its attempt ended.
    const v1::Job job = store_.get_finished(id);
    const JobFiles files = measure_job_files(layout_, job.id());
    auto [updated, now] = store_.record_files_deleted(id, files.bytes, now_unix_ms());
    try {
      remove_job_files(layout_, job.id());
    } catch (const std::filesystem::filesystem_error& e) {
      service::log_line("%s: deleting its files failed: %s", job.id().c_str(), e.what());
      return grpc::Status(grpc::StatusCode::INTERNAL,
                          "deleting " + layout_.job_dir(job.id()).string() +
                              " failed (what was removed stays removed; call again to "
                              "retry): " +
                              e.what());
    }
    if (now || files.files > 0)
      service::log_line("%s: deleted %lld files (%lld bytes) in %s", job.id().c_str(),
                        static_cast<long long>(files.files), static_cast<long long>(files.bytes),
                        layout_.job_dir(job.id()).string().c_str());
    *response->mutable_job() = std::move(updated);
    response->set_deleted_now(now);
    return grpc::Status::OK;
  });
}

}  // namespace sph::server::api
