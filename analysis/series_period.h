#pragma once
// The period of an oscillating result series against an exact one (reference.series_period),
// e.g. a cantilever's first bending period against Euler-Bernoulli.
#include <vector>

#include "analysis/measurement.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

// Times at which `values` passes through `mean`, linearly interpolated between samples.
// Samples exactly at the mean take no side: a crossing is a change between a sample above and
// one below, placed at the first sample on the mean between them if there is one. With
// starts_at_crossing, the first sample is the first crossing and takes no side either.
std::vector<double> mean_crossings(const std::vector<double>& t, const std::vector<double>& values,
                                   double mean, bool starts_at_crossing);

// t, values: the series (one scalar per sample). Throws naming the reference when the series
// crosses its mean too few times for the cycles asked for. quantity: the measured period.
Measurement series_period_error(const std::vector<double>& t, const std::vector<double>& values,
                                const v1::SeriesPeriodReference& r);

}  // namespace sph::analysis
