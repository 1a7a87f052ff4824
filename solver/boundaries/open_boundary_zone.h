#pragma once
// The geometry and prescribed flow of one open boundary's buffer zone (case.proto
// OpenBoundary): an axis-aligned box, the flow direction n = +-e_axis, the face next to the
// fluid (the inlet or outlet plane), and the lanes of the buffer: the transverse lattice
// positions inside the box. Buffer particles keep their transverse position (they move along
// n only), so each lane is a row of particles spaced dx; the lanes carry the velocity
// profile, and each lane has one sample point r_c inside the fluid, across the inner face,
// where the fluid's state is read (zero normal gradient, see open_boundaries.h).
//
// The profile is normalised over the lanes that are not inside a wall, so that the discrete
// mass flux rho0 dx^(d-1) sum_lanes u_lane equals rho0 U A exactly, with A = lanes dx^(d-1)
// (the box's cross-section when its transverse faces lie on lattice cell faces). For a
// parabola on 20 lanes the plain midpoint sum would be 0.125% high.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "solver/core/types.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class OpenBoundaryZone {
 public:
  // Builds zone `index` of a validated case. `material` is the resolved material index.
  OpenBoundaryZone(const v1::Case& c, int index, std::uint16_t material, double rho0);

  const std::string& name() const { return name_; }
  bool inflow() const { return inflow_; }
  // Velocity prescribed (inflows and velocity outlets); otherwise a pressure outlet.
  bool prescribed() const { return prescribed_; }
  std::uint16_t material() const { return material_; }
  double rho0() const { return rho0_; }
  double outlet_pressure() const { return pressure_; }
  // Pressure outlets: beta of OpenBoundary.backflow_stabilization (0: off).
  double backflow_stabilization() const { return backflow_; }
  double temperature() const { return temperature_; }
  double concentration() const { return concentration_; }
  int axis() const { return axis_; }
  const Vec<D>& normal() const { return n_; }
  // Buffer length along n (a whole number of dx).
  double length() const { return length_; }
  double dx() const { return dx_; }

  // Coordinate along the flow, xi = x . n.
  double xi(const Vec<D>& x) const { return sign_ * x[axis_]; }
  // xi of the face next to the fluid: the downstream face of an inflow, the upstream face of
  // an outflow. And of the far face: upstream of an inflow, downstream of an outflow.
  double inner_xi() const { return inner_; }
  double outer_xi() const { return outer_; }
  // Inside the box across the flow (transverse axes only, faces included).
  bool across(const Vec<D>& x) const {
    for (int a = 0; a < D; ++a)
      if (a != axis_ && (x[a] < lo_[a] || x[a] > hi_[a])) return false;
    return true;
  }

  // Lanes: lane_count() sample points r_c from the inner face in the fluid, one per
  // transverse lattice position.
  std::size_t lane_count() const { return samples_.size(); }
  const Vec<D>& sample_point(std::size_t lane) const { return samples_[lane]; }
  // The lane whose lattice cell holds x across the flow (clamped into the box).
  std::size_t lane_of(const Vec<D>& x) const {
    std::size_t lane = 0, stride = 1;
    for (int a = 0; a < D; ++a) {
      if (a == axis_) continue;
      int i = static_cast<int>(std::floor((x[a] - origin_[a]) / dx_)) - first_[a];
      i = std::clamp(i, 0, count_[a] - 1);
      lane += static_cast<std::size_t>(i) * stride;
      stride *= static_cast<std::size_t>(count_[a]);
    }
    return lane;
  }

  // Prescribed speed along n of a lane at time t (profile times ramp).
  double speed(std::size_t lane, double t) const { return lane_speed_[lane] * ramp(t); }
  // 0 before start_time, (1 - cos(pi s))/2 with s = (t - start)/ramp_time during the ramp
  // (smooth: no acceleration jump at its end), 1 after.
  double ramp(double t) const;

 private:
  std::string name_;
  bool inflow_ = true, prescribed_ = true;
  std::uint16_t material_ = 0;
  double rho0_ = 1, pressure_ = 0, backflow_ = 0, temperature_ = 0, concentration_ = 0;
  int axis_ = 0;
  double sign_ = 1;
  Vec<D> n_ = Vec<D>::Zero(), lo_ = Vec<D>::Zero(), hi_ = Vec<D>::Zero(), origin_ = Vec<D>::Zero();
  double dx_ = 1, length_ = 0, inner_ = 0, outer_ = 0;
  double start_ = 0, ramp_time_ = 0;
  std::array<int, D> first_{}, count_{};  // transverse lattice index range of the lanes
  std::vector<Vec<D>> samples_;
  std::vector<double> lane_speed_;  // at full ramp
};

}  // namespace sph
