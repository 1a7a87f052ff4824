#include "case/estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "case/anisotropy.h"
#include "case/case_limits.h"
#include "case/geometry.h"
#include "case/lattice.h"
#include "case/materials.h"

namespace sph {
namespace {

// Where the regions that claim lattice points first lie (walls before rigid bodies, rigid
// bodies before elastic bodies, those before open-boundary buffers, all of them before fluids,
// as the scene builder claims them): a grid
// of bins over the clip box, each listing the claiming shapes whose bounds overlap it in
// claiming order. A point is tested against the shapes of its own bin only, so a fluid
// around a thousand grains tests the few grains near each of its points, and the cost of a
// region's test is known before it is walked.
class ClaimIndex {
 public:
  ClaimIndex(const Aabb& clip, int dim) : clip_(clip) {
    const int per_axis = dim == 2 ? 32 : 10;
    for (int a = 0; a < 3; ++a) n_[a] = a < dim && clip.hi[a] > clip.lo[a] ? per_axis : 1;
    bins_.resize(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]));
    bin_cost_.assign(bins_.size(), 0.0);
  }

  // Adds the next claiming shape (kept by the caller).
  void add(const Shape* s) {
    const int id = static_cast<int>(shapes_.size());
    shapes_.push_back({s, s->bounds()});
    const double cost = s->cost() + 1;  // its bounds are compared first
    for_each_bin(shapes_.back().bounds, [&](std::size_t b) {
      bins_[b].push_back(id);
      bin_cost_[b] += cost;
    });
  }
  int size() const { return static_cast<int>(shapes_.size()); }

  // The most work claimed() does at a point of `box` with every shape added so far.
  double max_cost(const Aabb& box) const {
    double m = 0;
    for_each_bin(box, [&](std::size_t b) { m = std::max(m, bin_cost_[b]); });
    return m;
  }

  // Whether one of the first `before` shapes added contains p (a point of the clip box).
  bool claimed(const Point3& p, int before) const {
    for (const int id : bins_[bin_of(p)]) {
      if (id >= before) break;
      const Entry& e = shapes_[static_cast<std::size_t>(id)];
      if ((p.array() >= e.bounds.lo.array()).all() && (p.array() <= e.bounds.hi.array()).all() &&
          e.shape->contains(p))
        return true;
    }
    return false;
  }

 private:
  struct Entry {
    const Shape* shape;
    Aabb bounds;
  };
  int cell(double v, int a) const {
    const double w = clip_.hi[a] - clip_.lo[a];
    if (!(w > 0)) return 0;
    const double f = std::floor((v - clip_.lo[a]) / w * n_[a]);
    return static_cast<int>(std::clamp(f, 0.0, static_cast<double>(n_[a] - 1)));
  }
  std::size_t bin_of(const Point3& p) const {
    return static_cast<std::size_t>((cell(p.z(), 2) * n_[1] + cell(p.y(), 1)) * n_[0] +
                                    cell(p.x(), 0));
  }
  template <class Fn>
  void for_each_bin(const Aabb& box, Fn&& fn) const {
    const Aabb b = box.intersected(clip_);
    for (int a = 0; a < 3; ++a)
      if (n_[a] > 1 && b.hi[a] < b.lo[a]) return;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = n_[a] > 1 ? cell(b.lo[a], a) : 0;
      hi[a] = n_[a] > 1 ? cell(b.hi[a], a) : 0;
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          fn(static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x));
  }

  Aabb clip_;
  int n_[3] = {1, 1, 1};
  std::vector<Entry> shapes_;
  std::vector<std::vector<int>> bins_;  // ids in the order added
  std::vector<double> bin_cost_;        // cost of testing every shape of the bin
};

// A shape minus the lattice points of the first `before` claiming shapes.
class Claimed final : public Shape {
 public:
  Claimed(const Shape& s, const ClaimIndex& index, int before, double cost)
      : s_(s), index_(index), before_(before), cost_(cost) {}
  double distance(const Point3& p) const override {
    const double d = s_.distance(p);
    if (d >= 0 || before_ == 0) return d;
    return index_.claimed(p, before_) ? 1.0 : d;
  }
  Aabb bounds() const override { return s_.bounds(); }
  double cost() const override { return cost_; }
  const std::vector<Point3>* explicit_points() const override { return s_.explicit_points(); }

 private:
  const Shape& s_;
  const ClaimIndex& index_;
  int before_;
  double cost_;
};

enum RegionKind { kWallRegion, kBodyRegion, kElasticRegion, kBufferRegion, kFluidRegion };

