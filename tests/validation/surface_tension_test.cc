// Surface tension (solver/physics/surface_tension.h; Adami, Hu, Adams 2010) against analytic
// solutions, at CI sizes (docs/surface_tension.md has the finer runs):
//  - a static 2D drop in a periodic box of a second fluid: the Laplace jump p_in - p_out =
//    sigma / R, and, started from the Laplace state, the spurious currents;
//  - a square droplet relaxing to a circle, its mass exact;
//  - a drop oscillating in mode 2: its period and decay rate against the viscous normal mode
//    (surface_tension/viscous_drop_mode.h; Lamb's inviscid period printed too), from a
//    damped cosine fitted to the drop's second moments;
//  - the Laplace jump of a drop in a gas 1000 times lighter;
//  - a half drop on a wall with a static contact angle of 60 and 120 degrees (Breinlinger et
//    al. 2013): the equilibrium angle from a circle fitted to the cap;
//  - free surfaces (a drop against void, surface_tension_free_surface.h): the Laplace pressure
//    against the void's 0 and the spurious currents of a drop at rest, a square relaxing to a
//    circle, and the mode-2 period of a free drop against its viscous normal mode.
//
// Units: R = 1, rho = 1, sigma = 1 (capillary time sqrt(rho R^3 / sigma) = 1). The sound speed
// c = 10 keeps the density within 1% of rho0 under the capillary pressure sigma / R = 1
// (sigma / (R rho c^2) = 0.01) and the flow Mach number below 0.03. Both fluids carry the
// EOS background pressure 5: without it the outer fluid goes to negative pressure, the
// interface particles clump (tensile instability) and the curvature is noise (measured:
// p_in - p_out 20% low, spurious speeds 0.017 sigma/mu). The time step is the
// smallest of Fuchs 2021 eq. 41 and the capillary bound 0.25 sqrt(rho h^3 / (2 pi sigma)),
// about 1.1e-3 at h = R / 20.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "case/load.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"
#include "tests/validation/surface_tension/viscous_drop_mode.h"

namespace sph {
namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// Two fluids of density 1 and sound speed 10 in the periodic box [-half, half]^2, the drop of
// material "drop" given by `drop_shape` (plus `drop_extra`, e.g. an initial velocity field),
// the rest "outer". Dynamic viscosity mu in both (density summation: the number-density form
// of Adami 2010 suits a multi-phase flow). Both carry the EOS background pressure
// `background_pressure`, the drop `laplace_jump` more: with laplace_jump = sigma / R the drop
// starts in the Laplace state (p_in - p_out = sigma / R at rho = rho0 on both sides) instead
// of building the jump by compressing itself, which sends a pressure wave through the box.
// The outer fluid's properties where they differ from the drop's (density 1, sound speed 10,
// dynamic viscosity mu).
struct OuterFluid {
  double density = 1, sound_speed = 10;
  double mu = -1;  // < 0: the drop's
};

v1::Case two_fluid_box(double dx, double half, const std::string& drop_shape, double mu,
                       double end_time, double interval, const std::string& drop_extra = "",
                       double background_pressure = 5, double laplace_jump = 0,
                       const OuterFluid& outer = {}) {
  const std::string box = "box { lo { x: " + num(-half) + " y: " + num(-half) +
                          " } hi { x: " + num(half) + " y: " + num(half) + " } }";
  auto material = [&](const char* name, double rho, double c, double pb, double eta) {
    return std::string("materials { name: \"") + name + "\" density: " + num(rho) +
           " eos { kind: LINEAR sound_speed: " + num(c) + " background_pressure: " + num(pb) +
           " } dynamic_viscosity: " + num(eta) + " }\n";
  };
  return parse_case_text(
      "name: \"surface_tension_drop\"\n"
      "dimension: 2\n"
      "dx: " +
      num(dx) + "\ndomain { " + box.substr(6, box.size() - 8) +
      " }\n"
      "periodic_x: true\nperiodic_y: true\n" +
      material("drop", 1, 10, background_pressure + laplace_jump, mu) +
      material("outer", outer.density, outer.sound_speed, background_pressure,
               outer.mu < 0 ? mu : outer.mu) +
      "fluids { name: \"drop\" material: \"drop\" shape { " + drop_shape + " } " + drop_extra +
      " }\n"
      "fluids { name: \"outer\" material: \"outer\" shape { difference { base { " +
      box + " } subtract { " + drop_shape +
      " } } } }\n"
      "surface_tension { pairs { material_a: \"drop\" material_b: \"outer\" sigma: 1 } }\n"
      "fluid_model { density: SUMMATION }\n"
      "time { end_time: " +
      num(end_time) +
      " }\n"
      "output { interval: " +
      num(interval) + " series_interval: " + num(interval / 10) + " }\n");
}

struct DropFields {
  std::vector<double> x, y, p, speed;
  std::vector<int> material;
  double time = 0;
};

DropFields read_snapshot(const test::ResultReader& rr, int k) {
  const test::Snapshot s = rr.snapshot(k);
  const std::vector<double> mat = rr.snapshot_field(k, "material");
  DropFields f;
  f.time = s.time;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    f.x.push_back(s.position[3 * i]);
    f.y.push_back(s.position[3 * i + 1]);
    f.p.push_back(s.pressure[i]);
    f.speed.push_back(std::hypot(s.velocity[3 * i], s.velocity[3 * i + 1]));
    f.material.push_back(static_cast<int>(mat[i]));
  }
  return f;
}

// Radius of a disk with the drop's particle area, N dx^2 = pi R^2 (the lattice's ball).
double area_radius(const DropFields& f, int drop_material, double dx) {
  const auto n = std::count(f.material.begin(), f.material.end(), drop_material);
  return std::sqrt(static_cast<double>(n) * dx * dx / kPi);
}

// Mean pressure of the particles with r < r_in (inside) minus that of r > r_out (outside).
double pressure_jump(const DropFields& f, double r_in, double r_out) {
  double in = 0, out = 0;
  int n_in = 0, n_out = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    const double r = std::hypot(f.x[i], f.y[i]);
    if (r < r_in) {
      in += f.p[i];
      ++n_in;
    } else if (r > r_out) {
      out += f.p[i];
      ++n_out;
    }
  }
  return in / n_in - out / n_out;
}

// The largest fluid speed sampled at t >= from (the series diagnostics/max_speed).
double largest_speed(const test::ResultReader& rr, double from) {
  const auto t = rr.series("diagnostics/time");
  const auto vmax = rr.series("diagnostics/max_speed");
  double largest = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= from) largest = std::max(largest, vmax[k]);
  return largest;
}

