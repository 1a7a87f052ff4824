#pragma once
// Request bytes that do not parse as the method's request message (malformed protobuf, or
// nested past protobuf's recursion limit) are answered INVALID_ARGUMENT with a message naming
// the message type. gRPC itself answers them INTERNAL with no message, which tells a client
// neither that the fault is its own nor what to fix; no handler of ours runs for them.
#include <grpcpp/support/server_interceptor.h>

namespace sph::server::api {

class MalformedRequestInterceptorFactory final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;
};

}  // namespace sph::server::api
