#include "worker/pool/server_link.h"

#include <chrono>

#include "common/auth_token.h"
#include "common/channel.h"

namespace sph::worker::pool {
namespace {

constexpr double kReportTimeout = 5;
constexpr double kFinishTimeout = 10;
// Beyond the long poll itself.
constexpr double kClaimSlack = 10;

}  // namespace

ServerLink::ServerLink(const std::string& address, std::string token, std::string pool_id,
                       std::string hostname, int ranks)
    : address_(address),
      token_(std::move(token)),
      pool_id_(std::move(pool_id)),
      hostname_(std::move(hostname)),
      ranks_(ranks),
      stub_(v1::WorkerService::NewStub(service::make_channel(address))) {}

std::unique_ptr<grpc::ClientContext> ServerLink::context(double timeout_seconds,
                                                         bool wait_for_ready) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  service::add_token(*ctx, token_);
  // A fail-fast call made while the channel sits in its reconnect backoff fails at once even
  // when the server is already back; a restarted server only extends running leases by one
  // lease length, so reports and finishes wait (up to their deadline) for the connection.
  ctx->set_wait_for_ready(wait_for_ready);
  ctx->set_deadline(std::chrono::system_clock::now() +
                    std::chrono::milliseconds(static_cast<long long>(timeout_seconds * 1000)));
  return ctx;
}

grpc::Status ServerLink::claim(double wait_seconds, v1::ClaimResponse* out) {
  v1::ClaimRequest req;
  req.set_pool_id(pool_id_);
  req.set_ranks(ranks_);
  req.set_hostname(hostname_);
  req.set_wait_seconds(wait_seconds);
  // Fail fast: the claim loop must stay responsive to SIGTERM while the server is away.
  return stub_->Claim(context(wait_seconds + kClaimSlack, false).get(), req, out);
}

grpc::Status ServerLink::report(const v1::ReportRequest& request, v1::ReportResponse* out) {
  return stub_->Report(context(kReportTimeout, true).get(), request, out);
}

grpc::Status ServerLink::finish(const v1::FinishRequest& request, v1::FinishResponse* out) {
  return stub_->Finish(context(kFinishTimeout, true).get(), request, out);
}

bool attempt_lost(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::ABORTED ||
         status.error_code() == grpc::StatusCode::NOT_FOUND ||
         status.error_code() == grpc::StatusCode::FAILED_PRECONDITION;
}

}  // namespace sph::worker::pool
