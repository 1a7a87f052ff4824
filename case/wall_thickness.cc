#include "case/wall_thickness.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/geometry.h"
#include "case/lattice.h"
#include "case/number_text.h"

namespace sph {
namespace {

// What occupies a lattice cell at t = 0: nothing, fluid (regions and open-boundary buffers),
// a body, or wall k (kWall + k).
enum : std::uint16_t { kEmpty = 0, kFluid = 1, kBody = 2, kWall = 3 };

// The domain's lattice cells, tagged in the scene builder's claiming order (walls, bodies,
// open-boundary buffers, fluids; the first claim wins).
class Occupancy {
 public:
  Occupancy(const v1::Case& c, const LatticeSpec& spec) : spec_(spec), dim_(c.dimension()) {
    const Point3 lo = to_point(c.domain().lo()), hi = to_point(c.domain().hi());
    const bool periodic[3] = {c.periodic_x(), c.periodic_y(), c.periodic_z()};
    cells_ = 1;
    for (int a = 0; a < 3; ++a) {
      if (a >= dim_) {
        lo_[a] = 0;
        n_[a] = 1;
        continue;
      }
      lo_[a] = static_cast<std::int64_t>(std::ceil((lo[a] - spec.origin[a]) / spec.dx - 0.5));
      const auto last =
          static_cast<std::int64_t>(std::floor((hi[a] - spec.origin[a]) / spec.dx - 0.5));
      n_[a] = std::max<std::int64_t>(0, last - lo_[a] + 1);
      periodic_[a] = periodic[a];
      cells_ *= static_cast<double>(n_[a]);
    }
  }
  double cells() const { return cells_; }
  void allocate() {
    tag_.assign(static_cast<std::size_t>(cells_), kEmpty);
    stride_[0] = 1;
    stride_[1] = n_[0];
    stride_[2] = n_[0] * n_[1];
  }

  // Tags every lattice point of `shape` inside the domain that is still empty (a cell taken
  // already is not tested again).
  void claim(const Shape& shape, const Aabb& clip, std::uint16_t tag) {
    auto take = [&](std::int64_t k) {
      if (k >= 0 && tag_[static_cast<std::size_t>(k)] == kEmpty)
        tag_[static_cast<std::size_t>(k)] = tag;
    };
    if (const auto* pts = shape.explicit_points()) {
      for (const auto& p : *pts) {
        if (!inside_box(p, clip, dim_)) continue;
        std::array<std::int64_t, 3> i{};
        for (int a = 0; a < dim_; ++a)
          i[a] = static_cast<std::int64_t>(std::llround((p[a] - spec_.origin[a]) / spec_.dx - 0.5));
        take(linear(i));
      }
      return;
    }
    const LatticeRange r = lattice_range(shape, spec_, clip);
    for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z)
      for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
        for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x) {
          const std::int64_t k = linear({x, y, z});
          if (k < 0 || tag_[static_cast<std::size_t>(k)] != kEmpty) continue;
          const Point3 p = lattice_point(spec_, x, y, z);
          if (inside_box(p, clip, dim_) && shape.contains(p)) take(k);
        }
  }

  // Tag of the cell `steps` cells along axis a from the cell at lattice index i, whose place in
  // the grid is k (wrapped on periodic axes; outside the domain: empty). Strides instead of the
  // index from scratch: the scan looks up every neighbour of every fluid cell.
  std::uint16_t along(const std::array<std::int64_t, 3>& i, std::int64_t k, int a,
                      std::int64_t steps) const {
    const std::int64_t from = i[a] - lo_[a];
    std::int64_t r = from + steps;
    if (r < 0 || r >= n_[a]) {
      if (!periodic_[a]) return kEmpty;
      r = ((r % n_[a]) + n_[a]) % n_[a];
    }
    return tag_[static_cast<std::size_t>(k + (r - from) * stride_[a])];
  }

  // Calls fn(i, k) for the lattice index i and grid place k of every fluid cell.
  template <class Fn>
  void for_each_fluid(Fn&& fn) const {
    std::int64_t k = 0;
    for (std::int64_t z = 0; z < n_[2]; ++z)
      for (std::int64_t y = 0; y < n_[1]; ++y)
        for (std::int64_t x = 0; x < n_[0]; ++x, ++k)
          if (tag_[static_cast<std::size_t>(k)] == kFluid)
            fn(std::array<std::int64_t, 3>{lo_[0] + x, lo_[1] + y, lo_[2] + z}, k);
  }

  Point3 position(const std::array<std::int64_t, 3>& i) const {
    Point3 p = Point3::Zero();
    for (int a = 0; a < dim_; ++a)
      p[a] = spec_.origin[a] + (static_cast<double>(i[a]) + 0.5) * spec_.dx;
    return p;
  }

 private:
  std::int64_t linear(std::array<std::int64_t, 3> i) const {
    std::int64_t k = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
      std::int64_t r = i[a] - lo_[a];
      if (periodic_[a] && n_[a] > 0 && (r < 0 || r >= n_[a])) r = ((r % n_[a]) + n_[a]) % n_[a];
      if (r < 0 || r >= n_[a]) return -1;
      k += r * stride;
      stride *= n_[a];
    }
    return k;
  }

  LatticeSpec spec_;
  int dim_;
  std::int64_t lo_[3] = {0, 0, 0}, n_[3] = {1, 1, 1}, stride_[3] = {1, 1, 1};
  bool periodic_[3] = {false, false, false};
  double cells_ = 0;
  std::vector<std::uint16_t> tag_;
};

