#pragma once
// One place that turns store and validation failures into gRPC status codes.
#include <grpcpp/support/status.h>

#include <string>

namespace sph::server::api {

grpc::Status invalid_argument(const std::string& field, const std::string& problem);

// Maps the exception being handled: JobError by kind, SQLite errors to UNAVAILABLE (busy,
// retry) / RESOURCE_EXHAUSTED (disk full) / INTERNAL, anything else to INTERNAL.
grpc::Status status_from_current_exception();

// Runs a handler body, turning what it throws into a status.
template <typename Body>
grpc::Status guarded(Body&& body) {
  try {
    return body();
  } catch (...) {
    return status_from_current_exception();
  }
}

}  // namespace sph::server::api
