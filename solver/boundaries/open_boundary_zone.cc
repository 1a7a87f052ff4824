#include "solver/boundaries/open_boundary_zone.h"

#include <memory>
#include <numbers>

#include "case/estimate.h"
#include "case/geometry.h"

namespace sph {

template <int D>
OpenBoundaryZone<D>::OpenBoundaryZone(const v1::Case& c, int index, std::uint16_t material,
                                      double rho0)
    : material_(material), rho0_(rho0) {
  const v1::OpenBoundary& ob = c.open_boundaries(index);
  name_ = ob.name();
  inflow_ = ob.kind() == v1::INFLOW;
  prescribed_ = inflow_ || ob.has_mean_velocity();
  pressure_ = ob.has_pressure() ? ob.pressure() : 0.0;
  backflow_ = ob.backflow_stabilization();
  temperature_ = ob.has_temperature() ? ob.temperature() : c.thermal().initial_temperature();
  concentration_ =
      ob.has_concentration() ? ob.concentration() : c.diffusion().initial_concentration();
  start_ = ob.start_time();
  ramp_time_ = ob.ramp_time();
  dx_ = c.dx();
  const Point3 dir = to_point(ob.direction());
  const Point3 lo = to_point(ob.region().lo()), hi = to_point(ob.region().hi()),
               origin = to_point(c.lattice_origin());
  for (int a = 0; a < D; ++a) {
    lo_[a] = lo[a];
    hi_[a] = hi[a];
    origin_[a] = origin[a];
    if (dir[a] != 0.0) axis_ = a;  // validated: exactly one non-zero component
  }
  sign_ = dir[axis_] > 0 ? 1.0 : -1.0;
  n_[axis_] = sign_;
  length_ = hi_[axis_] - lo_[axis_];
  // Faces in xi = x . n: an inflow enters the fluid through its downstream face, an outflow
  // takes fluid in through its upstream face.
  const double up = sign_ > 0 ? lo_[axis_] : -hi_[axis_];
  const double down = sign_ > 0 ? hi_[axis_] : -lo_[axis_];
  inner_ = inflow_ ? down : up;
  outer_ = inflow_ ? up : down;

  // Lanes: lattice points origin + (i + 1/2) dx strictly inside the box across the flow, as
  // the lattice fill places them.
  std::size_t lanes = 1;
  for (int a = 0; a < D; ++a) {
    if (a == axis_) {
      count_[a] = 1;
      continue;
    }
    const double flo = (lo_[a] - origin_[a]) / dx_ - 0.5, fhi = (hi_[a] - origin_[a]) / dx_ - 0.5;
    first_[a] = static_cast<int>(std::floor(flo)) + 1;
    count_[a] = std::max(1, static_cast<int>(std::ceil(fhi)) - 1 - first_[a] + 1);
    lanes *= static_cast<std::size_t>(count_[a]);
  }
  // Lanes inside a wall hold no buffer particles and carry no flux.
  const double shell = default_shell_thickness(c);
  std::vector<std::unique_ptr<Shape>> walls;
  for (const auto& w : c.walls()) walls.push_back(compile_shape(w.shape(), D, shell));
  const double mid = 0.5 * (lo_[axis_] + hi_[axis_]);
  // Sample points lie r_c inside the fluid: their kernel support reaches the face but not the
  // buffer. At the face itself the mean would half be made by the buffer's own state, and a
  // pressure outlet's velocity would then feed back on itself (docs/effects.md, "Design
  // measurements").
  const double sample_depth = kernel_support_radius(c);
  std::vector<double> shape(lanes, 0.0);
  std::vector<bool> open(lanes, true);
  samples_.resize(lanes);
  double sum = 0;
  std::size_t used = 0;
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    Vec<D> x = Vec<D>::Zero();
    double phi = 1.0;
    std::size_t rest = lane;
    for (int a = 0; a < D; ++a) {
      if (a == axis_) continue;
      const int i = first_[a] + static_cast<int>(rest % static_cast<std::size_t>(count_[a]));
      rest /= static_cast<std::size_t>(count_[a]);
      x[a] = origin_[a] + (i + 0.5) * dx_;
      if (ob.profile() == v1::PARABOLIC) {
        const double w = hi_[a] - lo_[a], s = x[a] - lo_[a];
        phi *= 4.0 * s * (w - s) / (w * w);
      }
    }
    x[axis_] = sign_ * (inner_ + (inflow_ ? sample_depth : -sample_depth));
    samples_[lane] = x;
    Point3 p = Point3::Zero();
    for (int a = 0; a < D; ++a) p[a] = a == axis_ ? mid : x[a];
    for (const auto& w : walls) open[lane] = open[lane] && !w->contains(p);
    shape[lane] = phi;
    if (open[lane]) {
      sum += phi;
      ++used;
    }
  }
  const double u = ob.has_mean_velocity() ? ob.mean_velocity() : 0.0;
  const double mean = used > 0 ? sum / static_cast<double>(used) : 1.0;
  lane_speed_.resize(lanes);
  for (std::size_t lane = 0; lane < lanes; ++lane)
    lane_speed_[lane] = open[lane] && mean > 0 ? u * shape[lane] / mean : 0.0;
}

template <int D>
double OpenBoundaryZone<D>::ramp(double t) const {
  if (t < start_) return 0.0;
  if (ramp_time_ <= 0 || t >= start_ + ramp_time_) return 1.0;
  return 0.5 * (1.0 - std::cos(std::numbers::pi * (t - start_) / ramp_time_));
}

template class OpenBoundaryZone<2>;
template class OpenBoundaryZone<3>;

}  // namespace sph