// max_spurious: the bound on the largest fluid speed for t >= 2 in units of sigma / mu.
void static_drop(double dx, const char* name, const OuterFluid& outer = {},
                 double max_spurious = 1e-2) {
  // R = 20 dx. mu = 0.2 (Ohnesorge number mu / sqrt(rho sigma R) = 0.2) damps the start-up's
  // capillary and acoustic oscillations within t = 3; the box is 3 R wide. Both fluids start
  // at rho0: the jump is built by the surface tension alone.
  const double R = 1, mu = 0.2, end = 3;
  auto c = two_fluid_box(dx, 1.5 * R, "ball { radius: 1 }", mu, end, 0.05, "", 5, 0, outer);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const int drop = 0;  // materials are numbered in the case's order
  const double Rn = area_radius(read_snapshot(rr, 0), drop, dx);
  const double h = dx;  // quintic kernel, support 3 h
  // The jump averaged over the snapshots of the last third.
  double jump = 0;
  int n = 0;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const DropFields f = read_snapshot(rr, k);
    if (f.time < 1.5) continue;
    jump += pressure_jump(f, Rn - 4 * h, Rn + 4 * h);
    ++n;
  }
  jump /= n;
  const double exact = 1.0 / Rn;  // sigma / R in 2D
  const double error = std::abs(jump / exact - 1);
  const double spurious = largest_speed(rr, 2.0);
  const double scale = 1.0 / mu;  // sigma / mu
  std::printf(
      "Static drop, R/dx = %.0f (R = %.4f from the particle area), density ratio %g, %lld steps: "
      "p_in - p_out = %.5f vs sigma/R = %.5f, error %.2f%%; largest speed for t >= 2: %.3g = "
      "%.3g sigma/mu\n",
      R / dx, Rn, 1 / outer.density, static_cast<long long>(r.steps), jump, exact, 100 * error,
      spurious, spurious / scale);
  EXPECT_LT(error, 0.05);
  // Started from rest at rho0, the start-up leaves 5.3e-3 sigma/mu at t = 3 at density ratio 1
  // (SurfaceTension.StaticDropSpuriousCurrents starts from the Laplace state instead).
  EXPECT_LT(spurious / scale, max_spurious);
}

TEST(SurfaceTension, StaticDropLaplacePressureDensityRatio1) {
  static_drop(0.05, "surface_tension_static_drop");
}

TEST(SurfaceTension, StaticDropLaplacePressureDensityRatio1000) {
  // The drop (rho 1, c 10) in a gas of density 1e-3. The gas only has to hold its own small
  // pressure changes (the jump sits in the drop), so it needs no reference pressure equal to
  // the drop's (sound speed 316): c = 50 gives rho c^2 = 2.5, 2.5 times the Laplace jump, at a
  // step 5 times shorter than at ratio 1 (12 000 steps, about 20 s). The gas has the drop's
  // kinematic viscosity (dynamic 2e-4; the drop's 0.2 in the gas would bound the step by
  // 0.125 h^2 / nu = 1.6e-6). The largest speed, in the gas, is 0.24 = 0.048 sigma/mu at
  // t >= 2 (light particles near the interface); it is bounded at 0.1 sigma/mu here, the
  // issue's 1e-3 being a density-ratio-1 figure (SurfaceTension.StaticDropSpuriousCurrents).
  OuterFluid gas;
  gas.density = 1e-3;
  gas.sound_speed = 50;
  gas.mu = 0.2e-3;
  static_drop(0.05, "surface_tension_static_drop_r1000", gas, 0.1);
}

TEST(SurfaceTension, StaticDropSpuriousCurrents) {
  // The static drop (R = 20 dx, box 3 R) started in the Laplace state: the drop's EOS
  // background pressure is sigma / R above the outer fluid's, so nothing has to be compressed
  // and no pressure wave starts. Background pressure 20 (instead of 5) keeps the particles
  // more evenly spread; mu = 0.05 (Ohnesorge number 0.05). Spurious currents are the largest
  // fluid speed over 2 <= t <= 4 in units of sigma / mu, the capillary number of A10 sec. 4.1
  // (docs/surface_tension.md has the other settings measured).
  const double dx = 0.05, R = 1, mu = 0.05;
  auto c = two_fluid_box(dx, 1.5 * R, "ball { radius: 1 }", mu, 4.0, 0.5, "", 20.0, 1.0 / R);
  const std::string out = test::output_dir("surface_tension_spurious_currents");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const double spurious = largest_speed(rr, 2.0), scale = 1.0 / mu;
  std::printf(
      "Static drop from the Laplace state, R/dx = %.0f, mu = %g, %lld steps: largest speed for "
      "2 <= t <= 4: %.3g = %.3g sigma/mu (the issue asks < 1e-3)\n",
      R / dx, mu, static_cast<long long>(r.steps), spurious, spurious / scale);
  EXPECT_LT(spurious / scale, 1e-3);
}

TEST(SurfaceTension, SquareDropletRelaxesToACircle) {
  // A square of side 2 a, a = 0.8 (R_eq = 2 a / sqrt(pi) = 0.903 = 18 dx), in a periodic box
  // of 3.2 x 3.2; mu = 0.1 lets it overshoot once and settle within t = 4.
  const double dx = 0.05, a = 0.8, mu = 0.1;
  auto c =
      two_fluid_box(dx, 1.6, "box { lo { x: -0.8 y: -0.8 } hi { x: 0.8 y: 0.8 } }", mu, 4.0, 1.0);
  const std::string out = test::output_dir("surface_tension_square");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot first = rr.snapshot(0), last = rr.last();
  const std::vector<double> m0 = rr.snapshot_field(0, "material"),
                            m1 = rr.snapshot_field(rr.snapshot_count() - 1, "material");
  // Mass of each phase, summed in id order on both snapshots: exactly the same.
  auto phase_mass = [](const test::Snapshot& s, const std::vector<double>& mat, int which) {
    std::vector<std::pair<std::int64_t, double>> by_id;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == 0 && static_cast<int>(mat[i]) == which)
        by_id.push_back({s.id[i], s.mass[i]});
    std::sort(by_id.begin(), by_id.end());
    double sum = 0;
    for (const auto& [id, mass] : by_id) sum += mass;
    return sum;
  };
  EXPECT_EQ(phase_mass(first, m0, 0), phase_mass(last, m1, 0));
  EXPECT_EQ(phase_mass(first, m0, 1), phase_mass(last, m1, 1));
  // The drop's boundary: its particles with a particle of the other fluid within 1.5 dx.
  // Their distances from the drop's centroid should all be the same within one dx.
  const DropFields f = read_snapshot(rr, rr.snapshot_count() - 1);
  double cx = 0, cy = 0;
  int n = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    if (f.material[i] == 0) {
      cx += f.x[i];
      cy += f.y[i];
      ++n;
    }
  cx /= n;
  cy /= n;
  std::vector<double> radii;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (f.material[i] != 0) continue;
    bool edge = false;
    for (std::size_t j = 0; j < f.x.size() && !edge; ++j)
      edge = f.material[j] == 1 && std::hypot(f.x[i] - f.x[j], f.y[i] - f.y[j]) < 1.5 * dx;
    if (edge) radii.push_back(std::hypot(f.x[i] - cx, f.y[i] - cy));
  }
  ASSERT_FALSE(radii.empty());
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  double mean = 0;
  for (double rr_ : radii) mean += rr_;
  mean /= static_cast<double>(radii.size());
  const double r_eq = 2 * a / std::sqrt(kPi);
  // The square's corners were at 1.41 a = 1.25 R_eq from the centre, its sides at 0.89 R_eq.
  std::printf(
      "Square droplet (side %.1f, R_eq = %.3f = %.0f dx), t = %.1f: %zu boundary particles at "
      "%.4f to %.4f from the centroid (spread %.2f dx, mean %.4f); phase masses exact\n",
      2 * a, r_eq, r_eq / dx, f.time, radii.size(), *lo, *hi, (*hi - *lo) / dx, mean);
  EXPECT_LT(*hi - *lo, dx);
  EXPECT_LT(std::abs(mean - r_eq), dx);
}

