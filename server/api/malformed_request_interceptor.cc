#include "server/api/malformed_request_interceptor.h"

#include <google/protobuf/descriptor.h>

#include <string>

namespace sph::server::api {
namespace {

using grpc::experimental::InterceptionHookPoints;

// "/sph.v1.JobService/Submit" -> "sph.v1.SubmitRequest", from the compiled-in descriptors.
std::string request_type_of(const char* method) {
  std::string name = method != nullptr ? method : "";
  if (!name.empty() && name.front() == '/') name.erase(0, 1);
  const auto slash = name.find('/');
  if (slash != std::string::npos) name[slash] = '.';
  const auto* m = google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(name);
  return m != nullptr ? m->input_type()->full_name() : "request message";
}

class MalformedRequestInterceptor final : public grpc::experimental::Interceptor {
 public:
  explicit MalformedRequestInterceptor(grpc::experimental::ServerRpcInfo* info) : info_(info) {}

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    // The server sets the received message to null when deserialisation failed; the status it
    // then sends is the parse failure's, which is replaced here.
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE) &&
        methods->GetRecvMessage() == nullptr)
      malformed_ = true;
    if (malformed_ && methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS))
      methods->ModifySendStatus(grpc::Status(
          grpc::StatusCode::INVALID_ARGUMENT,
          "request: the bytes received are not a valid " + request_type_of(info_->method()) +
              " (malformed protobuf, or nested deeper than 100 levels)"));
    methods->Proceed();
  }

 private:
  grpc::experimental::ServerRpcInfo* info_;
  bool malformed_ = false;
};

}  // namespace

grpc::experimental::Interceptor* MalformedRequestInterceptorFactory::CreateServerInterceptor(
    grpc::experimental::ServerRpcInfo* info) {
  return new MalformedRequestInterceptor(info);
}

}  // namespace sph::server::api
