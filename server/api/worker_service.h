#pragma once
// WorkerService: what worker pools call. Every call after Claim names (job, attempt); a call
// for an attempt that is no longer current is refused with ABORTED (fencing), so a pool that
// lost its lease cannot overwrite the work of the attempt that replaced it.
#include "server/api/auth.h"
#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/job_store.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::server::api {

class WorkerServiceImpl final : public v1::WorkerService::Service {
 public:
  WorkerServiceImpl(store::JobStore& store, EventFeed& feed, const ResultLayout& layout,
                    const TokenCheck& auth)
      : store_(store), feed_(feed), layout_(layout), auth_(auth) {}

  grpc::Status Claim(grpc::ServerContext* context, const v1::ClaimRequest* request,
                     v1::ClaimResponse* response) override;
  grpc::Status Report(grpc::ServerContext* context, const v1::ReportRequest* request,
                      v1::ReportResponse* response) override;
  grpc::Status Finish(grpc::ServerContext* context, const v1::FinishRequest* request,
                      v1::FinishResponse* response) override;

 private:
  grpc::Status check_checkpoint(const std::string& job_id, const v1::Checkpoint& cp,
                                const std::string& field) const;

  store::JobStore& store_;
  EventFeed& feed_;
  const ResultLayout& layout_;
  const TokenCheck& auth_;
};

}  // namespace sph::server::api
