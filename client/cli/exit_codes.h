#pragma once
// sphctl's exit codes. Scripts rely on them: never renumber, only add (docs/service.md).

namespace sph::ctl {

enum ExitCode : int {
  kOk = 0,
  kFailure = 1,        // anything not listed below (an internal server error, ...)
  kUsage = 2,          // bad command line
  kInvalidCase = 3,    // the case failed validation (locally or at the server)
  kNotFound = 4,       // no such job, or no such result file
  kUnavailable = 5,    // server unreachable, shutting down, or a call timed out
  kAuth = 6,           // missing or wrong token
  kVerifyFailed = 7,   // a fetched file failed its sha256/size check, or could not be written
  kConflict = 8,       // request id reused with a different case; job has no result yet
  kJobFailed = 10,     // watch / submit --watch: the job ended FAILED
  kJobCancelled = 11,  // watch / submit --watch: the job ended CANCELLED
};

}  // namespace sph::ctl
