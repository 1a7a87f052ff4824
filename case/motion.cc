#include "case/motion.h"

namespace sph {

MotionPath::MotionPath(const v1::Motion& m, int dim)
    : dim_(dim),
      v_{TimeFunction(m.velocity_x()), TimeFunction(m.velocity_y()), TimeFunction(m.velocity_z())},
      omega_(m.angular_velocity()),
      center0_(to_point(m.center())) {
  if (dim == 3 && to_point(m.axis()).norm() > 0) axis_ = to_point(m.axis()).normalized();
  static_ = v_[0].is_zero() && v_[1].is_zero() && v_[2].is_zero() && omega_.is_zero();
}

Point3 MotionPath::translation(double t) const {
  return {v_[0].integral(t), v_[1].integral(t), dim_ == 3 ? v_[2].integral(t) : 0.0};
}
Point3 MotionPath::translation_velocity(double t) const {
  return {v_[0].value(t), v_[1].value(t), dim_ == 3 ? v_[2].value(t) : 0.0};
}
Point3 MotionPath::translation_acceleration(double t) const {
  return {v_[0].derivative(t), v_[1].derivative(t), dim_ == 3 ? v_[2].derivative(t) : 0.0};
}

Point3 MotionPath::center(double t) const {
  return center0_ + translation(t);
}

MotionPath::Pose MotionPath::pose(double t) const {
  Pose p;
  p.rotation_ = Eigen::AngleAxisd(omega_.integral(t), axis_).toRotationMatrix();
  p.center_ = center(t);
  p.center0_ = center0_;
  p.axis_ = axis_;
  p.velocity_ = translation_velocity(t);
  p.acceleration_ = translation_acceleration(t);
  p.omega_ = omega_.value(t);
  p.alpha_ = omega_.derivative(t);
  return p;
}

Point3 MotionPath::position(const Point3& x0, double t) const {
  return pose(t).position(x0);
}

Point3 MotionPath::velocity(const Point3& x0, double t) const {
  return pose(t).velocity(x0);
}

Point3 MotionPath::acceleration(const Point3& x0, double t) const {
  return pose(t).acceleration(x0);
}

}  // namespace sph
