#pragma once
// 1D conduction (or diffusion) into a semi-infinite medium whose surface is held at a fixed
// value: the erf profile T = T_b + (T_0 - T_b) erf((x - x_b) / (2 sqrt(a t))).
#include <vector>

#include "analysis/measurement.h"
#include "analysis/result_reader.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

double conduction_profile(const v1::ConductionReference& r, double x, double t);

// values: the snapshot's temperature (or concentration) per particle. Max |T - exact| over
// fluid and rigid particles with x <= x_max, relative to |T_b - T_0|.
Measurement conduction_error(const Snapshot& s, const std::vector<double>& values,
                             const v1::ConductionReference& r);

}  // namespace sph::analysis
