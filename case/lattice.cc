#include "case/lattice.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sph {
namespace {

thread_local double t_work = 0;

struct IndexRange {
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // inclusive
  std::int64_t count(int a) const { return std::max<std::int64_t>(0, hi[a] - lo[a] + 1); }
  double points() const {
    double n = 1;
    for (int a = 0; a < 3; ++a) n *= static_cast<double>(count(a));
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

IndexRange index_range(const Aabb& box, const LatticeSpec& s) {
  IndexRange r;
  for (int a = 0; a < s.dim; ++a) {
    const double step = s.dx * s.stretch[a];
    r.lo[a] = to_index(std::ceil((box.lo[a] - s.origin[a]) / step - 0.5));
    r.hi[a] = to_index(std::floor((box.hi[a] - s.origin[a]) / step - 0.5));
  }
  return r;
}

// The lattice indices of the shape's bounds inside the clip box; empty when they miss it.
IndexRange walk_range(const Shape& shape, const LatticeSpec& s, const Aabb& clip) {
  const Aabb box = shape.bounds().intersected(clip);
  for (int a = 0; a < s.dim; ++a)
    if (box.hi[a] < box.lo[a]) return IndexRange{{0, 0, 0}, {-1, -1, -1}};
  return index_range(box, s);
}

// How a count samples one axis: n consecutive lattice indices from lo cut into m runs (strata)
// of n / m indices, rounded; run j holds lo + [floor(j n / m), floor((j + 1) n / m)).
struct AxisSample {
  std::int64_t lo = 0, n = 0, m = 0;
};

struct Run {
  std::int64_t start = 0, length = 0;
};

// k n / m can pass 2^63 before the division.
__extension__ using Wide = unsigned __int128;

Run run_of(const AxisSample& a, std::int64_t j) {
  auto edge = [&](std::int64_t k) {
    return a.lo + static_cast<std::int64_t>(static_cast<Wide>(k) * static_cast<Wide>(a.n) /
                                            static_cast<Wide>(a.m));
  };
  const std::int64_t s = edge(j);
  return {s, edge(j + 1) - s};
}

// The runs of an axis in order, with integer steps (a division per tested point would cost as
// much as testing a box).
class RunStepper {
 public:
  explicit RunStepper(const AxisSample& a)
      : a_(a), step_(a.n / a.m), rest_(a.n % a.m), carry_(rest_), run_{a.lo, step_} {}
  const Run& run() const { return run_; }
  void next() {
    run_.start += run_.length;
    run_.length = step_;
    carry_ += rest_;
    if (carry_ >= a_.m) {
      ++run_.length;
      carry_ -= a_.m;
    }
  }

 private:
  AxisSample a_;
  std::int64_t step_, rest_, carry_;
  Run run_;
};

// A well-mixed 64-bit value of k (SplitMix64): where in its stratum a sample lies.
std::uint64_t mix(std::uint64_t k) {
  k += 0x9E3779B97F4A7C15ull;
  k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
  k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
  return k ^ (k >> 31);
}

// An offset in [0, length) from 21 bits of a hash.
std::int64_t pick(std::uint64_t h, int part, std::int64_t length) {
  const std::uint64_t bits = (h >> (21 * part)) & 0x1FFFFF;
  return static_cast<std::int64_t>((bits * static_cast<std::uint64_t>(length)) >> 21);
}

// Runs per axis such that their product is at most `target` (>= 1): the same run length k
// along every axis, an axis shorter than k keeping one run, with k as small as that allows.
void choose_runs(AxisSample (&axes)[3], double target) {
  auto product = [&](double k) {
    double p = 1;
    for (const auto& a : axes) p *= std::max(1.0, std::floor(static_cast<double>(a.n) / k));
    return p;
  };
  double lo = 1, hi = 1;
  for (const auto& a : axes) hi = std::max(hi, static_cast<double>(a.n));
  for (int it = 0; it < 200 && hi - lo > 1e-9 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (product(mid) <= target ? hi : lo) = mid;
  }
  for (auto& a : axes)
    a.m =
        std::min(a.n, std::max<std::int64_t>(
                          1, static_cast<std::int64_t>(std::floor(static_cast<double>(a.n) / hi))));
}

}  // namespace

Point3 lattice_point(const LatticeSpec& s, std::int64_t i, std::int64_t j, std::int64_t k) {
  return {
      s.origin.x() + (static_cast<double>(i) + 0.5) * (s.dx * s.stretch.x()),
      s.origin.y() + (static_cast<double>(j) + 0.5) * (s.dx * s.stretch.y()),
      s.dim == 3 ? s.origin.z() + (static_cast<double>(k) + 0.5) * (s.dx * s.stretch.z()) : 0.0};
}

bool inside_box(const Point3& p, const Aabb& box, int dim) {
  for (int a = 0; a < dim; ++a)
    if (p[a] < box.lo[a] || p[a] > box.hi[a]) return false;
  return true;
}

LatticeRange lattice_range(const Shape& shape, const LatticeSpec& spec, const Aabb& clip) {
  const IndexRange r = walk_range(shape, spec, clip);
  LatticeRange out;
  for (int a = 0; a < 3; ++a) {
    out.lo[a] = r.lo[a];
    out.hi[a] = r.hi[a];
  }
  return out;
}

void for_each_lattice_point(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            const std::function<void(const Point3&)>& fn) {
  if (const auto* pts = shape.explicit_points()) {
    for (const auto& p : *pts)
      if (inside_box(p, clip, spec.dim)) fn(p);
    return;
  }
  const IndexRange r = walk_range(shape, spec, clip);
  t_work += r.points() * (shape.cost() + kLatticePointWork);
  for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k)
    for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
      for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i) {
        const Point3 p = lattice_point(spec, i, j, k);
        if (inside_box(p, clip, spec.dim) && shape.contains(p)) fn(p);
      }
}

