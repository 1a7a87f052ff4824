#include "case/distance_grid/distance_grid_shape.h"

#include <algorithm>
#include <cmath>

namespace sph {

DistanceGridShape::DistanceGridShape(const v1::DistanceGrid& g, int dim) : dim_(dim) {
  const double scale = g.has_scale() ? g.scale() : 1.0;
  for (int a = 0; a < dim; ++a) n_[a] = g.counts(a);
  origin_ = scale * to_point(g.origin());
  if (dim == 2) origin_.z() = 0.0;
  spacing_ = scale * g.spacing();
  values_.reserve(static_cast<std::size_t>(g.values_size()));
  for (const float v : g.values()) values_.push_back(scale * static_cast<double>(v));
  grid_ = {origin_, origin_};
  for (int a = 0; a < dim; ++a) grid_.hi[a] += spacing_ * static_cast<double>(n_[a] - 1);
  // Nodes with a negative value, widened by one node: every cell that can hold a point with a
  // negative interpolant has one of them as a corner.
  std::int64_t lo[3] = {n_[0], n_[1], n_[2]}, hi[3] = {-1, -1, -1};
  for (std::int64_t k = 0; k < n_[2]; ++k)
    for (std::int64_t j = 0; j < n_[1]; ++j)
      for (std::int64_t i = 0; i < n_[0]; ++i)
        if (node(i, j, k) < 0) {
          const std::int64_t at[3] = {i, j, k};
          for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], at[a]);
            hi[a] = std::max(hi[a], at[a]);
          }
        }
  if (hi[0] < 0) return;  // no negative node: empty (validation refuses that)
  for (int a = 0; a < dim; ++a) {
    inside_.lo[a] =
        origin_[a] + spacing_ * static_cast<double>(std::max<std::int64_t>(lo[a] - 1, 0));
    inside_.hi[a] =
        origin_[a] + spacing_ * static_cast<double>(std::min<std::int64_t>(hi[a] + 1, n_[a] - 1));
  }
  if (dim == 2) inside_.lo.z() = inside_.hi.z() = 0.0;
}

double DistanceGridShape::distance(const Point3& p) const {
  // Outside the grid: the distance to the grid plus the nearest boundary node's value, which
  // validation keeps > 0. Not the exact distance there, but of the right sign and growing with
  // it, which is what the lattice fill and the boolean combinations need.
  Point3 q = p;
  if (dim_ == 2) q.z() = 0.0;
  const Point3 clamped = q.cwiseMax(grid_.lo).cwiseMin(grid_.hi);
  const double outside = (q - clamped).norm();
  // The cell of the clamped point and its local coordinates in [0, 1].
  std::int64_t c[3] = {0, 0, 0};
  double f[3] = {0, 0, 0};
  for (int a = 0; a < dim_; ++a) {
    const double x = (clamped[a] - origin_[a]) / spacing_;
    c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), 0, n_[a] - 2);
    f[a] = std::clamp(x - static_cast<double>(c[a]), 0.0, 1.0);
  }
  double v;
  const auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
  if (dim_ == 2) {
    const double v0 = lerp(node(c[0], c[1], 0), node(c[0] + 1, c[1], 0), f[0]);
    const double v1 = lerp(node(c[0], c[1] + 1, 0), node(c[0] + 1, c[1] + 1, 0), f[0]);
    v = lerp(v0, v1, f[1]);
  } else {
    double w[2];
    for (int dk = 0; dk < 2; ++dk) {
      const double v0 = lerp(node(c[0], c[1], c[2] + dk), node(c[0] + 1, c[1], c[2] + dk), f[0]);
      const double v1 =
          lerp(node(c[0], c[1] + 1, c[2] + dk), node(c[0] + 1, c[1] + 1, c[2] + dk), f[0]);
      w[dk] = lerp(v0, v1, f[1]);
    }
    v = lerp(w[0], w[1], f[2]);
  }
  return outside > 0 ? std::max(v, 0.0) + outside : v;
}

}  // namespace sph