// A half drop of radius 1 on a flat no-slip wall (the floor, y < 0) in a second fluid,
// periodic in x, closed by a lid at y = 3, with the static contact angle theta_deg at the floor
// (measured through the drop; Breinlinger et al. 2013). The cap starts at 90 degrees.
v1::Case drop_on_wall(double dx, double theta_deg, double mu, double end_time) {
  const double half = 3, top = 3, wall = 4 * dx;
  const std::string drop =
      "intersection { shapes { ball { radius: 1 } } shapes { box { lo { x: -2 y: 0 } hi { x: 2 "
      "y: 2 } } } }";
  const std::string fluid_box =
      "box { lo { x: " + num(-half) + " y: 0 } hi { x: " + num(half) + " y: " + num(top) + " } }";
  auto material = [&](const char* name) {
    return std::string("materials { name: \"") + name +
           "\" density: 1 eos { kind: LINEAR sound_speed: 10 background_pressure: 5 } "
           "dynamic_viscosity: " +
           num(mu) + " }\n";
  };
  return parse_case_text(
      "name: \"surface_tension_contact_angle\"\n"
      "dimension: 2\n"
      "dx: " +
      num(dx) + "\ndomain { lo { x: " + num(-half) + " y: " + num(-wall) +
      " } hi { x: " + num(half) + " y: " + num(top + wall) +
      " } }\n"
      "periodic_x: true\n" +
      material("drop") + material("outer") + "fluids { name: \"drop\" material: \"drop\" shape { " +
      drop +
      " } }\n"
      "fluids { name: \"outer\" material: \"outer\" shape { difference { base { " +
      fluid_box + " } subtract { " + drop +
      " } } } }\n"
      "walls { name: \"floor\" shape { box { lo { x: " +
      num(-half) + " y: " + num(-wall) + " } hi { x: " + num(half) +
      " y: 0 } } } }\n"
      "walls { name: \"lid\" shape { box { lo { x: " +
      num(-half) + " y: " + num(top) + " } hi { x: " + num(half) + " y: " + num(top + wall) +
      " } } } }\n"
      "surface_tension { pairs { material_a: \"drop\" material_b: \"outer\" sigma: 1 } walls { "
      "wall: \"floor\" contact_angle: " +
      num(theta_deg) +
      " material: \"drop\" } }\n"
      "fluid_model { density: SUMMATION }\n"
      "time { end_time: " +
      num(end_time) +
      " }\n"
      "output { interval: 0.5 series_interval: 0.05 }\n");
}

struct CapAngles {
  double circle_fit = 0;   // from a circle fitted to the cap's boundary particles [degrees]
  double height_base = 0;  // from the cap's height and base width, tan(theta/2) = h/b
  double radius = 0, centre_y = 0, height = 0, half_base = 0;
};

// Algebraic circle fit (Kasa): x^2 + y^2 + D x + E y + F = 0 in least squares; {D, E, F}.
std::array<double, 3> kasa_circle_fit(const std::vector<std::pair<double, double>>& points) {
  double A[3][3] = {}, b[3] = {};
  for (const auto& [x, y] : points) {
    const double row[3] = {x, y, 1.0}, rhs = -(x * x + y * y);
    for (int i = 0; i < 3; ++i) {
      b[i] += row[i] * rhs;
      for (int j = 0; j < 3; ++j) A[i][j] += row[i] * row[j];
    }
  }
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  std::array<double, 3> sol{};
  const double d = det3(A);
  for (int c = 0; c < 3; ++c) {
    double M[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) M[i][j] = j == c ? b[i] : A[i][j];
    sol[c] = det3(M) / d;
  }
  return sol;
}

// The equilibrium angle of the drop (material 0) on the floor (y = 0).
CapAngles cap_angles(const DropFields& f, double dx) {
  // Boundary particles: drop particles with a particle of the other fluid within 1.5 dx, more
  // than 3 dx above the floor (the kernel support there overlaps the wall).
  std::vector<std::pair<double, double>> edge;
  double top = 0, left = 1e300, right = -1e300;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (f.material[i] != 0) continue;
    top = std::max(top, f.y[i]);
    if (f.y[i] < dx) {
      left = std::min(left, f.x[i]);
      right = std::max(right, f.x[i]);
    }
    if (f.y[i] < 3 * dx) continue;
    bool on_edge = false;
    for (std::size_t j = 0; j < f.x.size() && !on_edge; ++j)
      on_edge = f.material[j] == 1 && std::hypot(f.x[i] - f.x[j], f.y[i] - f.y[j]) < 1.5 * dx;
    if (on_edge) edge.push_back({f.x[i], f.y[i]});
  }
  const std::array<double, 3> sol = kasa_circle_fit(edge);
  CapAngles a;
  const double cx = -sol[0] / 2, cy = -sol[1] / 2;
  // The boundary particles sit about half a spacing inside the interface.
  a.radius = std::sqrt(cx * cx + cy * cy - sol[2]) + 0.5 * dx;
  a.centre_y = cy;
  a.circle_fit = std::acos(std::clamp(-cy / a.radius, -1.0, 1.0)) * 180 / kPi;
  // Cap height and base half-width, each particle taken to fill dx around it.
  a.height = top + 0.5 * dx;
  a.half_base = 0.5 * (right - left) + 0.5 * dx;
  a.height_base = 2 * std::atan(a.height / a.half_base) * 180 / kPi;
  return a;
}

// drop_on_wall with the floor under the drop, |x| < 2, a FIXED rigid body of a SOLID material
// ("plate") that carries the contact angle (surface_tension.bodies) instead of the wall.
v1::Case drop_on_body(double dx, double theta_deg, double mu, double end_time) {
  v1::Case c = drop_on_wall(dx, theta_deg, mu, end_time);
  const double wall = 4 * dx;
  v1::Shape plate = parse_case_text("walls { shape { box { lo { x: -2 y: " + num(-wall) +
                                    " } hi { x: 2 y: 0 } } } }")
                        .walls(0)
                        .shape();
  v1::Wall& floor = *c.mutable_walls(0);
  v1::Shape whole = floor.shape();
  *floor.mutable_shape()->mutable_difference()->mutable_base() = whole;
  *floor.mutable_shape()->mutable_difference()->add_subtract() = plate;
  v1::Material& steel = *c.add_materials();
  steel.set_name("plate");
  steel.set_phase(v1::SOLID);
  steel.set_density(1);
  v1::RigidBody& body = *c.add_bodies();
  body.set_name("plate");
  body.set_material("plate");
  body.set_motion_type(v1::FIXED);
  *body.mutable_shape() = plate;
  v1::SurfaceTension& st = *c.mutable_surface_tension();
  st.clear_walls();
  v1::SurfaceTension::SolidContactAngle& a = *st.add_bodies();
  a.set_solid_material("plate");
  a.set_contact_angle(theta_deg);
  a.set_material("drop");
  return c;
}

