#pragma once
// Validation of a case's surface_tension { } block (solver/physics/surface_tension.h). Called by
// validate_case once the materials are known to be well formed; every error names its field
// below "surface_tension".
#include <vector>

#include "case/validate.h"
#include "sph/v1/case.pb.h"

namespace sph {

std::vector<FieldError> validate_surface_tension(const v1::Case& c);

}  // namespace sph
