#pragma once
// Rank 0's connection to sph-server's WorkerService: claim, report, finish, each with a
// deadline so that a vanished server never blocks the pool.
#include <memory>
#include <string>

#include "sph/v1/service.grpc.pb.h"

namespace sph::worker::pool {

class ServerLink {
 public:
  ServerLink(const std::string& address, std::string token, std::string pool_id,
             std::string hostname, int ranks);

  // Long-polls up to wait_seconds; an OK reply with an empty job_id means no work.
  grpc::Status claim(double wait_seconds, v1::ClaimResponse* out);
  grpc::Status report(const v1::ReportRequest& request, v1::ReportResponse* out);
  grpc::Status finish(const v1::FinishRequest& request, v1::FinishResponse* out);

  const std::string& pool_id() const { return pool_id_; }
  const std::string& address() const { return address_; }

 private:
  std::unique_ptr<grpc::ClientContext> context(double timeout_seconds, bool wait_for_ready) const;
  std::string address_;
  std::string token_;
  std::string pool_id_;
  std::string hostname_;
  int ranks_;
  std::unique_ptr<v1::WorkerService::Stub> stub_;
};

// A call whose failure means the attempt is no longer ours (lease lost, job reassigned).
bool attempt_lost(const grpc::Status& status);

}  // namespace sph::worker::pool
