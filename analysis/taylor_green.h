#pragma once
// Taylor-Green vortex decay (Adami, Hu, Adams 2013): in 2D the velocity decays as
// exp(-2 nu k^2 t), k = 2 pi / wavelength; the measured rate is the least-squares slope of
// log max|u| against t after the acoustic start-up. The velocity field itself is
// U exp(-2 nu k^2 t) (-cos kx sin ky, sin kx cos ky).
#include <vector>

#include "analysis/measurement.h"
#include "analysis/result_reader.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

// Least-squares slope of log(v) against t over samples with t >= t_start and v > 0.
double log_slope(const std::vector<double>& t, const std::vector<double>& v, double t_start);

double taylor_green_decay_rate(const v1::TaylorGreenReference& r);  // -2 nu k^2

// The decay-rate error. t, max_speed: diagnostics/time and diagnostics/max_speed.
Measurement taylor_green_error(const std::vector<double>& t, const std::vector<double>& max_speed,
                               const v1::TaylorGreenReference& r);

// The velocity-field error of a snapshot (mean |u - u_exact| over fluid / the exact
// amplitude); `decay_rate` (the fitted rate, or NaN) is reported as the quantity.
Measurement taylor_green_field_error(const Snapshot& s, const v1::TaylorGreenReference& r,
                                     double decay_rate);

}  // namespace sph::analysis