void contact_angle(double theta_deg, const char* name, bool on_body = false) {
  // R/dx = 15; mu = 0.2 (Ohnesorge number 0.2) damps the spreading within t = 8.
  const double dx = 1.0 / 15, mu = 0.2, end = 8;
  const v1::Case c =
      on_body ? drop_on_body(dx, theta_deg, mu, end) : drop_on_wall(dx, theta_deg, mu, end);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const DropFields f = read_snapshot(rr, rr.snapshot_count() - 1);
  const CapAngles a = cap_angles(f, dx);
  // The circular cap of the drop's area pi/2 with the prescribed angle.
  const double th = theta_deg * kPi / 180;
  const double area =
      static_cast<double>(std::count(f.material.begin(), f.material.end(), 0)) * dx * dx;
  const double R_cap = std::sqrt(area / (th - std::sin(th) * std::cos(th)));
  std::printf(
      "Drop on a %s, contact angle %.0f deg, R/dx = 15, %lld steps, t = %.1f: angle from the "
      "fitted circle %.1f deg (error %+.1f deg), from height and base %.1f deg (error %+.1f "
      "deg); cap radius %.3f (circular cap of the drop's area at the prescribed angle: %.3f)\n",
      on_body ? "rigid body" : "wall", theta_deg, static_cast<long long>(r.steps), f.time,
      a.circle_fit, a.circle_fit - theta_deg, a.height_base, a.height_base - theta_deg, a.radius,
      R_cap);
  EXPECT_LT(std::abs(a.circle_fit - theta_deg), 10.0);
}

TEST(SurfaceTension, ContactAngle60) {
  contact_angle(60, "surface_tension_contact_angle_60");
}
TEST(SurfaceTension, ContactAngle120) {
  contact_angle(120, "surface_tension_contact_angle_120");
}
// The angle of a rigid body's material (surface_tension.bodies): the same drop on a FIXED body.
TEST(SurfaceTension, ContactAngle60OnARigidBody) {
  contact_angle(60, "surface_tension_contact_angle_60_body", true);
}

// Least-squares fit of y(t) = e^{-gamma t} (p cos(omega t) + q sin(omega t)) + offset. For a
// given (omega, gamma) the model is linear in (p, q, offset) (variable projection): a grid
// over omega and gamma, then three finer grids around the best point.
struct DampedCosine {
  double omega = 0, gamma = 0, amplitude = 0, rms_residual = 0;
};

double fit_linear(const std::vector<double>& t, const std::vector<double>& y, double omega,
                  double gamma, double* coef) {
  // Normal equations of the three basis functions, solved by Cramer's rule.
  double A[3][3] = {}, b[3] = {};
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-gamma * t[k]);
    const double f[3] = {e * std::cos(omega * t[k]), e * std::sin(omega * t[k]), 1.0};
    for (int i = 0; i < 3; ++i) {
      b[i] += f[i] * y[k];
      for (int j = 0; j < 3; ++j) A[i][j] += f[i] * f[j];
    }
  }
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(A);
  for (int c = 0; c < 3; ++c) {
    double M[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) M[i][j] = j == c ? b[i] : A[i][j];
    coef[c] = det3(M) / d;
  }
  double ss = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-gamma * t[k]);
    const double r =
        e * (coef[0] * std::cos(omega * t[k]) + coef[1] * std::sin(omega * t[k])) + coef[2] - y[k];
    ss += r * r;
  }
  return ss;
}

DampedCosine fit_damped_cosine(const std::vector<double>& t, const std::vector<double>& y,
                               double omega_lo, double omega_hi, double gamma_hi) {
  double w0 = omega_lo, w1 = omega_hi, g0 = 0, g1 = gamma_hi, best_w = 0, best_g = 0;
  int nw = 400, ng = 60;
  for (int round = 0; round < 5; ++round) {
    double best = std::numeric_limits<double>::infinity(), coef[3];
    for (int i = 0; i <= nw; ++i)
      for (int j = 0; j <= ng; ++j) {
        const double w = w0 + (w1 - w0) * i / nw, g = g0 + (g1 - g0) * j / ng;
        const double ss = fit_linear(t, y, w, g, coef);
        if (ss < best) {
          best = ss;
          best_w = w;
          best_g = g;
        }
      }
    const double dw = 2 * (w1 - w0) / nw, dg = 2 * (g1 - g0) / ng;
    w0 = best_w - dw;
    w1 = best_w + dw;
    g0 = std::max(0.0, best_g - dg);
    g1 = best_g + dg;
    nw = ng = 20;
  }
  DampedCosine f;
  double coef[3];
  const double ss = fit_linear(t, y, best_w, best_g, coef);
  f.omega = best_w;
  f.gamma = best_g;
  f.amplitude = std::hypot(coef[0], coef[1]);
  f.rms_residual = std::sqrt(ss / static_cast<double>(t.size()));
  return f;
}

// Mode-2 anisotropy of the drop: the second moments of its particles about their centre of
// mass, (Ixx - Iyy) / (Ixx + Iyy).
double anisotropy(const DropFields& f, int drop_material) {
  double cx = 0, cy = 0;
  int n = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    if (f.material[i] == drop_material) {
      cx += f.x[i];
      cy += f.y[i];
      ++n;
    }
  cx /= n;
  cy /= n;
  double ixx = 0, iyy = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    if (f.material[i] == drop_material) {
      ixx += (f.x[i] - cx) * (f.x[i] - cx);
      iyy += (f.y[i] - cy) * (f.y[i] - cy);
    }
  return (ixx - iyy) / (ixx + iyy);
}

struct OscillationResult {
  double period = 0, lamb_period = 0, gamma = 0, amplitude = 0, rms = 0;
  double viscous_period = 0, viscous_gamma = 0;  // the viscous normal mode, viscous_drop_mode.h
};

// Settings of an oscillating-drop run: a drop of radius 1 in a periodic box [-half, half]^2 of
// a second fluid of the same density and viscosity mu. Started either with the mode-2 flow
// u = A (x, -y) inside (velocity_gradient A) or at rest with the shape r = 1 + eps cos 2 theta
// (shape_amplitude eps) and the Laplace jump sigma / R in the drop's background pressure.
struct DropOscillation {
  double dx = 0.1, half = 3, mu = 0.01;
  double velocity_gradient = 0, shape_amplitude = 0;
  double sound_speed = 10, background_pressure = 5, cfl_factor = 0;  // 0: the default
  double end = 11, t_fit = 0.3;
};

