#pragma once
// Client channels to sph-server for sphctl and worker pools.
#include <grpcpp/channel.h>

#include <memory>
#include <string>

namespace sph::service {

// An insecure channel that reconnects quickly after a server restart (gRPC's default
// reconnect backoff grows to two minutes, which would leave a pool idle long after the
// server is back).
std::shared_ptr<grpc::Channel> make_channel(const std::string& address);

}  // namespace sph::service
