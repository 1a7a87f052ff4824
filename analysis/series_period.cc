#include "analysis/series_period.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sph::analysis {

std::vector<double> mean_crossings(const std::vector<double>& t, const std::vector<double>& values,
                                   double mean, bool starts_at_crossing) {
  std::vector<double> out;
  std::size_t k = 0;
  if (starts_at_crossing && !t.empty()) out.push_back(t[k++]);
  int side = 0;             // +1 above the mean, -1 below; 0 until a sample leaves it
  std::size_t last = 0;     // the last sample that took a side
  std::size_t on_mean = 0;  // the first sample exactly on the mean since then (0: none)
  for (; k < t.size(); ++k) {
    const double d = values[k] - mean;
    if (d == 0) {
      if (side != 0 && on_mean == 0) on_mean = k + 1;
      continue;
    }
    const int s = d > 0 ? 1 : -1;
    if (side != 0 && s != side) {
      if (on_mean != 0) {
        out.push_back(t[on_mean - 1]);
      } else {
        const double d0 = values[last] - mean;
        out.push_back(t[last] + (t[k] - t[last]) * d0 / (d0 - d));
      }
    }
    side = s;
    last = k;
    on_mean = 0;
  }
  return out;
}

Measurement series_period_error(const std::vector<double>& t, const std::vector<double>& values,
                                const v1::SeriesPeriodReference& r) {
  if (t.empty() || t.size() != values.size())
    throw std::runtime_error("reference.series_period.series: the series is empty");
  const int first = r.has_first_cycle() ? r.first_cycle() : 1;
  const int cycles = r.has_cycles() ? r.cycles() : 1;
  const std::vector<double> c = mean_crossings(t, values, r.mean(), r.starts_at_crossing());
  // Cycle n runs from crossing 2n - 1 to 2n + 1 (counting from 1), i.e. c[2n - 2] to c[2n].
  const std::size_t from = 2 * static_cast<std::size_t>(first - 1);
  const std::size_t to = from + 2 * static_cast<std::size_t>(cycles);
  if (to >= c.size()) {
    const std::string which = cycles == 1 ? "cycle " + std::to_string(first)
                                          : "cycles " + std::to_string(first) + " to " +
                                                std::to_string(first + cycles - 1);
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "reference.series_period: the series crosses its mean (%.6g) %zu times up to "
                  "t = %.6g; %s need%s %zu (run longer: time.end_time)",
                  r.mean(), c.size(), t.back(), which.c_str(), cycles == 1 ? "s" : "", to + 1);
    throw std::runtime_error(buf);
  }
  Measurement m;
  m.quantity = (c[to] - c[from]) / cycles;
  m.error = std::abs(m.quantity / r.period() - 1);
  char buf[300];
  std::snprintf(
      buf, sizeof buf,
      "period of cycle%s %d%s%s from the crossings at t = %.6g and %.6g: %.6g s vs %.6g s "
      "(%+.3f%%)",
      cycles > 1 ? "s" : "", first, cycles > 1 ? " to " : "",
      cycles > 1 ? std::to_string(first + cycles - 1).c_str() : "", c[from], c[to], m.quantity,
      r.period(), 100 * (m.quantity / r.period() - 1));
  m.detail = buf;
  return m;
}

}  // namespace sph::analysis