double lattice_points_in(const Aabb& box, const LatticeSpec& spec) {
  for (int a = 0; a < spec.dim; ++a)
    if (box.hi[a] < box.lo[a]) return 0;
  return index_range(box, spec).points();
}

double walk_work(const Shape& shape, const LatticeSpec& spec, const Aabb& clip) {
  if (shape.explicit_points()) return 0;
  return walk_range(shape, spec, clip).points() * (shape.cost() + kLatticePointWork);
}

PointCount count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                                const Aabb& core, double max_work) {
  PointCount c;
  if (const auto* pts = shape.explicit_points()) {
    for (const auto& p : *pts)
      if (inside_box(p, clip, spec.dim)) {
        c.points += 1;
        c.hits += 1;
        c.in_core += inside_box(p, core, spec.dim) ? 1 : 0;
      }
    return c;
  }
  const IndexRange r = walk_range(shape, spec, clip);
  const double full = r.points();
  if (full < 1) return c;
  const double cost = shape.cost() + kLatticePointWork;
  const double target = std::floor(max_work / cost);
  AxisSample axes[3];
  for (int a = 0; a < 3; ++a) axes[a] = {r.lo[a], r.count(a), r.count(a)};
  if (full <= target) {
    c.tested = full;
    t_work += full * cost;
    for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z)
      for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
        for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x) {
          const Point3 p = lattice_point(spec, x, y, z);
          if (inside_box(p, clip, spec.dim) && shape.contains(p)) {
            c.hits += 1;
            c.in_core += inside_box(p, core, spec.dim) ? 1 : 0;
          }
        }
    c.points = c.hits;
    return c;
  }
  c.exact = false;
  if (target < 1) return c;
  choose_runs(axes, target);
  c.tested = static_cast<double>(axes[0].m) * static_cast<double>(axes[1].m) *
             static_cast<double>(axes[2].m);
  t_work += c.tested * cost;
  // One lattice point of each stratum, chosen by a hash of the stratum, stands for all of its
  // points. The same place in every stratum would alias with the lattice: a wall a few layers
  // thick would count as many layers as happen to fall on those places, along its whole face.
  for (std::int64_t z = 0; z < axes[2].m; ++z) {
    const Run rz = run_of(axes[2], z);
    for (std::int64_t y = 0; y < axes[1].m; ++y) {
      const Run ry = run_of(axes[1], y);
      const std::uint64_t row =
          mix((static_cast<std::uint64_t>(z) << 32) ^ static_cast<std::uint64_t>(y));
      RunStepper x(axes[0]);
      for (std::int64_t i = 0; i < axes[0].m; ++i, x.next()) {
        const Run& rx = x.run();
        const std::uint64_t h = mix(row + static_cast<std::uint64_t>(i));
        const Point3 p =
            lattice_point(spec, rx.start + pick(h, 0, rx.length), ry.start + pick(h, 1, ry.length),
                          rz.start + pick(h, 2, rz.length));
        if (inside_box(p, clip, spec.dim) && shape.contains(p)) {
          const double weight = static_cast<double>(rx.length) * static_cast<double>(ry.length) *
                                static_cast<double>(rz.length);
          c.hits += 1;
          c.points += weight;
          c.in_core += inside_box(p, core, spec.dim) ? weight : 0.0;
        }
      }
    }
  }
  return c;
}

double count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            double max_work) {
  return count_lattice_points(shape, spec, clip, clip, max_work).points;
}

std::vector<double> share_work(const std::vector<double>& needs, double budget) {
  std::vector<std::size_t> order(needs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return needs[a] < needs[b]; });
  std::vector<double> share(needs.size(), 0.0);
  double left = budget;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const double equal = left / static_cast<double>(order.size() - k);
    const double s = std::max(0.0, std::min(needs[order[k]], equal));
    share[order[k]] = s;
    left -= s;
  }
  return share;
}

double lattice_work_done() {
  return t_work;
}

void charge_lattice_work(double units) {
  t_work += units;
}

}  // namespace sph
