#include "server/api/auth.h"

#include <openssl/crypto.h>

#include "common/auth_token.h"

namespace sph::server::api {

grpc::Status TokenCheck::check(const grpc::ServerContextBase& context) const {
  if (token_.empty()) return grpc::Status::OK;
  const auto& md = context.client_metadata();
  const auto it = md.find(service::kAuthorizationKey);
  if (it == md.end())
    return {grpc::StatusCode::UNAUTHENTICATED,
            "missing 'authorization: Bearer <token>' metadata (sphctl --token-file)"};
  const std::string expected = "Bearer " + token_;
  const grpc::string_ref got = it->second;
  // Constant time, so the comparison does not leak how much of the token matched.
  if (got.size() != expected.size() ||
      CRYPTO_memcmp(got.data(), expected.data(), expected.size()) != 0)
    return {grpc::StatusCode::UNAUTHENTICATED, "wrong token"};
  return grpc::Status::OK;
}

}  // namespace sph::server::api