struct Region {
  std::unique_ptr<Shape> shape;
  RegionKind kind;
  int claimed_by = 0;                // the claiming shapes before it
  double cost = 0;                   // of one test at a lattice point, claims included
  double need = 0;                   // work to test every lattice point
  LatticeSpec spec = LatticeSpec{};  // its lattice (an anisotropic elastic body's is stretched)
  bool anisotropic = false;
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

v1::PairKernelStorage pair_kernel_storage(const v1::Case& c) {
  if (c.pair_kernel_storage() != v1::PAIR_KERNEL_STORAGE_UNSPECIFIED)
    return c.pair_kernel_storage();
  return c.fluid_model().has_riemann_dissipation() ? v1::PAIR_KERNEL_TABLE
                                                   : v1::PAIR_KERNEL_COMPACT;
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
  // The lists reach the search radius: the longest semi-axis of an anisotropic body's support.
  const double rc_over_dx = search_radius(c) / dx;
  const double shell = default_shell_thickness(c);
  LatticeSpec spec{d, dx, to_point(c.lattice_origin())};
  Aabb clip{to_point(c.domain().lo()), to_point(c.domain().hi())};
  if (d == 2) clip.lo.z() = clip.hi.z() = 0.0;

  // The regions in claiming order, and what testing each of them costs: claims are made by
  // the kinds before a region's own (walls by none; bodies do not claim from bodies, nor
  // fluids from fluids).
  std::vector<Region> regions;
  for (const auto& w : c.walls())
    regions.push_back({compile_shape(w.shape(), d, shell), kWallRegion});
  for (const auto& b : c.bodies())
    regions.push_back({compile_shape(b.shape(), d, shell), kBodyRegion});
  for (const auto& b : c.elastic_bodies()) {
    regions.push_back({compile_shape(b.shape(), d, shell), kElasticRegion});
    regions.back().spec = elastic_lattice_spec(c, b);
    regions.back().anisotropic = is_anisotropic(b);
  }
  for (const auto& o : c.open_boundaries()) {
    v1::Shape box;
    *box.mutable_box() = o.region();
    regions.push_back({compile_shape(box, d, shell), kBufferRegion});
  }
  for (const auto& f : c.fluids())
    regions.push_back({compile_shape(f.shape(), d, shell), kFluidRegion});
  for (Region& r : regions)
    if (!r.anisotropic) r.spec = spec;
  ClaimIndex index(clip, d);
  for (std::size_t i = 0; i < regions.size();) {
    std::size_t end = i;
    while (end < regions.size() && regions[end].kind == regions[i].kind) ++end;
    for (std::size_t k = i; k < end; ++k) {
      Region& r = regions[k];
      r.claimed_by = index.size();
      r.cost = r.shape->cost() +
               (r.claimed_by > 0 ? index.max_cost(r.shape->bounds().intersected(clip)) : 0.0);
      r.need = walk_work(Claimed(*r.shape, index, r.claimed_by, r.cost), r.spec, clip);
    }
    if (regions[i].kind != kFluidRegion)
      for (std::size_t k = i; k < end; ++k) index.add(regions[k].shape.get());
    i = end;
  }
  std::vector<double> needs;
  for (const auto& r : regions) needs.push_back(r.need);
  const std::vector<double> share = share_work(needs, kEstimateWork);
  // Particles of anisotropic bodies, each weighted by how much fewer lattice neighbours its
  // stretched lattice puts within the search radius than dx spacing would.
  double sparse_listed = 0;
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const Region& r = regions[k];
    double n = 0;
    if (share[k] >= r.cost + kLatticePointWork || r.need == 0) {
      n = count_lattice_points(Claimed(*r.shape, index, r.claimed_by, r.cost), r.spec, clip,
                               share[k]);
    } else if (share[k] >= r.shape->cost() + kLatticePointWork) {
      // Too little for the claims (a thousand regions over one huge polygon): the region alone.
      n = count_lattice_points(*r.shape, r.spec, clip, share[k]);
    } else {
      // Not even one test: every lattice point of its bounds.
      n = lattice_points_in(r.shape->bounds().intersected(clip), r.spec);
    }
    if (r.kind == kElasticRegion && r.anisotropic) {
      // Its lattice cells are stretch[a] dx long along the surface: the search sphere holds
      // that many times fewer of them (and fewer still where the thickness cuts it off).
      double cell = 1;
      for (int a = 0; a < d; ++a) cell *= r.spec.stretch[a];
      sparse_listed += n * (1.0 - 1.0 / cell);
    }
    if (r.kind == kElasticRegion)
      // What the body would take resolved isotropically (docs/asph.md: what ASPH saves).
      e.elastic_isotropic_particles +=
          r.anisotropic ? count_lattice_points(Claimed(*r.shape, index, r.claimed_by, r.cost), spec,
                                               clip, share[k])
                        : n;
    (r.kind == kWallRegion      ? e.wall_particles
     : r.kind == kBodyRegion    ? e.rigid_particles
     : r.kind == kElasticRegion ? e.elastic_particles
                                : e.fluid_particles) += n;
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
  const std::vector<MaterialParams> materials = resolve_materials(c);
  for (const auto& m : materials) {
    if (!m.fluid) continue;
    limit(f * 0.25 * h / m.c, "acoustic CFL 0.25 h/c");
    double nu = m.nu();
    // Artificial viscosity acts like nu = alpha h c / (2(d+2)) (Adami 2012 eq. 12).
    nu = std::max(nu, c.fluid_model().artificial_viscosity() * h * m.c / (2.0 * (d + 2)));
    if (nu > 0) limit(f * 0.125 * h * h / nu, "viscous 0.125 h^2/nu");
  }
  // An elastic body's material at rest: thesis eq. (33) without its velocity and acceleration
  // terms, 0.6 h / c_s with the bulk sound speed c_s = sqrt(K / rho0), K = E / (3 (1 - 2 nu)).
  for (const auto& eb : c.elastic_bodies()) {
    const int k = material_index(materials, eb.material());
    if (k < 0) continue;
    const MaterialParams& m = materials[static_cast<std::size_t>(k)];
    limit(f * 0.6 * h / std::sqrt(m.bulk_modulus() / m.rho0), "elastic 0.6 h/c_s");
  }
  Point3 b = to_point(c.body_force());
  if (c.has_gravity()) b += to_point(c.gravity().acceleration());
  if (b.norm() > 0) limit(f * 0.25 * std::sqrt(h / b.norm()), "body force 0.25 sqrt(h/|b|)");
  if (c.time().has_quasi_static() && fixed_time_step(c) > 0) {
    if (std::isfinite(dt)) e.inner_steps = std::ceil(c.time().end_time() / dt);
    dt = fixed_time_step(c);
    e.dt_limited_by = "time.quasi_static.load_step";
  } else if (c.time().fixed_dt() > 0) {
    dt = c.time().fixed_dt();
    e.dt_limited_by = "time.fixed_dt";
  }
  e.initial_dt = std::isfinite(dt) ? dt : 0.0;
  if (e.initial_dt > 0) e.steps = std::ceil(c.time().end_time() / e.initial_dt);
  if (c.time().max_steps() > 0)
    e.steps = std::min(e.steps, static_cast<double>(c.time().max_steps()));

  // Storage: particle columns (~40 doubles in 3D) plus a neighbour index per pair and, with
  // the pair kernel table, W and dW / r per pair in single precision (compact, the default)
  // or r, W and dW in double (PAIR_KERNEL_TABLE); about 15% ghost copies.
  const double k = rc_over_dx;
  const double neighbours =
      d == 2 ? std::numbers::pi * k * k : 4.0 / 3.0 * std::numbers::pi * k * k * k;
  // With a Verlet skin the candidates within r_c + skin are kept as well as the lists, each
  // sized for its pairs with 25% spare (4 bytes an index).
  const double skin = neighbor_skin(c);
  const double per_index =
      4.0 * 1.25 * (skin > 0 ? 1.0 + std::pow(1.0 + skin / kernel_support_radius(c), d) : 1.0);
  const v1::PairKernelStorage storage = pair_kernel_storage(c);
  const double per_value = storage == v1::PAIR_KERNEL_STREAM  ? 0.0
                           : storage == v1::PAIR_KERNEL_TABLE ? 24.0
                                                              : 8.0;
  const double per_pair = per_index + 1.25 * per_value;
  // Elastic bodies (solver/elastic/) add their columns (reference position, deformation
  // gradient, P B, displacement, ...: about 140 bytes in 2D, 240 in 3D) and their reference
  // pairs, an index and V0 grad0 W each (24 or 32 bytes) for the neighbours within the
  // kernel's support (as many on an anisotropic lattice: the ellipse is stretched as the
  // lattice is), kept in a vector grown by doubling (half spare on average).
  const double ks = kernel_support_radius(c) / dx;
  const double reference_pairs =
      d == 2 ? std::numbers::pi * ks * ks : 4.0 / 3.0 * std::numbers::pi * ks * ks * ks;
  const double per_elastic =
      (d == 2 ? 140.0 : 240.0) + 1.5 * (d == 2 ? 24.0 : 32.0) * reference_pairs;
  e.bytes = 1.15 * (e.total() * (d == 2 ? 200.0 : 280.0) +
                    (e.total() - sparse_listed) * per_pair * neighbours +
                    e.elastic_particles * per_elastic);
  return e;
}

double fixed_time_step(const v1::Case& c) {
  if (c.time().has_quasi_static()) return c.time().quasi_static().load_step();
  return c.time().fixed_dt();
}

}  // namespace sph
