#pragma once
// Functions of time used for prescribed motion and boundary schedules, with their exact
// integral and derivative (positions of moving walls are exact integrals of the velocity,
// and the wall acceleration enters the Adami 2012 pressure condition, eq. 27).
#include "sph/v1/case.pb.h"

namespace sph {

class TimeFunction {
 public:
  TimeFunction() = default;  // identically zero
  explicit TimeFunction(const v1::TimeFunction& f);
  double value(double t) const;
  double derivative(double t) const;
  double integral(double t) const;  // from 0 to t
  bool is_zero() const { return kind_ == Kind::kZero; }
  // The largest value it takes at any time t >= 0 (0 outside its active window, if it has one);
  // an upper bound where the window cuts off a sine's crest.
  double max_value() const;

 private:
  enum class Kind { kZero, kConstant, kSine, kLinear, kStep };
  double raw_value(double t) const;
  double raw_derivative(double t) const;
  double raw_antiderivative(double t) const;  // G with G' = raw_value
  bool active(double t) const { return t >= start_ && (end_ <= 0.0 || t <= end_); }

  Kind kind_ = Kind::kZero;
  double c_ = 0, offset_ = 0, amp_ = 0, omega_ = 0, phase_ = 0;
  std::vector<double> times_, values_, cumulative_;
  double start_ = 0, end_ = 0;
};

}  // namespace sph
