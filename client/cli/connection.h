#pragma once
// A connection to sph-server: stubs, the token, per-call deadlines, and how gRPC errors turn
// into messages and exit codes.
#include <grpcpp/client_context.h>
#include <grpcpp/support/status.h>

#include <memory>
#include <optional>
#include <string>

#include "cli/options.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::ctl {

class Connection {
 public:
  // Reads the token file; on failure prints why and returns nullopt.
  static std::optional<Connection> open(const GlobalOptions& options);

  // A context with the token and a deadline of timeout_seconds (0: none, for streams).
  std::unique_ptr<grpc::ClientContext> context(double timeout_seconds) const;
  std::unique_ptr<grpc::ClientContext> unary_context() const { return context(timeout_); }

  v1::JobService::Stub& jobs() { return *jobs_; }
  grpc::health::v1::Health::Stub& health() { return *health_; }
  const std::string& address() const { return address_; }

 private:
  Connection() = default;
  std::string address_;
  std::string token_;
  double timeout_ = 30;
  std::shared_ptr<v1::JobService::Stub> jobs_;
  std::shared_ptr<grpc::health::v1::Health::Stub> health_;
};

// The exit code for a failed call (see exit_codes.h).
int exit_code_for(const grpc::Status& status);

// Prints "sphctl: <what>: <message>" (with a hint for unreachable servers) and returns the
// exit code.
int report_error(const grpc::Status& status, const std::string& what, const std::string& server);

// True for errors worth retrying after a pause (server restarting, network blip).
bool is_transient(const grpc::Status& status);

// The exit code for a job that ended in `state` (0 for SUCCEEDED).
int exit_code_for_state(v1::JobState state);

}  // namespace sph::ctl