OscillationResult oscillating_drop(const DropOscillation& s, const char* name) {
  const std::string shape = s.shape_amplitude > 0
                                ? "polar_curve { radius: 1 amplitude: " + num(s.shape_amplitude) +
                                      " periods: 2 phase: " + num(kPi / 2) + " }"
                                : std::string("ball { radius: 1 }");
  const std::string velocity =
      s.velocity_gradient != 0
          ? "initial_velocity_field { linear { gradient_x { x: " + num(s.velocity_gradient) +
                " } gradient_y { y: " + num(-s.velocity_gradient) + " } } }"
          : std::string();
  OuterFluid outer;
  outer.sound_speed = s.sound_speed;
  v1::Case c = two_fluid_box(s.dx, s.half, shape, s.mu, s.end, 0.05, velocity,
                             s.background_pressure, s.shape_amplitude > 0 ? 1.0 : 0.0, outer);
  c.mutable_materials(0)->mutable_eos()->set_sound_speed(s.sound_speed);
  if (s.cfl_factor > 0) c.mutable_time()->set_cfl_factor(s.cfl_factor);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  std::vector<double> t, y;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const DropFields f = read_snapshot(rr, k);
    if (f.time < s.t_fit) continue;
    t.push_back(f.time);
    y.push_back(anisotropy(f, 0));
  }
  const double R = area_radius(read_snapshot(rr, 0), 0, s.dx);
  // Lamb 1932 sec. 275 for a cylinder: omega^2 = n (n^2 - 1) sigma / ((rho_in + rho_out) R^3).
  const double omega_lamb = std::sqrt(6.0 / (2.0 * R * R * R));
  const DampedCosine fit = fit_damped_cosine(t, y, 0.5 * omega_lamb, 1.5 * omega_lamb, 1.0);
  OscillationResult o;
  o.period = 2 * kPi / fit.omega;
  o.lamb_period = 2 * kPi / omega_lamb;
  o.gamma = fit.gamma;
  o.amplitude = fit.amplitude;
  o.rms = fit.rms_residual;
  const test::DropMode mode = test::viscous_cylinder_drop_mode(2, R, 1, 1, s.mu, s.mu, 1);
  o.viscous_period = 2 * kPi / mode.omega;
  o.viscous_gamma = mode.gamma;
  std::printf(
      "Oscillating drop, R/dx = %.0f (R = %.4f), box %.1f R, mu = %g, A = %g, eps = %g, c = %g, "
      "pb = %g, %lld steps, fit over %.2f <= t <= %.2f: period %.4f vs Lamb %.4f (%+.2f%%), "
      "viscous mode %.4f (%+.2f%%); decay rate %.4f vs viscous mode %.4f (%+.1f%%); anisotropy "
      "amplitude %.4f, rms residual %.2g\n",
      1 / s.dx, R, 2 * s.half, s.mu, s.velocity_gradient, s.shape_amplitude, s.sound_speed,
      s.background_pressure, static_cast<long long>(r.steps), s.t_fit, s.end, o.period,
      o.lamb_period, 100 * (o.period / o.lamb_period - 1), o.viscous_period,
      100 * (o.period / o.viscous_period - 1), o.gamma, o.viscous_gamma,
      100 * (o.gamma / o.viscous_gamma - 1), o.amplitude, o.rms);
  return o;
}

// The viscous normal mode of viscous_drop_mode.h against an independent mpmath solution of the
// same interface conditions (tests/validation/surface_tension/viscous_drop_mode.py, 30 digits),
// and its limits: Lamb's frequency without viscosity and the shear-layer asymptote
// s = i omega_0 - (1 + i) n / (2 R) sqrt(nu omega_0 / 2) for small viscosity.
TEST(SurfaceTension, ViscousDropModeTheory) {
  struct Reference {
    int n;
    double R, rho_out, mu_in, mu_out, omega, gamma;
  };
  const Reference refs[] = {
      {2, 1.0, 1, 0.01, 0.01, 1.63890559631, 0.103077427293},
      {2, 1.0, 1, 0.002, 0.002, 1.69042977687, 0.0436181759689},
      {2, 1.0029, 1, 0.01, 0.01, 1.6318694207, 0.102549135582},
      {2, 1.0, 0.5, 0.01, 0.003, 1.92505685433, 0.0849470138106},
      {3, 1.0, 1, 0.005, 0.005, 3.32442184411, 0.150814159716},
  };
  for (const Reference& r : refs) {
    const test::DropMode m =
        test::viscous_cylinder_drop_mode(r.n, r.R, 1, r.rho_out, r.mu_in, r.mu_out, 1);
    std::printf(
        "Viscous drop mode n = %d, R = %g, rho_out = %g, mu = %g / %g: omega %.11f (mpmath "
        "%.11f, %.1e), gamma %.11f (mpmath %.11f, %.1e)\n",
        r.n, r.R, r.rho_out, r.mu_in, r.mu_out, m.omega, r.omega, m.omega / r.omega - 1, m.gamma,
        r.gamma, m.gamma / r.gamma - 1);
    EXPECT_NEAR(m.omega / r.omega, 1, 1e-9);
    EXPECT_NEAR(m.gamma / r.gamma, 1, 1e-8);
  }
  const double w0 = std::sqrt(3.0);
  for (const double nu : {1e-4, 1e-5}) {
    const test::DropMode m = test::viscous_cylinder_drop_mode(2, 1, 1, 1, nu, nu, 1);
    const double layer = std::sqrt(nu * w0 / 2);
    std::printf(
        "Viscous drop mode n = 2, nu = %g: (omega_0 - omega) / layer rate %.4f, gamma / layer "
        "rate %.4f (asymptote 1, 1)\n",
        nu, (w0 - m.omega) / layer, m.gamma / layer);
    EXPECT_NEAR((w0 - m.omega) / layer, 1, 0.1);
    EXPECT_NEAR(m.gamma / layer, 1, 0.1);
  }
}

TEST(SurfaceTension, OscillatingDropMode2Period) {
  // R/dx = 10 in a periodic 6 R box, mu = 0.01 (Ohnesorge number 0.01), A = 0.2: the drop's
  // velocity is halved at once by the pressure impulse that sets the outer fluid moving (equal
  // densities), leaving a mode-2 amplitude of about 0.055 R, whose nonlinear frequency shift is
  // negligible. The reference is the drop's viscous normal mode (viscous_drop_mode.h): the
  // potential flows inside and outside slip at the interface, and the shear layer that removes
  // the slip lowers the frequency by as much as it damps the mode, n / (2 R) sqrt(nu omega / 2)
  // each for small nu; at mu = 0.01 the period is 5.7% longer than Lamb's and the decay rate
  // 0.103. Across sound speeds, background pressures, boxes and amplitudes at R/dx = 10 and 20
  // the period scatters from -1.5% to +7% about it (docs/surface_tension.md); these settings
  // give +3.3% and the decay rate within 1%.
  DropOscillation s;
  s.velocity_gradient = 0.2;
  const OscillationResult o = oscillating_drop(s, "surface_tension_oscillating_drop");
  EXPECT_LT(std::abs(o.period / o.viscous_period - 1), 0.05);
  EXPECT_LT(std::abs(o.gamma / o.viscous_gamma - 1), 0.5);
}

TEST(SurfaceTension, DISABLED_OscillatingDropMode2PeriodFine) {
  // R/dx = 20 (about 60 s); run by tests/validation/surface_tension/oscillating_drop_fine.sh.
  DropOscillation s;
  s.dx = 0.05;
  s.velocity_gradient = 0.2;
  const OscillationResult o = oscillating_drop(s, "surface_tension_oscillating_drop_fine");
  EXPECT_LT(std::abs(o.period / o.viscous_period - 1), 0.05);
}

// ---- Free surfaces: one fluid against void (surface_tension_free_surface.h) ----
//
// A drop of material "drop" (rho 1, sound speed 10, no background pressure: the void's
// pressure is 0) alone in an open 2D domain, no gravity, the continuity density (summation
// leaves the surface particles at about half of rho0, a pressure of -c^2 rho0 / 2 there).

// laplace_start: the EOS background pressure, sigma / R to start a drop of radius R in the
// Laplace state (p = sigma / R at rho0) instead of building it by compressing the drop.
v1::Case free_drop(double dx, const std::string& shape, double mu, double end_time, double interval,
                   const std::string& extra = "", double laplace_start = 0) {
  return parse_case_text(
      "name: \"free_drop\"\n"
      "dimension: 2\n"
      "dx: " +
      num(dx) +
      "\ndomain { lo { x: -3 y: -3 } hi { x: 3 y: 3 } }\n"
      "materials { name: \"drop\" density: 1 eos { kind: LINEAR sound_speed: 10 "
      "background_pressure: " +
      num(laplace_start) +
      " } "
      "dynamic_viscosity: " +
      num(mu) +
      " }\n"
      "fluids { name: \"drop\" material: \"drop\" shape { " +
      shape + " } " + extra +
      " }\n"
      "surface_tension { pairs { material_a: \"drop\" sigma: 1 } }\n"
      "fluid_model { density: CONTINUITY }\n"
      "time { end_time: " +
      num(end_time) +
      " }\n"
      "output { interval: " +
      num(interval) + " series_interval: " + num(interval / 10) + " }\n");
}

