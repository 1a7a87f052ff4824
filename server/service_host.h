#pragma once
// Everything sph-server serves, assembled from its configuration: the database and its lock,
// the results directory, the event feed, both gRPC services with their interceptors and the
// health service, and the lease reaper. main() adds only signals and the address file; the
// RPC fuzzer (tests/fuzz/) hosts the same assembly in its own process.
#include <grpcpp/server.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "server/api/auth.h"
#include "server/api/job_service.h"
#include "server/api/worker_service.h"
#include "server/config.h"
#include "server/events/event_feed.h"
#include "server/lease_reaper.h"
#include "server/metrics/metrics.h"
#include "server/metrics/metrics_endpoint.h"
#include "server/results/result_layout.h"
#include "server/store/database_lock.h"
#include "server/store/job_store.h"

namespace sph::server {

class ServiceHost {
 public:
  // Opens (or creates) the database and results directory and starts listening; throws
  // std::runtime_error when it cannot listen, and what the store and lock throw.
  explicit ServiceHost(const ServerConfig& config);
  ~ServiceHost();
  ServiceHost(const ServiceHost&) = delete;
  ServiceHost& operator=(const ServiceHost&) = delete;

  // HOST:PORT actually bound (the port filled in when the configuration asked for 0).
  const std::string& bound_address() const { return bound_; }
  grpc::Server& server() { return *server_; }
  const ResultLayout& layout() const { return layout_; }
  // The metrics endpoint's HOST:PORT; empty without --metrics-address.
  std::string metrics_address() const { return endpoint_ ? endpoint_->bound_address() : ""; }
  bool token_required() const { return auth_.enabled(); }

  // Health goes NOT_SERVING, open streams and long polls end at once, and calls still running
  // after `grace` are cut.
  void shutdown(std::chrono::milliseconds grace);
  // Until shutdown() has finished.
  void wait();

 private:
  api::TokenCheck
      auth_;  // first: an unreadable token file stops the server before it opens anything
  ResultLayout layout_;
  store::DatabaseLock db_lock_;
  EventFeed feed_;
  store::JobStore store_;
  api::JobServiceImpl jobs_;
  api::WorkerServiceImpl workers_;
  metrics::Metrics metrics_;
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<metrics::MetricsEndpoint> endpoint_;
  std::string bound_;
  std::optional<LeaseReaper> reaper_;
  std::atomic<bool> shut_down_{false};
};

}  // namespace sph::server
