#include "solver/boundaries/wall_growth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "case/estimate.h"
#include "case/time_function.h"
#include "solver/parallel/exact_sum.h"

namespace sph {

template <int D>
WallGrowth<D>::WallGrowth(const v1::Case& c, const std::vector<MaterialParams>& materials,
                          double dx, const std::array<bool, D>& periodic, const Vec<D>& length)
    : max_dt_(std::numeric_limits<double>::infinity()), dx_(dx) {
  const double shell = default_shell_thickness(c);
  for (int w = 0; w < c.walls_size(); ++w) {
    const v1::Wall& pw = c.walls(w);
    if (!pw.has_growth_speed()) continue;
    Growing g;
    g.wall = static_cast<std::uint16_t>(w);
    if (!pw.material().empty())
      g.material = static_cast<std::uint16_t>(material_index(materials, pw.material()));
    g.free_slip = pw.free_slip();
    g.name = pw.name().empty() ? "wall_" + std::to_string(w) : pw.name();
    g.speed = TimeFunction(pw.growth_speed());
    g.shape = compile_shape(pw.shape(), c.dimension(), shell);
    g.bounds = g.shape->bounds();
    // A quarter layer per step at most: the front passes each particle in its own step.
    const double v = TimeFunction(pw.growth_speed()).max_value();
    if (v > 0) max_dt_ = std::min(max_dt_, 0.25 * dx / v);
    walls_.push_back(std::move(g));
  }
  // Periodic images: shifts by -L, 0, +L along each periodic axis, the zero shift first.
  images_.push_back(Vec<D>::Zero());
  for (int a = 0; a < D; ++a) {
    if (!periodic[static_cast<std::size_t>(a)]) continue;
    const std::size_t n = images_.size();
    for (const double sign : {-1.0, 1.0})
      for (std::size_t k = 0; k < n; ++k) {
        Vec<D> shift = images_[k];
        shift[a] += sign * length[a];
        images_.push_back(shift);
      }
  }
}

template <int D>
double WallGrowth<D>::distance(std::size_t k, const Vec<D>& x, double reach) const {
  const Growing& g = walls_[k];
  double best = std::numeric_limits<double>::infinity();
  for (const Vec<D>& shift : images_) {
    Point3 p = Point3::Zero();
    bool near = true;
    for (int a = 0; a < D; ++a) {
      p[a] = x[a] + shift[a];
      // Outside the shape's box grown by the reach, the distance exceeds the reach.
      near = near && p[a] >= g.bounds.lo[a] - reach && p[a] <= g.bounds.hi[a] + reach;
    }
    if (near) best = std::min(best, g.shape->distance(p));
  }
  return best;
}

template <int D>
typename WallGrowth<D>::Outcome WallGrowth<D>::run(ParticleStore<D>& s, const Columns& cols,
                                                   RigidBodies<D>* bodies, double t,
                                                   const Comm& comm) {
  Outcome out;
  const std::size_t nw = walls_.size();
  std::vector<double> front(nw);
  bool any = false;
  for (std::size_t k = 0; k < nw; ++k) {
    front[k] = this->front(k, t);
    any = any || front[k] > 0;
  }
  if (!any) return out;  // every rank alike: t is the same everywhere
  const std::size_t nb = bodies ? bodies->bodies().size() : 0;
  const Column<std::int32_t>* body = bodies ? &bodies->body_index() : nullptr;
  // 1. Decide from the positions r^{n+1}: which wall takes each fluid particle the fronts
  //    passed (the one whose front passed it farthest; ties: the first), and which walls
  //    reached each body. Counts per wall, then per body and wall, summed over the ranks.
  std::vector<std::pair<std::size_t, std::size_t>> grow;  // (particle, growing wall)
  std::vector<std::int64_t> counts(nw + nb * nw, 0);
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const Kind kind = s.kind[i];
    const bool fluid = kind == Kind::kFluid && !(cols.open_zone && (*cols.open_zone)[i] != 0);
    const bool rigid = kind == Kind::kRigid && body && (*body)[i] >= 0;
    if (!fluid && !rigid) continue;
    std::size_t take = nw;
    double deepest = 0;
    for (std::size_t k = 0; k < nw; ++k) {
      if (front[k] <= 0) continue;
      const double past = front[k] - distance(k, s.x[i], front[k]);
      if (past <= 0) continue;
      if (rigid) {
        ++counts[nw + static_cast<std::size_t>((*body)[i]) * nw + k];
      } else if (take == nw || past > deepest) {
        take = k;
        deepest = past;
      }
    }
    if (take < nw) {
      grow.push_back({i, take});
      ++counts[take];
    }
  }
  comm.sum_inplace(counts);
  std::vector<std::size_t> engulfed_by(nb, nw);  // the first wall that reached each body
  std::vector<std::int64_t> involved(nb, 0);
  for (std::size_t b = 0; b < nb; ++b)
    for (std::size_t k = 0; k < nw && engulfed_by[b] == nw; ++k)
      if (counts[nw + b * nw + k] > 0 && bodies->bodies()[b].active()) {
        engulfed_by[b] = k;
        involved[b] = 1;
        ++out.engulfed;
      }
  for (std::size_t k = 0; k < nw; ++k) out.grown += counts[k];
  if (out.grown == 0 && out.engulfed == 0) return out;

