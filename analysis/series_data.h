#pragma once
// Result time series against tabulated data (reference.series_data): a published experiment
// or simulation sampled at its own times.
#include <string>
#include <vector>

#include "analysis/measurement.h"
#include "sph/v1/case.pb.h"

namespace sph::analysis {

// One scalar per sample from a flattened series of `samples` rows: the entry `component` of
// each row, or the sum of a row's finite entries. Throws naming `field` when the component is
// outside the row.
std::vector<double> series_component(const std::vector<double>& series, std::size_t samples,
                                     int component, bool sum_components, const std::string& field);

// t, values: the series (one scalar per sample) in simulation units.
Measurement series_data_error(const std::vector<double>& t, const std::vector<double>& values,
                              const v1::SeriesDataReference& r);

}  // namespace sph::analysis
