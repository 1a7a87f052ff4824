#pragma once
// Prescribed rigid motion (translation plus rotation about a moving centre) of walls and
// prescribed bodies. Positions follow exactly from the integrated velocity functions.
#include <Eigen/Geometry>

#include "case/geometry.h"
#include "case/time_function.h"

namespace sph {

class MotionPath {
 public:
  // The motion at one time, evaluated once for all the points that follow it: the time
  // functions and the rotation (a dozen transcendental calls) are shared, and each point
  // costs a few multiply-adds. Gives the same values, to the bit, as position(), velocity()
  // and acceleration() below, which evaluate it for a single point.
  class Pose {
   public:
    Point3 position(const Point3& x0) const { return center_ + rotation_ * (x0 - center0_); }
    Point3 velocity(const Point3& x0) const {
      return velocity_ + omega_ * axis_.cross(position(x0) - center_);
    }
    Point3 acceleration(const Point3& x0) const {
      const Point3 r = position(x0) - center_;
      const Point3 wvec = omega_ * axis_;
      return acceleration_ + alpha_ * axis_.cross(r) + wvec.cross(wvec.cross(r));
    }

   private:
    friend class MotionPath;
    Eigen::Matrix3d rotation_;
    Point3 center_, center0_, axis_, velocity_, acceleration_;
    double omega_ = 0, alpha_ = 0;
  };

  MotionPath() = default;
  MotionPath(const v1::Motion& m, int dim);
  bool is_static() const { return static_; }
  // Where a point that was at x0 at t = 0 is at time t, its velocity and acceleration.
  Point3 position(const Point3& x0, double t) const;
  Point3 velocity(const Point3& x0, double t) const;
  Point3 acceleration(const Point3& x0, double t) const;
  Pose pose(double t) const;
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
