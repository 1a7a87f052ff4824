// Shapes, the lattice fill, and prescribed motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "case/geometry.h"
#include "case/lattice.h"
#include "case/load.h"
#include "case/motion.h"
#include "case/time_function.h"

#include <google/protobuf/text_format.h>

namespace sph {
namespace {

v1::Shape shape(const std::string& text) {
  v1::Shape s;
  google::protobuf::TextFormat::ParseFromString(text, &s);
  return s;
}

double count(const std::string& text, int dim, double dx) {
  auto s = compile_shape(shape(text), dim, 3 * dx);
  Aabb clip{Point3::Constant(-100), Point3::Constant(100)};
  if (dim == 2) clip.lo.z() = clip.hi.z() = 0;
  return count_lattice_points(*s, LatticeSpec{dim, dx, Point3::Zero()}, clip);
}

TEST(Geometry, BoxFillIsExact) {
  EXPECT_EQ(count("box { lo { x: 0 y: 0 } hi { x: 1 y: 0.5 } }", 2, 0.1), 50);
  EXPECT_EQ(count("box { lo { x: 0 y: 0 z: 0 } hi { x: 1 y: 0.5 z: 0.2 } }", 3, 0.1), 100);
}

TEST(Geometry, ShellHasSquareCornersAndGivenThickness) {
  // A 3-layer shell around a 1 x 1 box: (10 + 6)^2 - 10^2 lattice points.
  EXPECT_EQ(count("shell { inner { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } }", 2, 0.1),
            16 * 16 - 100);
  EXPECT_EQ(
      count("shell { inner { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } thickness: 0.1 }", 2, 0.1),
      12 * 12 - 100);
}

TEST(Geometry, DiskAreaConverges) {
  for (double dx : {0.02, 0.01}) {
    const double n = count("ball { center { x: 0.3 y: 0.1 } radius: 0.5 }", 2, dx);
    EXPECT_NEAR(n * dx * dx, std::numbers::pi * 0.25, 0.02 * std::numbers::pi * 0.25) << dx;
  }
}

TEST(Geometry, CylinderVolume) {
  const double dx = 0.02;
  const double n =
      count("cylinder { base { x: 0 y: 0 z: 0 } axis { x: 1 y: 1 z: 0 } radius: 0.2 length: 0.6 }",
            3, dx);
  EXPECT_NEAR(n * dx * dx * dx, std::numbers::pi * 0.04 * 0.6,
              0.03 * std::numbers::pi * 0.04 * 0.6);
}

TEST(Geometry, PolygonAndBooleans) {
  // Triangle of area 0.5 minus a disk of radius 0.1.
  const double dx = 0.005;
  const double n = count(R"(difference {
      base { polygon { vertices { x: 0 y: 0 } vertices { x: 1 y: 0 } vertices { x: 0 y: 1 } } }
      subtract { ball { center { x: 0.3 y: 0.3 } radius: 0.1 } } })",
                         2, dx);
  EXPECT_NEAR(n * dx * dx, 0.5 - std::numbers::pi * 0.01, 0.005);
  const double u = count(R"(union { shapes { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } }
                                     shapes { box { lo { x: 0.5 y: 0 } hi { x: 1.5 y: 1 } } } })",
                         2, 0.1);
  EXPECT_EQ(u, 150);
  const double i = count(R"(intersection { shapes { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } }
                                     shapes { box { lo { x: 0.5 y: 0 } hi { x: 1.5 y: 1 } } } })",
                         2, 0.1);
  EXPECT_EQ(i, 50);
}

TEST(Geometry, PolarCurveArea) {
  // Area of r = R + a sin(k phi): pi (R^2 + a^2 / 2).
  const double dx = 0.005;
  const double n = count("polar_curve { radius: 0.7 amplitude: 0.1 periods: 8 }", 2, dx);
  EXPECT_NEAR(n * dx * dx, std::numbers::pi * (0.49 + 0.005), 0.005);
}

TEST(Geometry, PointSetGivesItsPoints) {
  EXPECT_EQ(count("points { points { x: 1 y: 2 } points { x: 3 y: 4 } }", 2, 0.1), 2);
}

