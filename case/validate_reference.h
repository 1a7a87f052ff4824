#pragma once
// Validation of a case's reference { } block (what a convergence study measures against).
// Called by validate_case; every error names its field below "reference".
#include <vector>

#include "case/validate.h"
#include "sph/v1/case.pb.h"

namespace sph {

std::vector<FieldError> validate_reference(const v1::Case& c);

}  // namespace sph
