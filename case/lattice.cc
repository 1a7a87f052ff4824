#include "case/lattice.h"

#include <algorithm>
#include <cmath>

namespace sph {
namespace {

struct IndexRange {
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // inclusive
  double points() const {
    double n = 1;
    for (int a = 0; a < 3; ++a)
      n *= static_cast<double>(std::max<std::int64_t>(0, hi[a] - lo[a] + 1));
    return n;
  }
};

// A lattice index as int64. Validation keeps the domain within kMaxLatticeCellsPerAxis of the
// origin (case/case_limits.h); the clamp only keeps a conversion defined for callers that did
// not validate (a double beyond the int64 range converts to anything).
std::int64_t to_index(double v) {
  constexpr double kLimit = 4.0e18;
  if (std::isnan(v)) return 0;
  return static_cast<std::int64_t>(std::clamp(v, -kLimit, kLimit));
}

IndexRange index_range(const Aabb& box, const LatticeSpec& s, double spacing) {
  IndexRange r;
  for (int a = 0; a < s.dim; ++a) {
    r.lo[a] = to_index(std::ceil((box.lo[a] - s.origin[a]) / spacing - 0.5));
    r.hi[a] = to_index(std::floor((box.hi[a] - s.origin[a]) / spacing - 0.5));
  }
  return r;
}

bool inside_clip(const Point3& p, const Aabb& clip, int dim) {
  for (int a = 0; a < dim; ++a)
    if (p[a] < clip.lo[a] || p[a] > clip.hi[a]) return false;
  return true;
}

template <class Fn>
void walk(const Shape& shape, const LatticeSpec& s, const Aabb& clip, double spacing, Fn&& fn) {
  const Aabb box = shape.bounds().intersected(clip);
  if (box.empty() && s.dim == 3) return;
  if (s.dim == 2 && (box.hi.x() < box.lo.x() || box.hi.y() < box.lo.y())) return;
  const IndexRange r = index_range(box, s, spacing);
  for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k)
    for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
      for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i) {
        Point3 p(s.origin.x() + (static_cast<double>(i) + 0.5) * spacing,
                 s.origin.y() + (static_cast<double>(j) + 0.5) * spacing,
                 s.dim == 3 ? s.origin.z() + (static_cast<double>(k) + 0.5) * spacing : 0.0);
        if (inside_clip(p, clip, s.dim) && shape.contains(p)) fn(p);
      }
}

}  // namespace

void for_each_lattice_point(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            const std::function<void(const Point3&)>& fn) {
  if (const auto* pts = shape.explicit_points()) {
    for (const auto& p : *pts)
      if (inside_clip(p, clip, spec.dim)) fn(p);
    return;
  }
  walk(shape, spec, clip, spec.dx, fn);
}

double count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            double exact_limit) {
  if (const auto* pts = shape.explicit_points()) {
    double n = 0;
    for (const auto& p : *pts) n += inside_clip(p, clip, spec.dim) ? 1 : 0;
    return n;
  }
  const Aabb box = shape.bounds().intersected(clip);
  const double full = index_range(box, spec, spec.dx).points();
  double spacing = spec.dx;
  if (full > exact_limit) spacing *= std::pow(full / exact_limit, 1.0 / spec.dim);
  double n = 0;
  walk(shape, spec, clip, spacing, [&](const Point3&) { n += 1; });
  return n * std::pow(spacing / spec.dx, spec.dim);
}

}  // namespace sph
