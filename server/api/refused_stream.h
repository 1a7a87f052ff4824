#pragma once
// A server stream that ends at once with a status, before anything is sent: how a callback
// handler refuses a call (bad arguments, no token, too many streams).
#include <grpcpp/support/server_callback.h>
#include <grpcpp/support/status.h>

namespace sph::server::api {

template <typename Message>
class RefusedStream final : public grpc::ServerWriteReactor<Message> {
 public:
  explicit RefusedStream(grpc::Status status) { this->Finish(std::move(status)); }
  void OnDone() override { delete this; }
};

}  // namespace sph::server::api
