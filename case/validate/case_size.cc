// The case's size: every region inside the domain, the particle and memory estimate
// against the limits, and walls thick enough.
#include "case/validate/validator.h"

#include <cmath>
#include <memory>

#include "case/case_bounds.h"
#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/geometry.h"
#include "case/lattice.h"
#include "case/wall_thickness.h"

namespace sph::case_validation {

// Each region must place particles, and a fluid or a body most of them inside the domain
// (kMinRegionFractionInDomain): the scene builder drops whatever lies outside without a word.
// The regions share kRegionCheckWork; one counted on a sample is refused for lying outside
// only when the sample is large enough to tell, and never for placing no particles (a thin
// region can slip between the points of a sample).
void Validator::regions_in_domain() {
  const int d = c_.dimension();
  const LatticeSpec spec{d, c_.dx(), to_point(c_.lattice_origin())};
  Aabb domain{to_point(c_.domain().lo()), to_point(c_.domain().hi())};
  if (d == 2) domain.lo.z() = domain.hi.z() = 0.0;
  // Lattice points around the domain, as far again as the domain is wide on each side of a
  // non-periodic axis: a finite box (the lattice range check covers it) that holds any region
  // "mostly" inside. Along a periodic axis the domain clips every region on purpose.
  Aabb around = domain;
  const bool periodic[3] = {c_.periodic_x(), c_.periodic_y(), c_.periodic_z()};
  for (int a = 0; a < d; ++a) {
    if (periodic[a]) continue;
    const double w = domain.hi[a] - domain.lo[a];
    around.lo[a] -= w;
    around.hi[a] += w;
  }
  struct Region {
    const v1::Shape* shape;
    std::string kind, name, field;
  };
  std::vector<Region> regions;
  for (int i = 0; i < c_.fluids_size(); ++i)
    regions.push_back(
        {&c_.fluids(i).shape(), "fluid", c_.fluids(i).name(), cat(idx("fluids", i), "shape")});
  for (int i = 0; i < c_.walls_size(); ++i)
    regions.push_back(
        {&c_.walls(i).shape(), "wall", c_.walls(i).name(), cat(idx("walls", i), "shape")});
  for (int i = 0; i < c_.bodies_size(); ++i)
    regions.push_back(
        {&c_.bodies(i).shape(), "body", c_.bodies(i).name(), cat(idx("bodies", i), "shape")});
  for (int i = 0; i < c_.elastic_bodies_size(); ++i)
    regions.push_back({&c_.elastic_bodies(i).shape(), "elastic body", c_.elastic_bodies(i).name(),
                       cat(idx("elastic_bodies", i), "shape")});
  const double shell = default_shell_thickness(c_);
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<double> needs;
  for (const auto& r : regions) {
    shapes.push_back(compile_shape(*r.shape, d, shell));
    needs.push_back(walk_work(*shapes.back(), spec, around));
  }
  // Each constraint of an elastic body must hold particles of it; its walk shares the budget.
  const std::vector<ConstraintCheck> constraints = constraint_checks(spec, domain);
  for (const auto& k : constraints) needs.push_back(k.need);
  const std::vector<double> share = share_work(needs, kRegionCheckWork);
  for (std::size_t k = 0; k < constraints.size(); ++k)
    check_constraint(constraints[k], spec, domain, share[regions.size() + k]);
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const Shape& shape = *shapes[k];
    const Region& r = regions[k];
    const PointCount n = count_lattice_points(shape, spec, around, domain, share[k]);
    const double inside = n.in_core, near = n.points;
    const std::string what = r.kind + (r.name.empty() ? "" : " '" + r.name + "'");
    const std::string points = shape.explicit_points() ? "points" : "lattice points";
    if (n.exact && inside < 1) {
      error(r.field,
            what + " places no particles: " +
                (near >= 1 ? "none of its " + count_text(near) + " " + points + " lies"
                           : std::string("it has no ") + points + " (dx = " + num(c_.dx()) + ")") +
                " inside the domain" + domain_text() + "; the shape spans " +
                box_text(shape.bounds()));
    } else if (r.kind != "wall" && (n.exact || n.hits >= kMinHitsToRefuse) &&
               inside < kMinRegionFractionInDomain * near) {
      const std::string about = n.exact ? "" : "about ";
      error(r.field, what + " lies mostly outside the domain" + domain_text() + ": " + about +
                         count_text(std::round(inside)) + " of its " + about +
                         count_text(std::round(near)) + " " + points + " are inside" +
                         (n.exact ? "" : " (counted on a sample)") + "; at least " +
                         count_text(100 * kMinRegionFractionInDomain) + "% must be");
    }
  }
}

std::string Validator::domain_text() const {
  return " (" + box_text({to_point(c_.domain().lo()), to_point(c_.domain().hi())}) + ")";
}

// "x in [0, 2], y in [0, 2]"
std::string Validator::box_text(const Aabb& b) const {
  std::string s;
  for (int a = 0; a < c_.dimension(); ++a)
    s += std::string(a ? ", " : "") + "xyz"[a] + " in [" + num(b.lo[a]) + ", " + num(b.hi[a]) + "]";
  return s;
}

void Validator::case_size() {
  if (!errors_.empty()) return;  // shapes must be valid to estimate
  regions_in_domain();
  if (!errors_.empty()) return;
  const CaseEstimate e = estimate_case(c_);
  if (estimate_ != nullptr) *estimate_ = e;
  if (e.total() < 1)
    error("fluids", "the case places no particles (check shapes against domain and dx)");
  if (limits_.max_particles > 0 && e.total() > limits_.max_particles)
    error("dx", "case too large: estimated " + count_text(e.total()) + " particles; " +
                    limits_.source + " limit is " + count_text(limits_.max_particles) +
                    " (--max-particles): increase dx or shrink the domain");
  if (limits_.max_memory_bytes > 0 && e.bytes > limits_.max_memory_bytes)
    error("dx", "case too large: estimated " + gib_text(e.bytes) + " GiB of memory for " +
                    count_text(e.total()) + " particles; " + limits_.source + " limit is " +
                    gib_text(limits_.max_memory_bytes) +
                    " GiB (--max-memory-gib): increase dx or shrink the domain");
  if (!errors_.empty()) return;
  for (auto& w : check_wall_thickness(c_)) errors_.push_back(std::move(w));
}

}  // namespace sph::case_validation
