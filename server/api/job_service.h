#pragma once
// JobService: what clients call (submit, inspect, follow, cancel, fetch, delete files).
#include <mutex>

#include "server/api/auth.h"
#include "server/api/job_service_limits.h"
#include "server/api/stream_limiter.h"
#include "server/api/submission.h"
#include "server/api/work_queue.h"
#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/job_store.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::server::api {

// WatchJob and FetchResult are callback (reactor) methods, so that an open stream costs
// memory and no thread, and so is Submit, whose work runs on a fixed pool; the other methods
// are synchronous.
using JobServiceBase =
    v1::JobService::WithCallbackMethod_Submit<v1::JobService::WithCallbackMethod_WatchJob<
        v1::JobService::WithCallbackMethod_FetchResult<v1::JobService::Service>>>;

class JobServiceImpl final : public JobServiceBase {
 public:
  static constexpr int kSubmitThreads = 8;

  JobServiceImpl(store::JobStore& store, EventFeed& feed, const ResultLayout& layout,
                 const TokenCheck& auth, JobServiceLimits limits)
      : store_(store), feed_(feed), layout_(layout), auth_(auth), limits_(limits) {}

  using JobServiceBase::Submit;  // the synchronous form, which the mixin disables
  grpc::ServerUnaryReactor* Submit(grpc::CallbackServerContext* context,
                                   const v1::SubmitRequest* request,
                                   v1::SubmitResponse* response) override;
  grpc::Status GetJob(grpc::ServerContext* context, const v1::GetJobRequest* request,
                      v1::Job* response) override;
  grpc::Status ListJobs(grpc::ServerContext* context, const v1::ListJobsRequest* request,
                        v1::ListJobsResponse* response) override;
  using JobServiceBase::FetchResult;  // the synchronous forms, which the mixins disable
  using JobServiceBase::WatchJob;
  grpc::ServerWriteReactor<v1::JobEvent>* WatchJob(grpc::CallbackServerContext* context,
                                                   const v1::WatchJobRequest* request) override;
  grpc::Status CancelJob(grpc::ServerContext* context, const v1::CancelJobRequest* request,
                         v1::Job* response) override;
  grpc::ServerWriteReactor<v1::FileChunk>* FetchResult(
      grpc::CallbackServerContext* context, const v1::FetchResultRequest* request) override;
  grpc::Status DeleteJobFiles(grpc::ServerContext* context,
                              const v1::DeleteJobFilesRequest* request,
                              v1::DeleteJobFilesResponse* response) override;
  grpc::Status GetJobLogs(grpc::ServerContext* context, const v1::GetJobLogsRequest* request,
                          v1::GetJobLogsResponse* response) override;

 private:
  store::JobStore& store_;
  EventFeed& feed_;
  const ResultLayout& layout_;
  const TokenCheck& auth_;
  JobServiceLimits limits_;
  // One removal at a time: two racing calls would each count what the other removed.
  std::mutex delete_mu_;
  // Open WatchJob and FetchResult streams per client, and the threads that read the store
  // for watches the event feed wakes.
  StreamLimiter streams_{limits_.max_streams_per_client};
  WorkQueue stream_work_{2};
  // Submits in arrival order; more threads than cores so that commits group (a thread waits
  // for its batch's fsync while the others validate the next requests). Declared last: it is
  // destroyed (joined) first, while what its tasks use still exists.
  Submission submission_{store_, auth_, limits_};
  WorkQueue submit_work_{kSubmitThreads};
};

}  // namespace sph::server::api
