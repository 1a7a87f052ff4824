#pragma once
// The shared-secret token that clients and pools present as "authorization: Bearer <token>"
// metadata. Insecure channels drop call credentials, so the token travels as plain metadata
// and the server checks it in every handler (see docs/service.md for TLS deployments).
#include <string>

namespace grpc {
class ClientContext;
}

namespace sph::service {

inline constexpr const char* kAuthorizationKey = "authorization";

// The first line of the file, surrounding whitespace removed. Throws std::runtime_error when
// the file cannot be read or holds no token.
std::string read_token_file(const std::string& path);

// Adds the token to a call (nothing when the token is empty).
void add_token(grpc::ClientContext& context, const std::string& token);

}  // namespace sph::service