// The outermost particle of each of `sectors` equal angles about the centroid of the fluid:
// the drop's boundary, its distances from the centroid.
std::vector<double> boundary_radii(const DropFields& f, int sectors) {
  double cx = 0, cy = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    cx += f.x[i];
    cy += f.y[i];
  }
  cx /= static_cast<double>(f.x.size());
  cy /= static_cast<double>(f.x.size());
  std::vector<double> radii(static_cast<std::size_t>(sectors), 0.0);
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    const double dx = f.x[i] - cx, dy = f.y[i] - cy;
    auto k = static_cast<std::size_t>((std::atan2(dy, dx) + kPi) / (2 * kPi) * sectors);
    k = std::min(k, radii.size() - 1);
    radii[k] = std::max(radii[k], std::hypot(dx, dy));
  }
  return radii;
}

// The free drop at rest: the pressure inside against the Laplace jump sigma / R (the void's
// pressure is 0) and the spurious currents. R/dx = 20 (3 840 steps, about 5 s).
void free_static_drop(double mu, double laplace_start, double max_spurious, const char* name) {
  const double dx = 0.05, end = 3;
  auto c = free_drop(dx, "ball { radius: 1 }", mu, end, 0.05, "", laplace_start);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const double Rn = area_radius(read_snapshot(rr, 0), 0, dx), h = dx;
  // The mean pressure of the particles more than 4 h inside, averaged over t >= 1.5.
  double inside = 0;
  int n = 0;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const DropFields f = read_snapshot(rr, k);
    if (f.time < 1.5) continue;
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < f.x.size(); ++i)
      if (std::hypot(f.x[i], f.y[i]) < Rn - 4 * h) {
        sum += f.p[i];
        ++count;
      }
    inside += sum / count;
    ++n;
  }
  inside /= n;
  const double exact = 1.0 / Rn, error = std::abs(inside / exact - 1);
  const double spurious = largest_speed(rr, 2.0), scale = 1.0 / mu;
  const std::vector<double> radii = boundary_radii(read_snapshot(rr, rr.snapshot_count() - 1), 64);
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  std::printf(
      "Free drop at rest, R/dx = %.0f (R = %.4f from the particle area), mu = %g, start %s, %lld "
      "steps: p_in = %.5f vs sigma/R = %.5f (void 0), error %.2f%% (tolerance 5%%); largest "
      "speed for 2 <= t <= 3: %.3g = %.3g sigma/mu (tolerance %.3g); outermost particles of 64 "
      "sectors at %.4f to %.4f at t = %.1f\n",
      1 / dx, Rn, mu, laplace_start > 0 ? "in the Laplace state" : "at p = 0",
      static_cast<long long>(r.steps), inside, exact, 100 * error, spurious, spurious / scale,
      max_spurious, *lo, *hi, end);
  EXPECT_LT(error, 0.05);
  EXPECT_LT(spurious / scale, max_spurious);
}

TEST(SurfaceTension, FreeDropLaplacePressure) {
  // Started at p = 0, the force compresses the drop until the pressure inside is sigma / R.
  // The start sets off the drop's acoustic breathing mode (J0(k R) = 0, period 0.26) with an
  // amplitude of about sigma / R, which the SPH viscosity hardly damps (p_in still swings by
  // +-0.6 at t = 3): mu = 0.2 and the jump averaged over 30 snapshots of t >= 1.5; the
  // largest speed is that oscillation's.
  free_static_drop(0.2, 0, 2e-2, "surface_tension_free_drop");
}

TEST(SurfaceTension, FreeDropSpuriousCurrents) {
  // Started in the Laplace state (EOS background pressure sigma / R = 1), mu = 0.05 (Ohnesorge
  // number 0.05): no acoustic start-up; the pressure inside still settles where the force
  // balances it (a jump off by 1% would need a density change of 1e-4 only).
  free_static_drop(0.05, 1.0, 2.5e-3, "surface_tension_free_drop_laplace_start");
}

TEST(SurfaceTension, FreeSquareRelaxesToACircle) {
  // A square of side 2 a, a = 0.8 (R_eq = 0.903 = 18 dx), in void; mu = 0.1.
  const double dx = 0.05, a = 0.8, mu = 0.1, end = 4;
  auto c = free_drop(dx, "box { lo { x: -0.8 y: -0.8 } hi { x: 0.8 y: 0.8 } }", mu, end, 0.5);
  const std::string out = test::output_dir("surface_tension_free_square");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot first = rr.snapshot(0), last = rr.last();
  auto mass = [](const test::Snapshot& s) {
    std::vector<std::pair<std::int64_t, double>> by_id;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == 0) by_id.push_back({s.id[i], s.mass[i]});
    std::sort(by_id.begin(), by_id.end());
    double sum = 0;
    for (const auto& [id, m] : by_id) sum += m;
    return sum;
  };
  EXPECT_EQ(mass(first), mass(last));
  const DropFields f = read_snapshot(rr, rr.snapshot_count() - 1);
  // 48 sectors: about 2.4 dx of arc each at the boundary.
  const std::vector<double> radii = boundary_radii(f, 48);
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  double mean = 0;
  for (double v : radii) mean += v;
  mean /= static_cast<double>(radii.size());
  const double r_eq = 2 * a / std::sqrt(kPi);
  // The outermost particles sit half a spacing inside the interface.
  std::printf(
      "Free square (side %.1f, R_eq = %.3f = %.0f dx), %lld steps, t = %.1f: outermost particles "
      "of 48 sectors at %.4f to %.4f from the centroid (spread %.2f dx, tolerance 1 dx), mean "
      "%.4f vs R_eq - dx/2 = %.4f (%+.2f dx, tolerance 1 dx); mass exact\n",
      2 * a, r_eq, r_eq / dx, static_cast<long long>(r.steps), f.time, *lo, *hi, (*hi - *lo) / dx,
      mean, r_eq - dx / 2, (mean - (r_eq - dx / 2)) / dx);
  EXPECT_LT(*hi - *lo, dx);
  EXPECT_LT(std::abs(mean - (r_eq - dx / 2)), dx);
}

