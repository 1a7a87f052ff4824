#include "solver/scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_set>

#include "case/anisotropy.h"
#include "case/estimate.h"
#include "case/lattice.h"

namespace sph {

SceneBuilder::SceneBuilder(const v1::Case& c, const std::vector<MaterialParams>& materials)
    : c_(c), mats_(materials) {
  const int d = c.dimension();
  const double shell = default_shell_thickness(c);
  for (const auto& w : c.walls()) walls_.push_back(compile_shape(w.shape(), d, shell));
  for (const auto& b : c.bodies()) bodies_.push_back(compile_shape(b.shape(), d, shell));
  for (const auto& f : c.fluids()) fluids_.push_back(compile_shape(f.shape(), d, shell));
  for (const auto& e : c.elastic_bodies()) {
    elastic_.push_back(compile_shape(e.shape(), d, shell));
    constraints_.emplace_back();
    for (const auto& k : e.constraints())
      constraints_.back().push_back(compile_shape(k.region(), d, shell));
  }
  for (const auto& o : c.open_boundaries()) {
    v1::Shape box;
    *box.mutable_box() = o.region();
    opens_.push_back(compile_shape(box, d, shell));
  }
  for (const auto& m : materials)
    if (m.fluid) {
      wall_rho_ = m.rho0;
      break;
    }
}

namespace {

// The initial velocity of a fluid region or elastic body at x: uniform plus its field.
Point3 initial_velocity(const Point3& uniform, const v1::VelocityField& field, const Point3& x) {
  Point3 v = uniform;
  if (field.has_taylor_green()) {
    const auto& tg = field.taylor_green();
    const double k = 2.0 * std::numbers::pi / tg.wavelength();
    v.x() -= tg.amplitude() * std::cos(k * x.x()) * std::sin(k * x.y());
    v.y() += tg.amplitude() * std::sin(k * x.x()) * std::cos(k * x.y());
  }
  if (field.has_linear()) {
    const auto& lf = field.linear();
    const Point3 r = x - to_point(lf.center());
    v.x() += to_point(lf.gradient_x()).dot(r);
    v.y() += to_point(lf.gradient_y()).dot(r);
    v.z() += to_point(lf.gradient_z()).dot(r);
  }
  if (field.has_beam_mode()) {
    // First clamped-free bending mode of an Euler-Bernoulli beam (thesis digest sec. 8.4,
    // eq. 40), scaled to the tip velocity.
    const auto& bm = field.beam_mode();
    const Point3 axis = to_point(bm.axis()).normalized();
    const Point3 dir = to_point(bm.direction()).normalized();
    const double L = bm.length(), kL = 1.875, k = kL / L;
    const auto shape = [&](double s) {
      return (std::cos(kL) + std::cosh(kL)) * (std::cosh(k * s) - std::cos(k * s)) +
             (std::sin(kL) - std::sinh(kL)) * (std::sinh(k * s) - std::sin(k * s));
    };
    const double s = std::clamp((x - to_point(bm.root())).dot(axis), 0.0, L);
    v += bm.tip_velocity() * shape(s) / shape(L) * dir;
  }
  return v;
}

}  // namespace

void SceneBuilder::for_each(const std::function<void(const SceneParticle&)>& fn) const {
  const int d = c_.dimension();
  const double dx = c_.dx();
  const double vol = std::pow(dx, d);
  LatticeSpec spec{d, dx, to_point(c_.lattice_origin())};
  Aabb clip{to_point(c_.domain().lo()), to_point(c_.domain().hi())};
  if (d == 2) clip.lo.z() = clip.hi.z() = 0.0;

  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const auto& wall = c_.walls(static_cast<int>(w));
    SceneParticle p;
    p.kind = Kind::kWall;
    p.wall = static_cast<std::uint16_t>(w);
    p.rho = wall_rho_;
    p.mass = wall_rho_ * vol;
    if (!wall.material().empty())
      p.material = static_cast<std::uint16_t>(material_index(mats_, wall.material()));
    for_each_lattice_point(*walls_[w], spec, clip, [&](const Point3& x) {
      for (std::size_t k = 0; k < w; ++k)
        if (walls_[k]->contains(x)) return;
      p.x = x;
      fn(p);
    });
  }

