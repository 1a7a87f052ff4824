#pragma once
// Reference data files of a case (reference.series_data.file) are read when the case is
// loaded and inlined into the case, as point files are: a submitted case never depends on
// files that only the submitting machine has.
#include <string>

#include "sph/v1/case.pb.h"

namespace sph {

// Replaces reference.series_data.file (relative to base_dir) by its times and values.
// Throws CaseLoadError naming the field when the file cannot be read or lacks the column.
void inline_reference_data(v1::Case& c, const std::string& base_dir);

}  // namespace sph