TEST(SurfaceTension, FreeDrop3DLaplacePressure) {
  // A sphere of R = 1 at R/dx = 8 in void, started in the Laplace state (background pressure
  // 2 sigma / R), mu = 0.2: the pressure inside against 2 sigma / R.
  const double dx = 0.125, mu = 0.2, end = 2;
  const v1::Case c = parse_case_text(
      "name: \"free_drop_3d\"\n"
      "dimension: 3\n"
      "dx: " +
      num(dx) +
      "\ndomain { lo { x: -2 y: -2 z: -2 } hi { x: 2 y: 2 z: 2 } }\n"
      "materials { name: \"drop\" density: 1 eos { kind: LINEAR sound_speed: 10 "
      "background_pressure: 2 } dynamic_viscosity: " +
      num(mu) +
      " }\n"
      "fluids { name: \"drop\" material: \"drop\" shape { ball { radius: 1 } } }\n"
      "surface_tension { pairs { material_a: \"drop\" sigma: 1 } }\n"
      "fluid_model { density: CONTINUITY }\n"
      "time { end_time: " +
      num(end) +
      " }\n"
      "output { interval: 0.1 series_interval: 0.01 }\n");
  const std::string out = test::output_dir("surface_tension_free_drop_3d");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot s0 = rr.snapshot(0);
  std::size_t n0 = 0;
  for (std::size_t i = 0; i < s0.size(); ++i) n0 += s0.kind[i] == 0;
  const double Rn = std::cbrt(3.0 * static_cast<double>(n0) * dx * dx * dx / (4 * kPi));
  double inside = 0;
  int n = 0;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const test::Snapshot sn = rr.snapshot(k);
    if (sn.time < 1.0) continue;
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < sn.size(); ++i) {
      const double rad = std::sqrt(sn.position[3 * i] * sn.position[3 * i] +
                                   sn.position[3 * i + 1] * sn.position[3 * i + 1] +
                                   sn.position[3 * i + 2] * sn.position[3 * i + 2]);
      if (sn.kind[i] == 0 && rad < Rn - 3 * dx) {
        sum += sn.pressure[i];
        ++count;
      }
    }
    inside += sum / count;
    ++n;
  }
  inside /= n;
  const double exact = 2.0 / Rn, error = std::abs(inside / exact - 1);
  const double spurious = largest_speed(rr, 1.0);
  std::printf(
      "Free 3D drop at rest, R/dx = 8 (R = %.4f from the particle volume), %zu particles, %lld "
      "steps: p_in = %.5f vs 2 sigma/R = %.5f, error %.2f%% (tolerance 5%%); largest speed for "
      "t >= 1: %.3g = %.3g sigma/mu\n",
      Rn, n0, static_cast<long long>(r.steps), inside, exact, 100 * error, spurious, spurious * mu);
  EXPECT_LT(error, 0.05);
}

// A free half drop of radius 1 centred at x0 on a floor (y < 0) in void, no gravity, the static
// contact angle theta_deg at the floor (surface_tension.walls with a free surface). The cap
// starts at 90 degrees, at p = 0.
v1::Case free_drop_on_floor(double dx, double theta_deg, double mu, double end_time, double x0,
                            bool free_slip) {
  const double half = 3, wall = 4 * dx;
  return parse_case_text(
      "name: \"free_drop_on_floor\"\n"
      "dimension: 2\n"
      "dx: " +
      num(dx) + "\ndomain { lo { x: " + num(-half) + " y: " + num(-wall) +
      " } hi { x: " + num(half) +
      " y: 2 } }\n"
      "materials { name: \"drop\" density: 1 eos { kind: LINEAR sound_speed: 10 } "
      "dynamic_viscosity: " +
      num(mu) +
      " }\n"
      "fluids { name: \"drop\" material: \"drop\" shape { intersection { shapes { ball { center "
      "{ x: " +
      num(x0) +
      " } radius: 1 } } shapes { box { lo { x: -2 y: 0 } hi { x: 2 y: 2 } } } } } }\n"
      "walls { name: \"floor\" shape { box { lo { x: " +
      num(-half) + " y: " + num(-wall) + " } hi { x: " + num(half) + " y: 0 } } } " +
      (free_slip ? "free_slip: true " : "") +
      "}\n"
      "surface_tension { pairs { material_a: \"drop\" sigma: 1 } walls { wall: \"floor\" "
      "contact_angle: " +
      num(theta_deg) +
      " material: \"drop\" } }\n"
      "fluid_model { density: CONTINUITY }\n"
      "time { end_time: " +
      num(end_time) +
      " }\n"
      "output { interval: 0.5 series_interval: 0.05 }\n");
}

// The angle of a free cap on the floor y = 0: a circle fitted (Kasa) to the outermost drop
// particle of each of 60 equal angles about the base's midpoint, those more than 3 dx above
// the floor, its radius moved out by half a spacing.
struct FreeCap {
  double angle = 0, radius = 0, centre_x = 0, centroid_x = 0;
};
FreeCap free_cap(const DropFields& f, double dx) {
  double left = 1e300, right = -1e300, cx = 0;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    cx += f.x[i];
    if (f.y[i] < dx) {
      left = std::min(left, f.x[i]);
      right = std::max(right, f.x[i]);
    }
  }
  cx /= static_cast<double>(f.x.size());
  const double mid = 0.5 * (left + right);
  constexpr int kSectors = 60;
  std::vector<double> far(kSectors, -1);
  std::vector<std::size_t> which(kSectors, 0);
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    const double a = std::atan2(f.y[i], f.x[i] - mid);
    if (!(a > 0 && a < kPi)) continue;
    const auto k = std::min(static_cast<int>(a / kPi * kSectors), kSectors - 1);
    const double r = std::hypot(f.x[i] - mid, f.y[i]);
    if (r > far[k]) {
      far[k] = r;
      which[k] = i;
    }
  }
  std::vector<std::pair<double, double>> outer;
  for (int k = 0; k < kSectors; ++k)
    if (far[k] >= 0 && f.y[which[k]] >= 3 * dx) outer.push_back({f.x[which[k]], f.y[which[k]]});
  const std::array<double, 3> sol = kasa_circle_fit(outer);
  FreeCap cap;
  cap.centre_x = -sol[0] / 2;
  const double cy = -sol[1] / 2;
  cap.radius = std::sqrt(cap.centre_x * cap.centre_x + cy * cy - sol[2]) + 0.5 * dx;
  cap.angle = std::acos(std::clamp(-cy / cap.radius, -1.0, 1.0)) * 180 / kPi;
  cap.centroid_x = cx;  // of all drop particles
  return cap;
}