  // 2. Convert. Mass per wall by exact sums (the same on any rank count).
  std::vector<std::pair<std::size_t, std::size_t>> engulf;  // (particle, growing wall)
  if (out.engulfed > 0)
    for (std::size_t i = 0; i < s.owned(); ++i)
      if (s.kind[i] == Kind::kRigid && (*body)[i] >= 0 &&
          engulfed_by[static_cast<std::size_t>((*body)[i])] < nw)
        engulf.push_back({i, engulfed_by[static_cast<std::size_t>((*body)[i])]});
  const std::vector<double> mass = exact_sum(
      nw,
      [&](auto emit) {
        for (const auto* list : {&grow, &engulf})
          for (const auto& [i, k] : *list) emit(k, s.m[i]);
      },
      comm);
  for (const auto* list : {&grow, &engulf})
    for (const auto& [i, k] : *list) {
      const Growing& g = walls_[k];
      s.kind[i] = Kind::kWall;
      s.material[i] = g.material;
      s.v[i] = Vec<D>::Zero();
      s.a[i] = Vec<D>::Zero();
      (*cols.wall_index)[i] = g.wall;
      if (cols.free_slip) (*cols.free_slip)[i] = g.free_slip ? 1 : 0;
      if (cols.transport) (*cols.transport)[i] = Vec<D>::Zero();
      if (cols.background) (*cols.background)[i] = Vec<D>::Zero();
      if (cols.wall_accel) (*cols.wall_accel)[i] = Vec<D>::Zero();
      if (body) bodies->body_index()[i] = -1;
    }
  for (std::size_t k = 0; k < nw; ++k) {
    walls_[k].particles += counts[k];
    walls_[k].mass += mass[k];
  }
  for (std::size_t b = 0; b < nb; ++b)
    if (involved[b]) walls_[engulfed_by[b]].particles += bodies->bodies()[b].particles;
  engulfed_ += out.engulfed;
  // 3. The engulfed bodies, their particles gone, are emptied (inactive from now on).
  if (out.engulfed > 0)
    out.error = BodyRegrouping<D>::whole_bodies(dx_).run(s, *bodies, involved, comm);
  return out;
}

template <int D>
void WallGrowth<D>::save(CheckpointState& state) const {
  state["wall_growth.engulfed"] = static_cast<double>(engulfed_);
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const std::string p = "wall_growth." + std::to_string(walls_[k].wall) + ".";
    state[p + "particles"] = static_cast<double>(walls_[k].particles);
    state[p + "mass"] = walls_[k].mass;
  }
}

template <int D>
void WallGrowth<D>::load(const CheckpointState& state) {
  engulfed_ = static_cast<std::int64_t>(state_value(state, "wall_growth.engulfed"));
  for (Growing& g : walls_) {
    const std::string p = "wall_growth." + std::to_string(g.wall) + ".";
    g.particles = static_cast<std::int64_t>(state_value(state, p + "particles"));
    g.mass = state_value(state, p + "mass");
  }
}

template class WallGrowth<2>;
template class WallGrowth<3>;

}  // namespace sph
