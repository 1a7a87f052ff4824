#include "case/time_function.h"

#include <algorithm>
#include <cmath>

namespace sph {

TimeFunction::TimeFunction(const v1::TimeFunction& f) : start_(f.start_time()), end_(f.end_time()) {
  switch (f.kind_case()) {
    case v1::TimeFunction::kConstant:
      kind_ = Kind::kConstant;
      c_ = f.constant();
      break;
    case v1::TimeFunction::kSine:
      kind_ = Kind::kSine;
      offset_ = f.sine().offset();
      amp_ = f.sine().amplitude();
      omega_ = f.sine().angular_frequency();
      phase_ = f.sine().phase();
      break;
    case v1::TimeFunction::kPiecewiseLinear:
    case v1::TimeFunction::kPiecewiseConstant: {
      const auto& tab = f.kind_case() == v1::TimeFunction::kPiecewiseLinear
                            ? f.piecewise_linear()
                            : f.piecewise_constant();
      kind_ = f.kind_case() == v1::TimeFunction::kPiecewiseLinear ? Kind::kLinear : Kind::kStep;
      times_.assign(tab.times().begin(), tab.times().end());
      values_.assign(tab.values().begin(), tab.values().end());
      // cumulative_[i] = integral of the raw table function from times_[0] to times_[i].
      cumulative_.assign(times_.size(), 0.0);
      for (size_t i = 1; i < times_.size(); ++i) {
        const double w = times_[i] - times_[i - 1];
        const double seg =
            kind_ == Kind::kLinear ? 0.5 * (values_[i] + values_[i - 1]) * w : values_[i - 1] * w;
        cumulative_[i] = cumulative_[i - 1] + seg;
      }
      break;
    }
    case v1::TimeFunction::KIND_NOT_SET:
      kind_ = Kind::kZero;
      break;
  }
}

double TimeFunction::max_value() const {
  double peak = 0;
  switch (kind_) {
    case Kind::kZero:
      return 0.0;
    case Kind::kConstant:
      peak = c_;
      break;
    case Kind::kSine:
      peak = offset_ + std::abs(amp_);
      break;
    case Kind::kLinear:
    case Kind::kStep:  // held at the ends, linear or constant between: a table value is the top
      if (!values_.empty()) peak = *std::max_element(values_.begin(), values_.end());
      break;
  }
  const bool always_active = start_ <= 0.0 && end_ <= 0.0;
  return always_active ? peak : std::max(peak, 0.0);
}

double TimeFunction::raw_value(double t) const {
  switch (kind_) {
    case Kind::kZero:
      return 0.0;
    case Kind::kConstant:
      return c_;
    case Kind::kSine:
      return offset_ + amp_ * std::sin(omega_ * t + phase_);
    case Kind::kLinear:
    case Kind::kStep: {
      if (t <= times_.front()) return values_.front();
      if (t >= times_.back()) return values_.back();
      const size_t i = static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) -
                                           times_.begin());  // times_[i-1] <= t < times_[i]
      if (kind_ == Kind::kStep) return values_[i - 1];
      const double s = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
      return values_[i - 1] + s * (values_[i] - values_[i - 1]);
    }
  }
  return 0.0;
}

double TimeFunction::raw_derivative(double t) const {
  switch (kind_) {
    case Kind::kSine:
      return amp_ * omega_ * std::cos(omega_ * t + phase_);
    case Kind::kLinear: {
      if (t <= times_.front() || t >= times_.back()) return 0.0;
      const size_t i =
          static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
      return (values_[i] - values_[i - 1]) / (times_[i] - times_[i - 1]);
    }
    default:
      return 0.0;
  }
}

double TimeFunction::raw_antiderivative(double t) const {
  switch (kind_) {
    case Kind::kZero:
      return 0.0;
    case Kind::kConstant:
      return c_ * t;
    case Kind::kSine:
      if (omega_ == 0.0) return (offset_ + amp_ * std::sin(phase_)) * t;
      return offset_ * t - amp_ / omega_ * std::cos(omega_ * t + phase_);
    case Kind::kLinear:
    case Kind::kStep: {
      if (t <= times_.front()) return values_.front() * (t - times_.front());
      if (t >= times_.back()) return cumulative_.back() + values_.back() * (t - times_.back());
      const size_t i =
          static_cast<size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
      const double w = t - times_[i - 1];
      const double v =
          kind_ == Kind::kLinear ? 0.5 * (values_[i - 1] + raw_value(t)) * w : values_[i - 1] * w;
      return cumulative_[i - 1] + v;
    }
  }
  return 0.0;
}

double TimeFunction::value(double t) const {
  return active(t) ? raw_value(t) : 0.0;
}

double TimeFunction::derivative(double t) const {
  return active(t) ? raw_derivative(t) : 0.0;
}

double TimeFunction::integral(double t) const {
  if (kind_ == Kind::kZero || t <= start_) return 0.0;
  const double upper = end_ > 0.0 ? std::min(t, end_) : t;
  return raw_antiderivative(upper) - raw_antiderivative(start_);
}

}  // namespace sph
