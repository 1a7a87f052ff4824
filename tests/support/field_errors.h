#pragma once
// Looking for one validation error among many, for the case and study tests.
#include <string>
#include <vector>

#include "case/validate.h"

namespace sph::testing {

// True if some error has exactly this field and a message containing `what`.
inline bool has_error(const std::vector<FieldError>& errs, const std::string& field,
                      const std::string& what) {
  for (const auto& e : errs)
    if (e.field == field && e.message.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace sph::testing
