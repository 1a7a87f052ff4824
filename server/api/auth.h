#pragma once
// Token authentication, checked at the top of every handler. gRPC drops call credentials on
// insecure channels and does not run AuthMetadataProcessor there, so the token is read from
// the "authorization" metadata directly.
#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include <string>

namespace sph::server::api {

class TokenCheck {
 public:
  // An empty token accepts every call (no --token-file given).
  explicit TokenCheck(std::string token) : token_(std::move(token)) {}
  grpc::Status check(const grpc::ServerContextBase& context) const;
  bool enabled() const { return !token_.empty(); }

 private:
  std::string token_;
};

}  // namespace sph::server::api