// The free half drop on a floor with the angle theta_deg: its angle within 5 degrees, its mass
// exact, and its centroid within max_drift of where it started (the contact-line forces of the
// two sides cancel: no net force along the floor). On a free-slip floor the contact line moves
// freely; on a no-slip floor only by the first row's numerical slip, and the drop creeps
// towards angles far from 90 (docs/surface_tension.md). x0: the drop's centre; at 0.3 dx its
// particles are not placed mirror-symmetrically.
void free_contact_angle(double theta_deg, bool free_slip, double x0, double max_drift,
                        const char* name) {
  // R/dx = 15; mu = 0.2 (Ohnesorge number 0.2) damps the spreading within t = 8.
  const double dx = 1.0 / 15, mu = 0.2, end = 8;
  const v1::Case c = free_drop_on_floor(dx, theta_deg, mu, end, x0, free_slip);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const DropFields f = read_snapshot(rr, rr.snapshot_count() - 1);
  const FreeCap cap = free_cap(f, dx), start = free_cap(read_snapshot(rr, 0), dx);
  const double drift = cap.centroid_x - start.centroid_x;
  // The angle settles within t = 4 to a level about which it still swings by a few degrees:
  // its mean over the snapshots of 4 <= t <= 8 (every 0.5) is the equilibrium angle.
  std::string history;  // every 1 capillary time
  double mean = 0, lo = 180, hi = 0;
  int n = 0;
  for (int k = 1; k < rr.snapshot_count(); ++k) {
    const DropFields g = read_snapshot(rr, k);
    const double angle = free_cap(g, dx).angle;
    if (k % 2 == 0) {
      char b[32];
      std::snprintf(b, sizeof b, " %.1f", angle);
      history += b;
    }
    if (g.time < 4 - 1e-9) continue;
    mean += angle;
    lo = std::min(lo, angle);
    hi = std::max(hi, angle);
    ++n;
  }
  mean /= n;
  auto mass = [](const test::Snapshot& s) {
    double sum = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == 0) sum += s.mass[i];
    return sum;
  };
  const double th = theta_deg * kPi / 180;
  const double area = static_cast<double>(f.x.size()) * dx * dx;
  const double R_cap = std::sqrt(area / (th - std::sin(th) * std::cos(th)));
  std::printf(
      "Free drop on a %s floor, centre x0 = %.1f dx, contact angle %.0f deg, R/dx = 15, mu = %g, "
      "%lld steps: "
      "angle from the fitted circle, mean over 4 <= t <= 8: %.1f deg (error %+.1f deg, tolerance "
      "5; range %.1f to %.1f; at t = 1, 2, ..., 8:%s); cap radius at t = 8 %.3f (circular cap of "
      "the drop's area at the prescribed angle: %.3f); centroid moved %+.2g dx along the floor "
      "(tolerance %.2g dx); "
      "mass %.17g -> %.17g\n",
      free_slip ? "free-slip" : "no-slip", x0 / dx, theta_deg, mu, static_cast<long long>(r.steps),
      mean, mean - theta_deg, lo, hi, history.c_str(), cap.radius, R_cap, drift / dx,
      max_drift / dx, mass(rr.snapshot(0)), mass(rr.last()));
  EXPECT_LT(std::abs(mean - theta_deg), 5.0);
  EXPECT_LT(std::abs(drift), max_drift);
  EXPECT_EQ(mass(rr.snapshot(0)), mass(rr.last()));
}

// On a free-slip floor, the drop placed mirror-symmetrically on the lattice (off it, the drop
// slides: docs/surface_tension.md).
TEST(SurfaceTension, FreeSurfaceContactAngle60) {
  free_contact_angle(60, true, 0, 0.5 / 15, "surface_tension_free_contact_angle_60");
}
// 105 degrees, the largest validated at a free surface (120 settles at about 107, swinging
// from 100 to 140: docs/surface_tension.md).
TEST(SurfaceTension, FreeSurfaceContactAngle105) {
  free_contact_angle(105, true, 0, 0.5 / 15, "surface_tension_free_contact_angle_105");
}
// Neutral, on a no-slip floor, off the lattice's mirror line: the two contact lines pull about
// equally, the drop drifts less than one spacing.
TEST(SurfaceTension, FreeSurfaceContactAngle90NoSlipOffLattice) {
  free_contact_angle(90, false, 0.3 / 15, 1.0 / 15,
                     "surface_tension_free_contact_angle_90_no_slip");
}

// A free drop of radius 1 set oscillating in mode 2 by u = A (x, -y): the period and decay
// rate of its anisotropy against the free drop's viscous normal mode (viscous_drop_mode.h;
// Lamb's omega_0^2 = n (n^2 - 1) sigma / (rho R^3) printed too).
OscillationResult free_oscillating_drop(double dx, double mu, double A, double end,
                                        const char* name) {
  const std::string velocity = "initial_velocity_field { linear { gradient_x { x: " + num(A) +
                               " } gradient_y { y: " + num(-A) + " } } }";
  auto c = free_drop(dx, "ball { radius: 1 }", mu, end, 0.05, velocity);
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  EXPECT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  std::vector<double> t, y;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const DropFields f = read_snapshot(rr, k);
    if (f.time < 0.2) continue;
    t.push_back(f.time);
    y.push_back(anisotropy(f, 0));
  }
  const double R = area_radius(read_snapshot(rr, 0), 0, dx);
  const double omega_lamb = std::sqrt(6.0 / (R * R * R));
  const DampedCosine fit = fit_damped_cosine(t, y, 0.5 * omega_lamb, 1.5 * omega_lamb, 1.0);
  const test::DropMode mode = test::free_cylinder_drop_mode(2, R, 1, mu, 1);
  OscillationResult o;
  o.period = 2 * kPi / fit.omega;
  o.lamb_period = 2 * kPi / omega_lamb;
  o.gamma = fit.gamma;
  o.amplitude = fit.amplitude;
  o.rms = fit.rms_residual;
  o.viscous_period = 2 * kPi / mode.omega;
  o.viscous_gamma = mode.gamma;
  std::printf(
      "Free oscillating drop, R/dx = %.0f (R = %.4f), mu = %g, A = %g, %lld steps, fit over "
      "0.2 <= t <= %.1f: period %.4f vs viscous mode %.4f (%+.2f%%, Lamb %.4f); decay rate "
      "%.4f vs %.4f (%+.1f%%); anisotropy amplitude %.4f, rms residual %.2g\n",
      1 / dx, R, mu, A, static_cast<long long>(r.steps), end, o.period, o.viscous_period,
      100 * (o.period / o.viscous_period - 1), o.lamb_period, o.gamma, o.viscous_gamma,
      100 * (o.gamma / o.viscous_gamma - 1), o.amplitude, o.rms);
  return o;
}

TEST(SurfaceTension, FreeDropMode2Period) {
  // R/dx = 20, mu = 0.1 (Ohnesorge number 0.1; at 0.01 the free surface fails, see
  // docs/surface_tension.md), A = 0.2: a shape amplitude of A / omega = 0.08 R.
  const OscillationResult o =
      free_oscillating_drop(0.05, 0.1, 0.2, 8, "surface_tension_free_oscillating_drop");
  EXPECT_LT(std::abs(o.period / o.viscous_period - 1), 0.05);
  EXPECT_LT(std::abs(o.gamma / o.viscous_gamma - 1), 0.5);
}

TEST(SurfaceTension, FreeDropModeTheory) {
  // The free drop's mode against mpmath (viscous_drop_mode.py free 2 1 MU) and its
  // irrotational limits.
  struct Reference {
    double mu, omega, gamma;
  };
  for (const Reference& ref : {Reference{0.01, 2.44748322909, 0.03814781939},
                               Reference{0.05, 2.42586857980, 0.17733415627}}) {
    const test::DropMode m = test::free_cylinder_drop_mode(2, 1, 1, ref.mu, 1);
    std::printf(
        "Free drop mode n = 2, mu = %g: omega %.11f (mpmath %.11f, %.1e), gamma %.11f (mpmath "
        "%.11f, %.1e)\n",
        ref.mu, m.omega, ref.omega, m.omega / ref.omega - 1, m.gamma, ref.gamma,
        m.gamma / ref.gamma - 1);
    EXPECT_NEAR(m.omega / ref.omega, 1, 1e-9);
    EXPECT_NEAR(m.gamma / ref.gamma, 1, 1e-8);
  }
  const test::DropMode m = test::free_cylinder_drop_mode(2, 1, 1, 1e-5, 1);
  std::printf("Free drop mode n = 2, mu = 1e-5: omega / sqrt(6) - 1 = %.2e, gamma / 4 nu = %.5f\n",
              m.omega / std::sqrt(6.0) - 1, m.gamma / 4e-5);
  EXPECT_NEAR(m.omega / std::sqrt(6.0), 1, 1e-5);
  EXPECT_NEAR(m.gamma / 4e-5, 1, 0.01);
}

}  // namespace
}  // namespace sph