// The scan's work per cell and axis, in units of Shape::cost(): a fluid cell looks at its two
// neighbours along each axis.
constexpr double kScanWorkPerCell = 2;

// The first place a wall was found too thin, and how often.
struct Finding {
  int count = 0;
  int layers = 0;        // wall layers found there
  bool through = false;  // fluid behind the wall (else empty space)
  std::array<std::int64_t, 3> at{}, behind{};
  int axis = 0, sign = 1;
};

std::string point_text(const Point3& p, int dim) {
  std::string s = number_text(p.x());
  for (int a = 1; a < dim; ++a) s.append(", ").append(number_text(p[a]));
  return s.insert(0, 1, '(').append(")");
}

}  // namespace

std::vector<FieldError> check_wall_thickness(const v1::Case& c) {
  std::vector<FieldError> errors;
  if (c.walls_size() == 0) return errors;
  const int dim = c.dimension();
  const double dx = c.dx(), rc = kernel_support_radius(c);
  // Wall layers a first-row fluid particle reaches: lattice distances n dx < r_c.
  int needed = 0;
  while ((needed + 1) * dx < rc * (1.0 - 1e-9)) ++needed;
  if (needed <= 1) return errors;

  const LatticeSpec spec{dim, dx, to_point(c.lattice_origin())};
  Occupancy occ(c, spec);
  if (occ.cells() < 1) return errors;
  Aabb clip{to_point(c.domain().lo()), to_point(c.domain().hi())};
  if (dim == 2) clip.lo.z() = clip.hi.z() = 0.0;
  const double shell = default_shell_thickness(c);
  // The claiming order of the scene builder: walls, bodies, open-boundary buffers, fluids.
  std::vector<std::pair<std::unique_ptr<Shape>, std::uint16_t>> claims;
  for (int k = 0; k < c.walls_size(); ++k)
    claims.emplace_back(compile_shape(c.walls(k).shape(), dim, shell),
                        static_cast<std::uint16_t>(kWall + k));
  for (const auto& b : c.bodies()) claims.emplace_back(compile_shape(b.shape(), dim, shell), kBody);
  for (const auto& o : c.open_boundaries()) {
    v1::Shape box;
    *box.mutable_box() = o.region();
    claims.emplace_back(compile_shape(box, dim, shell), kFluid);
  }
  for (const auto& f : c.fluids())
    claims.emplace_back(compile_shape(f.shape(), dim, shell), kFluid);
  // Every cell is tagged exactly, so the check cannot sample: it runs within kWallCheckWork or
  // not at all.
  double work = occ.cells() * kScanWorkPerCell * dim;
  for (const auto& [shape, tag] : claims) work += walk_work(*shape, spec, clip);
  if (work > kWallCheckWork) return errors;
  charge_lattice_work(work);
  occ.allocate();
  for (const auto& [shape, tag] : claims) occ.claim(*shape, clip, tag);

  std::vector<Finding> found(static_cast<std::size_t>(c.walls_size()));
  occ.for_each_fluid([&](const std::array<std::int64_t, 3>& f, std::int64_t k) {
    for (int a = 0; a < dim; ++a)
      for (int sign = -1; sign <= 1; sign += 2) {
        const std::uint16_t first = occ.along(f, k, a, sign);
        if (first < kWall) continue;
        int layers = 1;
        for (int n = 2; n <= needed; ++n) {
          const std::uint16_t t = occ.along(f, k, a, sign * n);
          if (t == kEmpty || t == kFluid) {
            Finding& g = found[first - kWall];
            if (g.count++ == 0) {
              g.layers = layers;
              g.through = t == kFluid;
              g.at = f;
              g.behind = f;
              g.behind[a] += sign * n;
              g.axis = a;
              g.sign = sign;
            }
            break;
          }
          ++layers;
        }
      }
  });

  static const char* kAxis[3] = {"x", "y", "z"};
  for (int k = 0; k < c.walls_size(); ++k) {
    const Finding& g = found[static_cast<std::size_t>(k)];
    if (g.count == 0) continue;
    const std::string along = std::string(g.sign < 0 ? "-" : "+") + kAxis[g.axis];
    std::string m = "wall '" + c.walls(k).name() + "' is " + std::to_string(g.layers) +
                    " particle layer" + (g.layers == 1 ? "" : "s") + " thick along " + along +
                    " next to the fluid particle at " + point_text(occ.position(g.at), dim);
    if (g.count > 1) m += " (and " + std::to_string(g.count - 1) + " more places)";
    m += g.through ? ", with fluid behind it at " + point_text(occ.position(g.behind), dim) +
                         ": the fluids on its two sides would interact through it"
                   : ": the kernel support reaches past it into empty space";
    m += "; r_c = " + number_text(rc) + " needs " + std::to_string(needed) + " layers (" +
         number_text(needed * dx) +
         " thick) behind the first fluid row: make the wall thicker (the domain bounds cut "
         "walls, so the domain must hold it too), give it as a `shell` without `thickness` "
         "(ceil(r_c/dx) layers), or lower smoothing_length_ratio";
    errors.push_back({"walls[" + std::to_string(k) + "].shape", m});
  }
  return errors;
}

}  // namespace sph
