#pragma once
// Prescribed rigid motion (translation plus rotation about a moving centre) of walls and
// prescribed bodies. Positions follow exactly from the integrated velocity functions.
#include <Eigen/Geometry>

#include "case/geometry.h"
#include "case/time_function.h"

namespace sph {

class MotionPath {
 public:
  MotionPath() = default;
  MotionPath(const v1::Motion& m, int dim);
  bool is_static() const { return static_; }
  // Where a point that was at x0 at t = 0 is at time t, its velocity and acceleration.
  Point3 position(const Point3& x0, double t) const;
  Point3 velocity(const Point3& x0, double t) const;
  Point3 acceleration(const Point3& x0, double t) const;
  Point3 center(double t) const;
  // Rotation angle about the axis since t = 0, and the axis.
  double angle(double t) const { return omega_.integral(t); }
  const Point3& axis() const { return axis_; }
  // Angular velocity and acceleration (about the axis).
  double angular_velocity(double t) const { return omega_.value(t); }
  double angular_acceleration(double t) const { return omega_.derivative(t); }

 private:
  Point3 translation(double t) const;
  Point3 translation_velocity(double t) const;
  Point3 translation_acceleration(double t) const;

  bool static_ = true;
  int dim_ = 2;
  TimeFunction v_[3];
  TimeFunction omega_;
  Point3 center0_ = Point3::Zero();
  Point3 axis_ = Point3::UnitZ();
};

}  // namespace sph
