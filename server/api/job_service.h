#pragma once
// JobService: what clients call (submit, inspect, follow, cancel, fetch, delete files).
#include <mutex>

#include "server/api/auth.h"
#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/job_store.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::server::api {

struct JobServiceLimits {
  double max_particles = 0;  // per case, 0 = no limit
};

class JobServiceImpl final : public v1::JobService::Service {
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
  grpc::Status WatchJob(grpc::ServerContext* context, const v1::WatchJobRequest* request,
                        grpc::ServerWriter<v1::JobEvent>* writer) override;
  grpc::Status CancelJob(grpc::ServerContext* context, const v1::CancelJobRequest* request,
                         v1::Job* response) override;
  grpc::Status FetchResult(grpc::ServerContext* context, const v1::FetchResultRequest* request,
                           grpc::ServerWriter<v1::FileChunk>* writer) override;
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
};

}  // namespace sph::server::api
