#include "server/api/errors.h"

#include <exception>

#include "common/log.h"
#include "server/store/job_error.h"
#include "server/store/sqlite.h"

namespace sph::server::api {

grpc::Status invalid_argument(const std::string& field, const std::string& problem) {
  return {grpc::StatusCode::INVALID_ARGUMENT, field + ": " + problem};
}

grpc::Status status_from_current_exception() {
  using store::JobError;
  try {
    throw;
  } catch (const JobError& e) {
    switch (e.kind()) {
      case JobError::Kind::kNotFound:
        return {grpc::StatusCode::NOT_FOUND, e.what()};
      case JobError::Kind::kStaleAttempt:
        return {grpc::StatusCode::ABORTED, e.what()};
      case JobError::Kind::kRequestConflict:
        return {grpc::StatusCode::ALREADY_EXISTS, e.what()};
      case JobError::Kind::kInvalid:
        return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
      case JobError::Kind::kPrecondition:
        return {grpc::StatusCode::FAILED_PRECONDITION, e.what()};
    }
  } catch (const store::SqliteError& e) {
    service::log_line("database error: %s", e.what());
    const int primary = e.code() & 0xff;
    if (primary == SQLITE_BUSY || primary == SQLITE_LOCKED)
      return {grpc::StatusCode::UNAVAILABLE, std::string("database busy, retry: ") + e.what()};
    if (primary == SQLITE_FULL)
      return {grpc::StatusCode::RESOURCE_EXHAUSTED, std::string("disk full: ") + e.what()};
    return {grpc::StatusCode::INTERNAL, std::string("database error: ") + e.what()};
  } catch (const std::exception& e) {
    service::log_line("internal error: %s", e.what());
    return {grpc::StatusCode::INTERNAL, e.what()};
  }
  return {grpc::StatusCode::INTERNAL, "unknown error"};
}

}  // namespace sph::server::api
