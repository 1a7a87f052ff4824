#pragma once
// The ladder of a convergence study: the particle spacing of each level from a StudySpec
// (proto/sph/v1/study.proto), its validation, and the case each level runs. Shared by sphctl
// (checks before submitting), sph-server (checks at Submit) and sph-worker (runs it).
#include <numbers>
#include <vector>

#include "case/validate.h"
#include "sph/v1/case.pb.h"
#include "sph/v1/study.pb.h"

namespace sph {

constexpr double kDefaultStudyRatio = std::numbers::sqrt2;
constexpr int kMaxStudyLevels = 12;

// Errors name the field: "reference" when the case has none, "study.refine", "study.ratio",
// "study.dx[k]" for the ladder, and a level's own problems (e.g. too many particles at the
// finest dx) under the ladder field with the level's dx. The case itself is assumed valid.
std::vector<FieldError> validate_study(const v1::Case& c, const v1::StudySpec& spec,
                                       const ValidationLimits& limits = {});

// The dx of every level, coarsest first, after reference.lattice_period snapping. Assumes
// validate_study found no errors.
std::vector<double> study_ladder(const v1::Case& c, const v1::StudySpec& spec);

// dx adjusted to lattice_period / n (reference.lattice_period; unchanged without one).
double snap_dx(const v1::Case& c, double dx);

// The case of one level: dx replaced, everything else unchanged.
v1::Case level_case(const v1::Case& c, double dx);

}  // namespace sph
