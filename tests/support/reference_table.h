#pragma once
// Tests read the reference CSV files under tests/validation/data with the case library's
// reader (case/reference_table.h).
#include <string>

#include "case/reference_table.h"

namespace sph::test {

inline ReferenceTable read_reference(const std::string& path) {
  return read_reference_table(path);
}
using sph::interpolate;

}  // namespace sph::test