  // Lattice points taken by explicit point sets of walls and bodies (a point set has no
  // interior to test, so the lattice cell of each of its points is claimed).
  std::unordered_set<std::int64_t> claimed;
  auto lattice_key = [&](const Point3& x) {
    std::int64_t key = 0;
    for (int a = d - 1; a >= 0; --a)
      key = key * 4000037 + static_cast<std::int64_t>(std::floor((x[a] - spec.origin[a]) / dx));
    return key;
  };
  for (const auto* group : {&walls_, &bodies_})
    for (const auto& shape : *group)
      if (const auto* pts = shape->explicit_points())
        for (const auto& x : *pts) claimed.insert(lattice_key(x));

  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const auto& body = c_.bodies(static_cast<int>(b));
    SceneParticle p;
    p.kind = Kind::kRigid;
    p.body = static_cast<std::int32_t>(b);
    const int mi = material_index(mats_, body.material());
    p.material = static_cast<std::uint16_t>(mi);
    p.rho = wall_rho_;  // a dummy density for the fluid (the wall condition overwrites it)
    p.mass = mats_[static_cast<std::size_t>(mi)].rho0 * vol;
    for_each_lattice_point(*bodies_[b], spec, clip, [&](const Point3& x) {
      for (const auto& w : walls_)
        if (w->contains(x)) return;
      for (std::size_t k = 0; k < b; ++k)
        if (bodies_[k]->contains(x)) return;
      p.x = x;
      fn(p);
    });
  }

  // Elastic bodies take the lattice points left by walls and rigid bodies (and by earlier
  // elastic bodies); fluids fill around them.
  for (std::size_t e = 0; e < elastic_.size(); ++e) {
    const auto& body = c_.elastic_bodies(static_cast<int>(e));
    SceneParticle p;
    p.kind = Kind::kElastic;
    p.elastic = static_cast<std::int32_t>(e);
    const int mi = material_index(mats_, body.material());
    p.material = static_cast<std::uint16_t>(mi);
    p.rho = wall_rho_;  // a dummy density for the fluid (the wall condition overwrites it)
    // An anisotropic body has its own lattice, stretched along its surface (case/anisotropy.h).
    p.mass = mats_[static_cast<std::size_t>(mi)].rho0 * elastic_particle_volume(c_, body);
    const LatticeSpec body_spec = elastic_lattice_spec(c_, body);
    for_each_lattice_point(*elastic_[e], body_spec, clip, [&](const Point3& x) {
      for (const auto& w : walls_)
        if (w->contains(x)) return;
      for (const auto& b : bodies_)
        if (b->contains(x)) return;
      if (!claimed.empty() && claimed.count(lattice_key(x))) return;
      for (std::size_t k = 0; k < e; ++k)
        if (elastic_[k]->contains(x)) return;
      p.x = x;
      p.constraint = -1;
      for (std::size_t k = 0; k < constraints_[e].size() && p.constraint < 0; ++k)
        if (constraints_[e][k]->contains(x)) p.constraint = static_cast<std::int32_t>(k);
      // Constrained particles start at rest (or with their motion, set by the elastic unit).
      p.v = p.constraint < 0 ? initial_velocity(to_point(body.initial_velocity()),
                                                body.initial_velocity_field(), x)
                             : Point3::Zero();
      fn(p);
    });
  }

  // SplitMix64: a well-mixed, reproducible pseudo-random value per particle.
  auto unit_random = [](std::uint64_t k) {
    k += 0x9E3779B97F4A7C15ull;
    k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
    k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
    k ^= k >> 31;
    return static_cast<double>(k >> 11) * 0x1.0p-53 * 2.0 - 1.0;  // [-1, 1)
  };
  std::uint64_t counter = 0;
  Point3 g = Point3::Zero();
  if (c_.has_gravity()) g = to_point(c_.gravity().acceleration());
  for (std::size_t f = 0; f < fluids_.size(); ++f) {
    const auto& region = c_.fluids(static_cast<int>(f));
    const int mi = material_index(mats_, region.material());
    const MaterialParams& m = mats_[static_cast<std::size_t>(mi)];
    SceneParticle p;
    p.kind = Kind::kFluid;
    p.region = static_cast<std::int32_t>(f);
    p.material = static_cast<std::uint16_t>(mi);
    for_each_lattice_point(*fluids_[f], spec, clip, [&](const Point3& x) {
      for (const auto& w : walls_)
        if (w->contains(x)) return;
      for (const auto& b : bodies_)
        if (b->contains(x)) return;
      for (const auto& b : elastic_)
        if (b->contains(x)) return;
      if (!claimed.empty() && claimed.count(lattice_key(x))) return;
      for (std::size_t k = 0; k < f; ++k)
        if (fluids_[k]->contains(x)) return;
      for (const auto& o : opens_)
        if (o->contains(x)) return;
      p.x = x;
      if (region.position_jitter() > 0)
        for (int a = 0; a < d; ++a)
          p.x[a] += region.position_jitter() * dx *
                    unit_random(3 * counter + static_cast<std::uint64_t>(a));
      ++counter;
      p.v = initial_velocity(to_point(region.initial_velocity()), region.initial_velocity_field(),
                             p.x);
      p.rho = m.rho0;
      if (region.has_hydrostatic_surface() && g.norm() > 0) {
        // p = rho0 |g| (surface - height), height measured along -g; the density follows
        // from the EOS and the mass keeps the lattice volume dx^d.
        const double height = -g.normalized().dot(p.x);
        const double pr = m.rho0 * g.norm() * (region.hydrostatic_surface() - height);
        const double base = std::max(pr / m.p0 + 1.0, 1e-3);  // p = chi + pr
        p.rho = m.rho0 * std::pow(base, 1.0 / m.gamma);
      }
      p.mass = p.rho * vol;
      fn(p);
    });
  }

  // Buffers of open boundaries: fluid at rest at the reference density (the boundary unit
  // sets their velocity and pressure).
  for (std::size_t o = 0; o < opens_.size(); ++o) {
    const int mi = material_index(mats_, c_.open_boundaries(static_cast<int>(o)).material());
    SceneParticle p;
    p.kind = Kind::kFluid;
    p.open = static_cast<std::int32_t>(o);
    p.material = static_cast<std::uint16_t>(mi);
    p.rho = mats_[static_cast<std::size_t>(mi)].rho0;
    p.mass = p.rho * vol;
    for_each_lattice_point(*opens_[o], spec, clip, [&](const Point3& x) {
      for (const auto& w : walls_)
        if (w->contains(x)) return;
      for (const auto& b : bodies_)
        if (b->contains(x)) return;
      for (const auto& b : elastic_)
        if (b->contains(x)) return;
      if (!claimed.empty() && claimed.count(lattice_key(x))) return;
      for (std::size_t k = 0; k < o; ++k)
        if (opens_[k]->contains(x)) return;
      p.x = x;
      fn(p);
    });
  }
}

}  // namespace sph
