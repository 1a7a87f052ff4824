#pragma once
// JobService: what clients call (submit, inspect, follow, cancel, fetch, delete files).
#include <mutex>

#include "server/api/auth.h"
#include "server/api/stream_limiter.h"
#include "server/api/work_queue.h"
#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/job_store.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::server::api {

// What one submit and all unfinished jobs together may ask for (server/config.h).
struct JobServiceLimits {
  double max_particles = 0;         // per case, 0 = no limit
  double max_memory_bytes = 0;      // per case (estimate_case().bytes), 0 = no limit
  double max_queued_jobs = 0;       // queued + running jobs, 0 = no limit
  double max_queued_particles = 0;  // their estimated particles, 0 = no limit
  int max_streams_per_client = 256;
};

// WatchJob and FetchResult are callback (reactor) methods, so that an open stream costs
// memory and no thread; the other methods are synchronous.
using JobServiceBase = v1::JobService::WithCallbackMethod_WatchJob<
    v1::JobService::WithCallbackMethod_FetchResult<v1::JobService::Service>>;

class JobServiceImpl final : public JobServiceBase {
 public:
  JobServiceImpl(store::JobStore& store, EventFeed& feed, const ResultLayout& layout,
                 const TokenCheck& auth, JobServiceLimits limits)
      : store_(store), feed_(feed), layout_(layout), auth_(auth), limits_(limits) {}

  grpc::Status Submit(grpc::ServerContext* context, const v1::SubmitRequest* request,
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
};

}  // namespace sph::server::api
