#include "server/service_host.h"

#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "common/auth_token.h"
#include "common/message_limits.h"
#include "server/api/malformed_request_interceptor.h"
#include "server/clock.h"
#include "server/metrics/rpc_metrics_interceptor.h"
#include "server/results/results_owner.h"

namespace sph::server {
namespace {

std::int64_t lease_ms(const ServerConfig& config) {
  return static_cast<std::int64_t>(config.lease_seconds * 1000);
}

ResultLayout make_results_dir(const std::string& dir) {
  std::filesystem::create_directories(dir);
  return ResultLayout(dir);
}

std::string read_token(const ServerConfig& config) {
  return config.token_file.empty() ? std::string() : service::read_token_file(config.token_file);
}

api::JobServiceLimits job_limits(const ServerConfig& config) {
  return {config.max_particles, config.max_memory_gib * 1073741824.0, config.max_queued_jobs,
          config.max_queued_particles, config.max_streams_per_client};
}

}  // namespace

ServiceHost::ServiceHost(const ServerConfig& config)
    : auth_(read_token(config)),
      layout_(make_results_dir(config.results_dir)),
      db_lock_(config.db_path),
      store_(config.db_path, layout_, store::StoreOptions{lease_ms(config), config.max_lost_leases},
             feed_),
      jobs_(store_, feed_, layout_, auth_, job_limits(config)),
      workers_(store_, feed_, layout_, auth_) {
  claim_results_directory(layout_, store_.database_id(), store_.has_jobs());
  // Pools could not report while the server was down; they get a full lease to reconnect.
  store_.renew_all_leases(now_unix_ms());

  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(config.address, grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&jobs_);
  builder.RegisterService(&workers_);
  builder.SetMaxReceiveMessageSize(service::kMaxMessageBytes);  // inlined point sets
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<api::MalformedRequestInterceptorFactory>());
  interceptors.push_back(std::make_unique<metrics::RpcMetricsInterceptorFactory>(metrics_));
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  server_ = builder.BuildAndStart();
  if (!server_ || port == 0) throw std::runtime_error("cannot listen on " + config.address);
  // Health answers for the server as a whole ("") and for each service by its full name.
  for (const char* name : {"sph.v1.JobService", "sph.v1.WorkerService"})
    server_->GetHealthCheckService()->SetServingStatus(name, true);
  bound_ = config.address.substr(0, config.address.rfind(':') + 1) + std::to_string(port);
  if (!config.metrics_address.empty())
    endpoint_ = std::make_unique<metrics::MetricsEndpoint>(
        config.metrics_address, [this] { return metrics_.render(store_.counts(), now_unix_ms()); });
  reaper_.emplace(
      store_, std::chrono::milliseconds(std::clamp<std::int64_t>(lease_ms(config) / 4, 50, 1000)));
}

ServiceHost::~ServiceHost() {
  // Without a deadline gRPC's shutdown waits for every open stream to end by itself.
  if (!shut_down_) shutdown(std::chrono::milliseconds(0));
  server_->Wait();
  if (reaper_) reaper_->stop();
}

void ServiceHost::shutdown(std::chrono::milliseconds grace) {
  shut_down_ = true;
  server_->GetHealthCheckService()->SetServingStatus(false);
  // Open streams and long polls see this and end at once; then no call outlives the grace.
  feed_.shutdown();
  if (endpoint_) endpoint_->stop();
  server_->Shutdown(std::chrono::system_clock::now() + grace);
}

void ServiceHost::wait() {
  server_->Wait();
}

}  // namespace sph::server
