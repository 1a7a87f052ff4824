#pragma once
// Placing particles: the cell-centred lattice x = origin + (i + 1/2) dx filled inside shapes
// (dx stretch[a] along axis a where a lattice is stretched).
#include <cstdint>
#include <functional>
#include <vector>

#include "case/geometry.h"

namespace sph {

struct LatticeSpec {
  int dim = 2;
  double dx = 1.0;
  Point3 origin = Point3::Zero();
  // The spacing along axis a is dx stretch[a]: 1 everywhere but along the surface of an
  // anisotropically resolved elastic body (case/anisotropy.h).
  Point3 stretch = Point3::Ones();
};

// Calls fn for every lattice point inside `shape` and inside `clip`, in a fixed order
// (z slowest, x fastest), or for every explicit point of a PointSet inside `clip`.
void for_each_lattice_point(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            const std::function<void(const Point3&)>& fn);

// Lattice points inside `box` (the points a walk over it visits).
double lattice_points_in(const Aabb& box, const LatticeSpec& spec);

// The lattice indices a walk over `shape` in `clip` visits, inclusive along each axis (0 to 0
// along z in 2D; hi < lo when the shape's bounds miss the clip box), and the point of an index.
struct LatticeRange {
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};
};
LatticeRange lattice_range(const Shape& shape, const LatticeSpec& spec, const Aabb& clip);
Point3 lattice_point(const LatticeSpec& spec, std::int64_t i, std::int64_t j, std::int64_t k);
bool inside_box(const Point3& p, const Aabb& box, int dim);

// The work of visiting one lattice point besides testing the shape there (placing the point,
// comparing it with the clip box), in units of Shape::cost(): a walk over n points with a shape
// of cost c does n (c + kLatticePointWork).
inline constexpr double kLatticePointWork = 2;
// The work of a walk over every lattice point of `shape` in `clip` (0 for explicit points).
double walk_work(const Shape& shape, const LatticeSpec& spec, const Aabb& clip);

// What count_lattice_points found.
struct PointCount {
  double points = 0;   // points inside the shape and the clip box
  double in_core = 0;  // of those, the ones inside the core box
  double tested = 0;   // lattice points at which the shape was evaluated
  double hits = 0;     // of those, the ones inside the shape and the clip box
  bool exact = true;   // every lattice point of the shape's bounds was tested
};

// Counts the points for_each_lattice_point(shape, spec, clip) would give, and how many of them
// lie in `core`, evaluating the shape at no more than max_work / (shape.cost() +
// kLatticePointWork) lattice points. Where the bounds hold more, a stratified sample of the
// lattice's own points stands for them: along each axis the indices are cut into runs of equal
// length (an axis shorter than a run keeps one, so a slab or a needle is sampled along its
// length), and in each box of runs one point, placed by a hash of the box, counts for all the
// box's points. The same case always gives the same counts. When not even one point can be
// afforded, nothing is tested and the counts are 0 (not exact). Explicit points (PointSet) are
// counted one by one, whatever the budget.
PointCount count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                                const Aabb& core, double max_work);

// The number of points alone, within a budget of max_work.
double count_lattice_points(const Shape& shape, const LatticeSpec& spec, const Aabb& clip,
                            double max_work = 4e6);

// Splits `budget` among tasks that each need needs[i] to be done exactly: a task that needs no
// more than an equal part of what is left gets all it needs, the rest share the remainder
// equally (small regions stay exact, large ones are sampled). The shares sum to at most
// `budget`.
std::vector<double> share_work(const std::vector<double>& needs, double budget);

// The work, in units of Shape::cost(), that lattice walks in this thread have done so far: each
// lattice point tested adds the cost of the shape tested there. The budgets of validation and
// estimates (case/case_limits.h) bound it; tests read it to check that they do.
double lattice_work_done();
// Adds work done outside the walks above (the wall check's scan of its grid).
void charge_lattice_work(double units);

}  // namespace sph
