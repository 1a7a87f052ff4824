#include "analysis/series_data.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "case/reference_table.h"

namespace sph::analysis {

std::vector<double> series_component(const std::vector<double>& series, std::size_t samples,
                                     int component, bool sum_components, const std::string& field) {
  if (samples == 0 || series.size() % samples != 0)
    throw std::runtime_error(field + ": the series has " + std::to_string(series.size()) +
                             " values for " + std::to_string(samples) + " samples");
  const std::size_t row = series.size() / samples;
  if (!sum_components && static_cast<std::size_t>(component) >= row)
    throw std::runtime_error(field + ".component: " + std::to_string(component) +
                             " is outside the series' rows of " + std::to_string(row) + " values");
  std::vector<double> out(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    if (!sum_components) {
      out[k] = series[k * row + static_cast<std::size_t>(component)];
      continue;
    }
    double sum = 0;
    for (std::size_t j = 0; j < row; ++j)
      if (std::isfinite(series[k * row + j])) sum += series[k * row + j];
    out[k] = sum;
  }
  return out;
}

Measurement series_data_error(const std::vector<double>& t, const std::vector<double>& values,
                              const v1::SeriesDataReference& r) {
  const double ts = r.has_time_scale() ? r.time_scale() : 1.0;
  const double vs = r.has_value_scale() ? r.value_scale() : 1.0;
  std::vector<double> T(t.size()), V(values.size());
  for (std::size_t k = 0; k < t.size(); ++k) T[k] = t[k] * ts;
  for (std::size_t k = 0; k < values.size(); ++k) V[k] = values[k] * vs;
  if (T.empty()) throw std::runtime_error("reference.series_data.series: the series is empty");
  const double lo = r.t_min(), hi = r.t_max() > 0 ? r.t_max() : T.back();
  Measurement m;
  char buf[200];
  if (r.metric() == v1::SeriesDataReference::WINDOW_MEAN) {
    double sim = 0, ref = 0;
    int ns = 0, nr = 0;
    for (std::size_t k = 0; k < T.size(); ++k)
      if (T[k] >= lo && T[k] <= hi) sim += V[k], ++ns;
    for (int k = 0; k < r.times_size(); ++k)
      if (r.times(k) >= lo && r.times(k) <= hi) ref += r.values(k), ++nr;
    if (ns == 0 || nr == 0)
      throw std::runtime_error("reference.series_data: no " +
                               std::string(ns == 0 ? "series samples" : "data points") +
                               " in the window [t_min, t_max]");
    sim /= ns;
    ref /= nr;
    m.quantity = sim;
    m.error = std::abs(sim / ref - 1);
    std::snprintf(buf, sizeof buf, "mean over [%g, %g]: %.5g vs data %.5g: %.3f%%", lo, hi, sim,
                  ref, 100 * m.error);
  } else {
    double sum = 0, worst = 0;
    int n = 0;
    for (int k = 0; k < r.times_size(); ++k) {
      const double tk = r.times(k);
      if (tk < lo || tk > hi || tk > T.back() || tk < T.front() || r.values(k) == 0) continue;
      const double d = std::abs(interpolate(T, V, tk) / r.values(k) - 1);
      sum += d;
      worst = std::max(worst, d);
      ++n;
    }
    if (n == 0)
      throw std::runtime_error(
          "reference.series_data: no data points within the window and the run's time span");
    m.error = sum / n;
    std::snprintf(buf, sizeof buf,
                  "mean |value / data - 1| over %d data points in [%g, %g]: %.3f%% (max %.3f%%)", n,
                  lo, hi, 100 * m.error, 100 * worst);
  }
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
