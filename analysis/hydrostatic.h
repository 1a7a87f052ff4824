#pragma once
// Hydrostatic tank (Adami 2012 sec. 6.1): the pressure of the first wall layer under the
// bottom against rho0 |g| (H + dx/2). The layer's centre lies dx/2 below the bottom surface,
// and H, the fluid depth, comes from the fluid mass, so a lattice that does not fill the
// nominal depth exactly is not counted as an error.
#include "analysis/measurement.h"
#include "analysis/result_reader.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

Measurement hydrostatic_error(const Snapshot& s, const v1::HydrostaticReference& r, double rho0,
                              double gravity, double dx);

}  // namespace sph::analysis
