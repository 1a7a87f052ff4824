#pragma once
// The study ladder as command-line text: `--refine N`, `--ratio R`, `--dx a,b,c` (sphctl
// study, sph-worker --study-*) into a StudySpec, and a StudySpec back into words for reports.
#include <string>

#include "sph/v1/study.pb.h"

namespace sph {

// Sets the field for one flag ("refine", "ratio" or "dx"); false with `error` naming the flag
// when the value is not a number (list).
bool set_study_field(v1::StudySpec& spec, const std::string& field, const std::string& value,
                     std::string& error);

// "--refine 4 (ratio 1.41421)" or "--dx 0.04,0.02,0.01".
std::string describe_study(const v1::StudySpec& spec);

}  // namespace sph
