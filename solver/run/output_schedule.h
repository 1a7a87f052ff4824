#pragma once
// When to write snapshots and series samples. Snapshot times are hit exactly: the time step
// is shortened to land on them (and on end_time).
#include <algorithm>
#include <cmath>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

class OutputSchedule {
 public:
  explicit OutputSchedule(const v1::Case& c) : end_(c.time().end_time()) {
    eps_ = 1e-12 * std::max(1.0, end_);
    times_.push_back(0.0);
    const double iv = c.output().interval();
    if (iv > 0)
      for (long k = 1; k * iv < end_ - eps_; ++k) times_.push_back(static_cast<double>(k) * iv);
    for (double t : c.output().times()) times_.push_back(t);
    times_.push_back(end_);
    std::sort(times_.begin(), times_.end());
    times_.erase(std::unique(times_.begin(), times_.end(),
                             [&](double a, double b) { return std::abs(a - b) <= eps_; }),
                 times_.end());
    series_interval_ =
        c.output().series_interval() > 0 ? c.output().series_interval() : end_ / 200.0;
  }

  double end_time() const { return end_; }
  bool finished(double t) const { return t >= end_ - eps_; }
  // Index of the first snapshot time after t (for a resumed run).
  std::size_t first_after(double t) const {
    std::size_t k = 0;
    while (k < times_.size() && times_[k] <= t + eps_) ++k;
    return k;
  }
  // Shortens dt so that a step lands on the next snapshot time instead of passing it, and
  // avoids a sliver of a step just before it.
  double clip(double t, double dt, std::size_t next) const {
    if (next >= times_.size()) return dt;
    const double left = times_[next] - t;
    if (dt >= left - eps_) return left;
    if (2.0 * dt > left) return 0.5 * left;
    return dt;
  }
  bool snapshot_due(double t, std::size_t next) const {
    return next < times_.size() && t >= times_[next] - eps_;
  }
  double series_interval() const { return series_interval_; }
  double eps() const { return eps_; }

 private:
  double end_, eps_;
  std::vector<double> times_;
  double series_interval_;
};

}  // namespace sph
