// Prescribed motions of walls and bodies and the time functions they are made of.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::time_function(const v1::TimeFunction& tf, const std::string& f) {
  switch (tf.kind_case()) {
    case v1::TimeFunction::kConstant:
      if (!finite(tf.constant())) error(cat(f, "constant"), "must be finite");
      break;
    case v1::TimeFunction::kSine:
      if (!finite(tf.sine().amplitude()) || !finite(tf.sine().angular_frequency()) ||
          !finite(tf.sine().offset()) || !finite(tf.sine().phase()))
        error(cat(f, "sine"), "all parameters must be finite");
      break;
    case v1::TimeFunction::kPiecewiseLinear:
    case v1::TimeFunction::kPiecewiseConstant: {
      const bool lin = tf.kind_case() == v1::TimeFunction::kPiecewiseLinear;
      const auto& t = lin ? tf.piecewise_linear() : tf.piecewise_constant();
      const std::string tfld = cat(f, lin ? "piecewise_linear" : "piecewise_constant");
      if (t.times_size() == 0) error(cat(tfld, "times"), "is empty");
      if (t.times_size() != t.values_size())
        error(cat(tfld, "values"),
              "needs as many values as times (" + std::to_string(t.times_size()) + ")");
      for (int i = 1; i < t.times_size(); ++i)
        if (!(t.times(i) > t.times(i - 1)))
          error(idx(cat(tfld, "times"), i), "times must be strictly increasing");
      break;
    }
    case v1::TimeFunction::KIND_NOT_SET:
      break;
  }
  non_negative(tf.start_time(), cat(f, "start_time"));
  if (tf.end_time() != 0 && tf.end_time() <= tf.start_time())
    error(cat(f, "end_time"), "must be greater than start_time (or 0 for never)");
}

void Validator::motion(const v1::Motion& m, const std::string& f) {
  time_function(m.velocity_x(), cat(f, "velocity_x"));
  time_function(m.velocity_y(), cat(f, "velocity_y"));
  if (c_.dimension() == 2 && m.has_velocity_z())
    error(cat(f, "velocity_z"), "not allowed in a 2D case");
  time_function(m.velocity_z(), cat(f, "velocity_z"));
  time_function(m.angular_velocity(), cat(f, "angular_velocity"));
  vec(m.center(), cat(f, "center"));
  vec(m.axis(), cat(f, "axis"));
  if (c_.dimension() == 3 && m.has_angular_velocity() && m.axis().x() == 0 && m.axis().y() == 0 &&
      m.axis().z() == 0)
    error(cat(f, "axis"), "a 3D rotation needs a non-zero axis");
}

}  // namespace sph::case_validation
