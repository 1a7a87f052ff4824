#pragma once
// Figures of a wall-pressure probe of the Colagrossi dam break (Buchner 2002 P1) in the units
// of the data, t sqrt(g/H) and p / (rho g H): the first impact's peak, window means (the
// plateaus) and the noise, the RMS of the signal about its running mean. Shared by the ctest
// (tests/validation/density_diffusion_test.cc) and the full-size report
// (tests/validation/density_diffusion/).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/reference_table.h"

namespace sph::test {

struct Signal {
  std::vector<double> t, p;
};

// A probe's series; where no fluid reaches the probe (NaN) the pressure is 0.
inline Signal probe_signal(std::vector<double> t, std::vector<double> p) {
  for (double& v : p)
    if (std::isnan(v)) v = 0;
  return {std::move(t), std::move(p)};
}

// Buchner's P1 data, sorted by time (the digitisation is not).
inline Signal buchner_p1(const std::string& path) {
  auto rows = read_reference(path).rows;
  std::sort(rows.begin(), rows.end());
  Signal s;
  for (const auto& r : rows) {
    s.t.push_back(r[0]);
    s.p.push_back(r[1]);
  }
  return s;
}

inline double value_at(const Signal& s, double t) {
  return interpolate(s.t, s.p, t);
}

// Mean of the piecewise linear signal over [t0, t1].
inline double window_mean(const Signal& s, double t0, double t1) {
  constexpr int kN = 4000;
  double sum = 0;
  for (int k = 0; k < kN; ++k) sum += value_at(s, t0 + (t1 - t0) * (k + 0.5) / kN);
  return sum / kN;
}

// Largest sample in [t0, t1] of the signal averaged over `window` (0: the raw samples).
inline double peak(const Signal& s, double t0, double t1, double window = 0) {
  double best = -1e300;
  std::size_t lo = 0, hi = 0;
  double sum = 0;
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    while (hi < s.t.size() && s.t[hi] <= s.t[k] + 0.5 * window) sum += s.p[hi++];
    while (s.t[lo] < s.t[k] - 0.5 * window) sum -= s.p[lo++];
    if (s.t[k] < t0 || s.t[k] > t1) continue;
    best = std::max(best, window > 0 ? sum / static_cast<double>(hi - lo) : s.p[k]);
  }
  return best;
}

// RMS of the samples in [t0, t1] about the mean of the samples within window/2 of each.
inline double noise(const Signal& s, double t0, double t1, double window) {
  std::size_t lo = 0, hi = 0, n = 0;
  double sum = 0, sq = 0;
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    while (hi < s.t.size() && s.t[hi] <= s.t[k] + 0.5 * window) sum += s.p[hi++];
    while (s.t[lo] < s.t[k] - 0.5 * window) sum -= s.p[lo++];
    if (s.t[k] < t0 || s.t[k] > t1) continue;
    const double d = s.p[k] - sum / static_cast<double>(hi - lo);
    sq += d * d;
    ++n;
  }
  return n ? std::sqrt(sq / static_cast<double>(n)) : 0.0;
}

// The windows compared with the experiment (t sqrt(g/H)): the first impact, the plateau after
// it and the second impact of the wave that plunges back.
struct ImpactWindows {
  double impact0 = 2.3, impact1 = 3.2;
  double plateau0 = 3.2, plateau1 = 5.2;
  double second0 = 5.5, second1 = 6.2;
  double noise0 = 3.2, noise1 = 8.0;  // after the first impact
  double noise_window = 0.05;
};

struct ImpactFigures {
  double peak = 0, smoothed_peak = 0, plateau = 0, second = 0, noise = 0;
};

inline ImpactFigures impact_figures(const Signal& s, const ImpactWindows& w = {}) {
  ImpactFigures f;
  f.peak = peak(s, w.impact0, w.impact1);
  f.smoothed_peak = peak(s, w.impact0, w.impact1, w.noise_window);
  f.plateau = window_mean(s, w.plateau0, w.plateau1);
  f.second = window_mean(s, w.second0, w.second1);
  f.noise = noise(s, w.noise0, std::min(w.noise1, s.t.back()), w.noise_window);
  return f;
}

}  // namespace sph::test