TEST(TimeFunction, IntegralsAndDerivativesAreExact) {
  v1::TimeFunction f;
  google::protobuf::TextFormat::ParseFromString(
      "sine { offset: 0.5 amplitude: 2 angular_frequency: 3 phase: 0.2 } start_time: 0.5 end_time: "
      "2",
      &f);
  const TimeFunction tf(f);
  // Numerical integral (midpoint rule) and derivative.
  double acc = 0;
  const double h = 1e-5;
  for (double t = h / 2; t < 2.5; t += h) acc += tf.value(t) * h;
  EXPECT_NEAR(tf.integral(2.5), acc, 1e-6);
  EXPECT_NEAR(tf.derivative(1.0), (tf.value(1.0 + 1e-6) - tf.value(1.0 - 1e-6)) / 2e-6, 1e-6);
  EXPECT_EQ(tf.value(0.2), 0.0);
  EXPECT_EQ(tf.value(2.1), 0.0);

  v1::TimeFunction g;
  google::protobuf::TextFormat::ParseFromString(
      "piecewise_linear { times: 0 times: 1 times: 3 values: 0 values: 2 values: -2 }", &g);
  const TimeFunction tg(g);
  EXPECT_DOUBLE_EQ(tg.value(0.5), 1.0);
  EXPECT_DOUBLE_EQ(tg.integral(1.0), 1.0);
  EXPECT_DOUBLE_EQ(tg.integral(3.0), 1.0);        // 1 + (2 - 2)/2 * 2
  EXPECT_DOUBLE_EQ(tg.integral(4.0), 1.0 - 2.0);  // holds the last value
  EXPECT_DOUBLE_EQ(tg.derivative(2.0), -2.0);

  v1::TimeFunction k;
  google::protobuf::TextFormat::ParseFromString(
      "piecewise_constant { times: 0 times: 1 values: 3 values: 5 }", &k);
  const TimeFunction tk(k);
  EXPECT_DOUBLE_EQ(tk.integral(2.0), 3.0 + 5.0);

  // The largest value over all t >= 0, sampled densely: the sine's crest, the table's top
  // value, and 0 where a function negative everywhere is inactive before its start. A window
  // that cuts off a crest leaves max_value() an upper bound.
  const auto sampled_max = [](const TimeFunction& fn) {
    double m = -1e300;
    for (double t = 0; t < 6; t += 1e-4) m = std::max(m, fn.value(t));
    return m;
  };
  EXPECT_NEAR(tf.max_value(), 2.5, 1e-12);
  EXPECT_LE(sampled_max(tf), tf.max_value());
  f.clear_start_time();
  f.clear_end_time();
  EXPECT_NEAR(sampled_max(TimeFunction(f)), TimeFunction(f).max_value(), 1e-6);
  EXPECT_DOUBLE_EQ(tg.max_value(), 2.0);
  EXPECT_NEAR(sampled_max(tg), tg.max_value(), 1e-9);  // the crest at t = 1, sampled near it
  EXPECT_DOUBLE_EQ(tk.max_value(), 5.0);
  v1::TimeFunction n;
  google::protobuf::TextFormat::ParseFromString("constant: -1 start_time: 1", &n);
  EXPECT_DOUBLE_EQ(TimeFunction(n).max_value(), 0.0);
  EXPECT_DOUBLE_EQ(sampled_max(TimeFunction(n)), 0.0);
  n.clear_start_time();
  EXPECT_DOUBLE_EQ(TimeFunction(n).max_value(), -1.0);
}

TEST(Motion, RotationAboutMovingCentre) {
  v1::Motion m;
  google::protobuf::TextFormat::ParseFromString(
      "velocity_x { constant: 1 } angular_velocity { constant: 2 } center { x: 1 y: 0 }", &m);
  const MotionPath path(m, 2);
  const Point3 x0(2, 0, 0);
  const double t = 0.3;
  const Point3 x = path.position(x0, t);
  EXPECT_NEAR(x.x(), 1 + t + std::cos(2 * t), 1e-14);
  EXPECT_NEAR(x.y(), std::sin(2 * t), 1e-14);
  const Point3 v = path.velocity(x0, t);
  EXPECT_NEAR(v.x(), 1 - 2 * std::sin(2 * t), 1e-14);
  EXPECT_NEAR(v.y(), 2 * std::cos(2 * t), 1e-14);
  const Point3 a = path.acceleration(x0, t);  // centripetal 4 r towards the centre
  EXPECT_NEAR(a.x(), -4 * std::cos(2 * t), 1e-13);
  EXPECT_NEAR(a.y(), -4 * std::sin(2 * t), 1e-13);
}

// A pose evaluated once serves every wall particle of a step: its positions must be those of
// the formula the walls moved by before, the rotation applied by Eigen's angle-axis product
// (velocity and acceleration are checked against the analytic motion above).
TEST(Motion, PoseOfOneTimeMatchesThePointwiseFormulaToTheBit) {
  v1::Motion m;
  google::protobuf::TextFormat::ParseFromString(
      "velocity_x { sine { amplitude: 0.3 angular_frequency: 1.5 phase: 0.2 } } "
      "velocity_y { constant: -0.1 } angular_velocity { sine { amplitude: 2 angular_frequency: 3 "
      "} } center { x: 0.4 y: -0.2 z: 0.1 } axis { x: 0.3 y: -1 z: 2 }",
      &m);
  const MotionPath path(m, 3);
  const Point3 c0 = path.center(0.0);
  for (double t : {0.0, 0.37, 2.9}) {
    const MotionPath::Pose pose = path.pose(t);
    for (const Point3& x0 : {Point3(2, 0, 0), Point3(-0.3, 0.7, 1.1), Point3(1e-3, 5, -2)}) {
      const Point3 expect =
          path.center(t) + Eigen::AngleAxisd(path.angle(t), path.axis()) * (x0 - c0);
      EXPECT_EQ(pose.position(x0), expect) << t;
    }
  }
}

}  // namespace
}  // namespace sph
