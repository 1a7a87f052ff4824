#pragma once
// Case validation, shared by server (at submit), worker (before running) and client
// (before submitting). Every error names the field path, e.g. "fluids[1].material". The bounds
// of case/case_limits.h are checked first (case/case_bounds.h); a case that breaks one gets
// only those errors, as the other checks may not run on it.
#include <string>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

struct FieldError {
  std::string field;    // path from the case root, "" for the case as a whole
  std::string message;  // what is wrong
  std::string to_string() const { return field.empty() ? message : field + ": " + message; }
};

// Size limits of whoever runs the case (sph-server's and sph-worker's --max-particles and
// --max-memory-gib); refusals quote the estimate, the limit and `source`.
struct ValidationLimits {
  double max_particles = 0;              // estimate_case().total(), 0 = no limit
  double max_memory_bytes = 0;           // estimate_case().bytes, 0 = no limit
  std::string source = "this server's";  // "this server's limit is 2e7 (--max-particles)"
};

struct CaseEstimate;  // case/estimate.h

// With `estimate`, a valid case's estimate_case() is left there (validation computes it for
// the limits; the server would otherwise compute it twice per submit).
std::vector<FieldError> validate_case(const v1::Case& c, const ValidationLimits& limits = {},
                                      CaseEstimate* estimate = nullptr);

// All errors joined with "; " (empty when valid).
std::string join_errors(const std::vector<FieldError>& errors);

}  // namespace sph
