#pragma once
// Why a job operation was refused. The API layer maps each kind to a gRPC status code.
#include <stdexcept>
#include <string>

namespace sph::server::store {

class JobError : public std::runtime_error {
 public:
  enum class Kind {
    kNotFound,         // no such job (or file)
    kStaleAttempt,     // a worker call for an attempt that is no longer current
    kRequestConflict,  // request_id reused with a different case
    kInvalid,          // a malformed request
    kPrecondition,     // the job's state does not allow the call
  };
  JobError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace sph::server::store
