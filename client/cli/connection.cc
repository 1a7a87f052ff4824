#include "cli/connection.h"

#include <chrono>
#include <cstdio>

#include "cli/exit_codes.h"
#include "common/auth_token.h"
#include "common/channel.h"

namespace sph::ctl {

std::optional<Connection> Connection::open(const GlobalOptions& options) {
  Connection c;
  c.address_ = options.server;
  c.timeout_ = options.timeout_seconds;
  if (!options.token_file.empty()) {
    try {
      c.token_ = service::read_token_file(options.token_file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sphctl: %s\n", e.what());
      return std::nullopt;
    }
  }
  auto channel = service::make_channel(c.address_);
  c.jobs_ = v1::JobService::NewStub(channel);
  c.health_ = grpc::health::v1::Health::NewStub(channel);
  return c;
}

std::unique_ptr<grpc::ClientContext> Connection::context(double timeout_seconds) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  service::add_token(*ctx, token_);
  if (timeout_seconds > 0)
    ctx->set_deadline(std::chrono::system_clock::now() +
                      std::chrono::milliseconds(static_cast<std::int64_t>(timeout_seconds * 1000)));
  return ctx;
}

int exit_code_for(const grpc::Status& status) {
  switch (status.error_code()) {
    case grpc::StatusCode::OK:
      return kOk;
    case grpc::StatusCode::INVALID_ARGUMENT:
      return kInvalidCase;
    case grpc::StatusCode::NOT_FOUND:
      return kNotFound;
    case grpc::StatusCode::UNAVAILABLE:
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return kUnavailable;
    case grpc::StatusCode::UNAUTHENTICATED:
    case grpc::StatusCode::PERMISSION_DENIED:
      return kAuth;
    case grpc::StatusCode::ALREADY_EXISTS:
    case grpc::StatusCode::FAILED_PRECONDITION:
      return kConflict;
    case grpc::StatusCode::DATA_LOSS:
      return kVerifyFailed;
    default:
      return kFailure;
  }
}

int report_error(const grpc::Status& status, const std::string& what, const std::string& server) {
  std::string hint;
  if (status.error_code() == grpc::StatusCode::UNAVAILABLE)
    hint = " (is sph-server running at " + server + "? see --server / SPHCTL_SERVER)";
  if (status.error_code() == grpc::StatusCode::UNAUTHENTICATED)
    hint = " (see --token-file / SPHCTL_TOKEN_FILE)";
  std::fprintf(stderr, "sphctl: %s: %s%s\n", what.c_str(), status.error_message().c_str(),
               hint.c_str());
  return exit_code_for(status);
}

bool is_transient(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::UNAVAILABLE;
}

int exit_code_for_state(v1::JobState state) {
  switch (state) {
    case v1::JOB_STATE_SUCCEEDED:
      return kOk;
    case v1::JOB_STATE_CANCELLED:
      return kJobCancelled;
    default:
      return kJobFailed;
  }
}

}  // namespace sph::ctl
