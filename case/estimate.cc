#include "case/estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "case/geometry.h"
#include "case/lattice.h"
#include "case/materials.h"

namespace sph {
namespace {

// A shape minus the regions claimed before it (walls claim lattice points before bodies,
// bodies before fluids), as the scene builder does.
class Claimed final : public Shape {
 public:
  Claimed(const Shape& s, const std::vector<const Shape*>& before) : s_(s), before_(before) {}
  double distance(const Point3& p) const override {
    double d = s_.distance(p);
    if (d >= 0) return d;
    for (const Shape* b : before_)
      if (b->contains(p)) return 1.0;
    return d;
  }
  Aabb bounds() const override { return s_.bounds(); }
  const std::vector<Point3>* explicit_points() const override { return s_.explicit_points(); }

 private:
  const Shape& s_;
  const std::vector<const Shape*>& before_;
};

}  // namespace

double kernel_support_factor(const v1::Case& c) {
  return c.kernel() == v1::WENDLAND_C2 ? 2.0 : 3.0;
}

double smoothing_length(const v1::Case& c) {
  return (c.has_smoothing_length_ratio() ? c.smoothing_length_ratio() : 1.0) * c.dx();
}

double kernel_support_radius(const v1::Case& c) {
  return kernel_support_factor(c) * smoothing_length(c);
}

double neighbor_skin(const v1::Case& c) {
  if (c.open_boundaries_size() > 0) return 0.0;
  double skin = (c.has_neighbor_skin() ? c.neighbor_skin() : 0.3) * c.dx();
  const auto& lo = c.domain().lo();
  const auto& hi = c.domain().hi();
  const double length[3] = {hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z()};
  const bool periodic[3] = {c.periodic_x(), c.periodic_y(), c.periodic_z()};
  for (int a = 0; a < c.dimension(); ++a)
    if (periodic[a]) skin = std::min(skin, 0.5 * length[a] - kernel_support_radius(c));
  return std::max(skin, 0.0);
}

double default_shell_thickness(const v1::Case& c) {
  return std::ceil(kernel_support_radius(c) / c.dx() - 1e-9) * c.dx();
}

CaseEstimate estimate_case(const v1::Case& c) {
  CaseEstimate e;
  const int d = c.dimension();
  const double dx = c.dx();
  const double rc_over_dx = kernel_support_radius(c) / dx;
  const double shell = default_shell_thickness(c);
  LatticeSpec spec{d, dx, to_point(c.lattice_origin())};
  Aabb clip{to_point(c.domain().lo()), to_point(c.domain().hi())};
  if (d == 2) clip.lo.z() = clip.hi.z() = 0.0;

  std::vector<std::unique_ptr<Shape>> owned;
  std::vector<const Shape*> claimed;
  for (const auto& w : c.walls()) {
    owned.push_back(compile_shape(w.shape(), d, shell));
    e.wall_particles += count_lattice_points(*owned.back(), spec, clip);
  }
  for (auto& s : owned) claimed.push_back(s.get());
  for (const auto& b : c.bodies()) {
    auto s = compile_shape(b.shape(), d, shell);
    e.rigid_particles += count_lattice_points(Claimed(*s, claimed), spec, clip);
    owned.push_back(std::move(s));
  }
  claimed.clear();
  for (auto& s : owned) claimed.push_back(s.get());
  // Buffers of open boundaries are fluid particles; they claim their region from the fluids.
  std::vector<std::unique_ptr<Shape>> buffers;
  for (const auto& o : c.open_boundaries()) {
    v1::Shape box;
    *box.mutable_box() = o.region();
    buffers.push_back(compile_shape(box, d, shell));
    e.fluid_particles += count_lattice_points(Claimed(*buffers.back(), claimed), spec, clip);
  }
  for (auto& b : buffers) claimed.push_back(b.get());
  for (const auto& f : c.fluids()) {
    auto s = compile_shape(f.shape(), d, shell);
    e.fluid_particles += count_lattice_points(Claimed(*s, claimed), spec, clip);
  }

  // Fuchs 2021 eq. (41) at rest (|u_max| = 0).
  const double h = smoothing_length(c);
  const double f = c.time().has_cfl_factor() ? c.time().cfl_factor() : 1.0;
  double dt = std::numeric_limits<double>::infinity();
  auto limit = [&](double v, const char* why) {
    if (v > 0 && std::isfinite(v) && v < dt) {
      dt = v;
      e.dt_limited_by = why;
    }
  };
  for (const auto& m : resolve_materials(c)) {
    if (!m.fluid) continue;
    limit(f * 0.25 * h / m.c, "acoustic CFL 0.25 h/c");
    double nu = m.nu();
    // Artificial viscosity acts like nu = alpha h c / (2(d+2)) (Adami 2012 eq. 12).
    nu = std::max(nu, c.fluid_model().artificial_viscosity() * h * m.c / (2.0 * (d + 2)));
    if (nu > 0) limit(f * 0.125 * h * h / nu, "viscous 0.125 h^2/nu");
  }
  Point3 b = to_point(c.body_force());
  if (c.has_gravity()) b += to_point(c.gravity().acceleration());
  if (b.norm() > 0) limit(f * 0.25 * std::sqrt(h / b.norm()), "body force 0.25 sqrt(h/|b|)");
  if (c.time().fixed_dt() > 0) {
    dt = c.time().fixed_dt();
    e.dt_limited_by = "time.fixed_dt";
  }
  e.initial_dt = std::isfinite(dt) ? dt : 0.0;
  if (e.initial_dt > 0) e.steps = std::ceil(c.time().end_time() / e.initial_dt);
  if (c.time().max_steps() > 0)
    e.steps = std::min(e.steps, static_cast<double>(c.time().max_steps()));

  // Storage: particle columns (~40 doubles in 3D) plus a neighbour index per pair and, with
  // the pair kernel table, r, W and dW per pair; about 15% ghost copies.
  const double k = rc_over_dx;
  const double neighbours =
      d == 2 ? std::numbers::pi * k * k : 4.0 / 3.0 * std::numbers::pi * k * k * k;
  // With a Verlet skin the candidates within r_c + skin are kept as well as the lists, both
  // sized for the candidates with 25% spare (4 bytes an index).
  const double skin = neighbor_skin(c);
  const double per_index =
      skin > 0 ? 2 * 4.0 * 1.25 * std::pow(1.0 + skin / kernel_support_radius(c), d) : 4.0;
  const double per_pair =
      per_index + (c.pair_kernel_storage() == v1::PAIR_KERNEL_STREAM ? 0 : 24.0);
  const double per_particle = (d == 2 ? 200.0 : 280.0) + per_pair * neighbours;
  e.bytes = 1.15 * e.total() * per_particle;
  return e;
}

}  // namespace sph
