#pragma once
// Times every gRPC call sph-server answers (from the interceptor's creation, when the call
// starts, to the status it sends) and notes the pools that call Claim, into Metrics.
#include <grpcpp/support/server_interceptor.h>

#include "server/metrics/metrics.h"

namespace sph::server::metrics {

class RpcMetricsInterceptorFactory final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  explicit RpcMetricsInterceptorFactory(Metrics& metrics) : metrics_(metrics) {}
  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;

 private:
  Metrics& metrics_;
};

}  // namespace sph::server::metrics
