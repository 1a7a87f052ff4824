#pragma once
// Case validation, shared by server (at submit), worker (before running) and client
// (before submitting). Every error names the field path, e.g. "fluids[1].material".
#include <string>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

struct FieldError {
  std::string field;    // path from the case root, "" for the case as a whole
  std::string message;  // what is wrong
  std::string to_string() const { return field.empty() ? message : field + ": " + message; }
};

struct ValidationLimits {
  double max_particles = 0;  // 0 = no limit
};

std::vector<FieldError> validate_case(const v1::Case& c, const ValidationLimits& limits = {});

// All errors joined with "; " (empty when valid).
std::string join_errors(const std::vector<FieldError>& errors);

}  // namespace sph
