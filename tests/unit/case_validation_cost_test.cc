// What validating and estimating a case may cost (issue #41): every Submit runs validate_case
// and estimate_case in a server thread, so the largest case the bounds of case/case_limits.h
// allow must be checked in a fraction of a second. The lattice walks count their work
// (lattice_work_done(), in units of Shape::cost()); these tests build the worst inputs the bounds
// allow and check that work against the budgets, which do not depend on the input. The time is
// printed, not checked: a loaded machine must not fail a test. The shipped cases stay within the
// budgets, so their estimates are exact counts, and sampled counts of large cases are close.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "case/anisotropy.h"
#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/lattice.h"
#include "case/load.h"
#include "case/validate.h"
#include "case/wall_thickness.h"

namespace sph {
namespace {

// What validate_case and one estimate_case together may do: the server runs both at Submit.
constexpr double kSubmitWork = kRegionCheckWork + 2 * kEstimateWork + kWallCheckWork;

struct Cost {
  double work = 0;
  double seconds = 0;
  std::vector<FieldError> errors;
  CaseEstimate estimate;
};

// validate_case then estimate_case, as sph-server's Submit runs them.
Cost submit_cost(const v1::Case& c, const char* what) {
  Cost cost;
  const double work0 = lattice_work_done();
  const auto t0 = std::chrono::steady_clock::now();
  cost.errors = validate_case(c);
  cost.estimate = estimate_case(c);
  cost.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cost.work = lattice_work_done() - work0;
  std::printf("%s: %.3g units of work (at most %.3g), %.3f s, %.4g particles estimated\n", what,
              cost.work, kSubmitWork, cost.seconds, cost.estimate.total());
  return cost;
}

std::string head(int dim, double dx) {
  char s[512];
  if (dim == 3)
    std::snprintf(s, sizeof s,
                  "name: \"worst\" dimension: 3 dx: %.17g\n"
                  "domain { lo { x: 0 y: 0 z: 0 } hi { x: 1 y: 1 z: 1 } }\n",
                  dx);
  else
    std::snprintf(s, sizeof s,
                  "name: \"worst\" dimension: 2 dx: %.17g\n"
                  "domain { lo { x: 0 y: 0 } hi { x: 1 y: 1 } }\n",
                  dx);
  return std::string(s) +
         "materials { name: \"water\" density: 1000 eos { sound_speed: 10 } }\n"
         "materials { name: \"steel\" phase: SOLID density: 7800 }\n"
         "time { end_time: 1 }\n";
}

std::string box3(double x0, double y0, double z0, double x1, double y1, double z1) {
  char s[256];
  std::snprintf(s, sizeof s, "box{lo{x:%g y:%g z:%g}hi{x:%g y:%g z:%g}}", x0, y0, z0, x1, y1, z1);
  return s;
}
std::string box2(double x0, double y0, double x1, double y1) {
  char s[256];
  std::snprintf(s, sizeof s, "box{lo{x:%g y:%g}hi{x:%g y:%g}}", x0, y0, x1, y1);
  return s;
}
std::string fluid(const std::string& shape) {
  return "fluids{material:\"water\" shape{" + shape + "}}\n";
}
std::string wall(const std::string& shape) {
  return "walls{shape{" + shape + "}}\n";
}
// A circle of n vertices around (0.5, 0.5).
std::string polygon(int n, double radius) {
  std::string s = "polygon{";
  char v[96];
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    std::snprintf(v, sizeof v, "vertices{x:%.9g y:%.9g}", 0.5 + radius * std::cos(a),
                  0.5 + radius * std::sin(a));
    s += v;
  }
  return s + "}";
}

void expect_within_budget(const Cost& cost) {
  EXPECT_TRUE(cost.errors.empty()) << join_errors(cost.errors);
  EXPECT_LE(cost.work, kSubmitWork);
  EXPECT_GT(cost.work, 0.1 * kSubmitWork);  // the input is as expensive as intended
}

// The input that took minutes: kMaxRegions regions of a million lattice points each, all
// overlapping, so that every fluid point was tested against every wall (16 + 16 such regions
// took 2 s, 512 + 512 would have taken about 20 minutes).
TEST(CaseValidationCost, OverlappingRegionsAtTheLimit) {
  std::string text = head(3, 0.01);
  for (int i = 0; i < kMaxRegions / 2; ++i) text += wall(box3(0, 0, 0, 1, 1, 0.3));
  for (int i = 0; i < kMaxRegions / 2; ++i) text += fluid(box3(0, 0, 0.3, 1, 1, 1));
  std::printf("%zu KB of text\n", text.size() / 1024);
  expect_within_budget(submit_cost(parse_case_text(text), "1024 overlapping regions, 3D"));
}

// One fluid of kMaxShapes - 1 balls: every lattice point tests each of them.
TEST(CaseValidationCost, UnionOfEveryShapeAllowed) {
  std::string shapes;
  char s[160];
  for (int i = 0; i < kMaxShapes - 1; ++i) {
    std::snprintf(s, sizeof s, "shapes{ball{center{x:0.5 y:0.5 z:0.5} radius:%g}}",
                  0.3 + 0.1 * i / kMaxShapes);
    shapes += s;
  }
  expect_within_budget(
      submit_cost(parse_case_text(head(3, 1.0 / 400) + fluid("union{" + shapes + "}")),
                  "a union of 1023 balls, 6.4e7 lattice points, 3D"));
}

// kMaxPolygonVertices in one polygon: each test visits every edge.
TEST(CaseValidationCost, PolygonOfEveryVertexAllowed) {
  const std::string text = head(2, 1.0 / 4000) + fluid(polygon(kMaxPolygonVertices, 0.45));
  std::printf("%zu KB of text\n", text.size() / 1024);
  expect_within_budget(
      submit_cost(parse_case_text(text), "a polygon of 1e5 vertices, 1.6e7 lattice points, 2D"));
}

// A wall of the largest polygon under every other region: each fluid point would test the
// polygon again, for each fluid (the claims a fluid region makes are not shared).
TEST(CaseValidationCost, PolygonWallUnderEveryRegion) {
  std::string text = head(2, 1.0 / 4000) + wall(polygon(kMaxPolygonVertices, 0.45));
  for (int i = 1; i < kMaxRegions; ++i) text += fluid(box2(0.1, 0.1, 0.9, 0.9));
  expect_within_budget(
      submit_cost(parse_case_text(text), "a 1e5-vertex wall under 1023 fluids, 2D"));
}

// The wall check tags every cell, so it runs only within kWallCheckWork: a one-layer floor
// (r_c = 3 dx needs two) is found on a domain the budget covers and not on a larger one.
TEST(CaseValidationCost, WallCheckRunsWithinItsBudget) {
  auto floor_case = [](int cells) {
    const double dx = 1.0 / cells;
    return parse_case_text(head(2, dx) + wall(box2(0, 0.5 - dx, 1, 0.5)) +
                           fluid(box2(0, 0.5, 1, 0.9)));
  };
  auto thin = [](const std::vector<FieldError>& errs) {
    return errs.size() == 1 && errs[0].field == "walls[0].shape" &&
           errs[0].message.find("is 1 particle layer thick") != std::string::npos;
  };
  // About 5.2 units a cell: 4 for the scan, a box's 3 at each fluid point (0.4 of the cells).
  const int inside = static_cast<int>(std::sqrt(kWallCheckWork / 6));
  const int outside = static_cast<int>(std::sqrt(kWallCheckWork / 3));
  const Cost cost = submit_cost(floor_case(inside), "the largest case the wall check takes, 2D");
  EXPECT_LE(cost.work, kSubmitWork);
  EXPECT_TRUE(thin(cost.errors)) << join_errors(cost.errors);
  const auto errs = validate_case(floor_case(outside));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
}

// Each error of a shape's vertices or points names its own field; a request of a few MB could
// make hundreds of MB of errors. The first kMaxReportedErrors are listed, the rest counted.
TEST(CaseValidationCost, ErrorsAreCapped) {
  std::string vertices;
  for (int i = 0; i < kMaxPolygonVertices; ++i) vertices += "vertices{x:0.5 y:0.5 z:1}";
  const auto errs =
      validate_case(parse_case_text(head(2, 0.01) + fluid("polygon{" + vertices + "}")));
  ASSERT_EQ(errs.size(), static_cast<std::size_t>(kMaxReportedErrors) + 1);
  EXPECT_EQ(errs[0].to_string(),
            "fluids[0].shape.polygon.vertices[0].z: must be 0 in a 2D case (got 1)");
  EXPECT_EQ(errs.back().to_string(), "and 99900 more errors (only the first 100 are listed)");
  // An unknown material names a few of those defined, not all of them in each error.
  std::string text = head(2, 0.01);
  for (int m = 0; m < 200; ++m)
    text += "materials{name:\"" + std::string(200, 'm') + std::to_string(m) +
            "\" density: 1 eos{sound_speed: 1}}\n";
  for (int i = 0; i < 50; ++i)
    text += "fluids{material:\"nope\" shape{" + box2(0.1, 0.1, 0.9, 0.9) + "}}\n";
  std::size_t bytes = 0;
  for (const auto& e : validate_case(parse_case_text(text))) bytes += e.to_string().size();
  std::printf("50 unknown materials among 202: %zu bytes of errors\n", bytes);
  EXPECT_LT(bytes, 150000u);
}

// The particles of a case counted one lattice point at a time, in the scene builder's claiming
// order as estimate_case counts them (walls each on their own, bodies outside walls, buffers
// outside both, fluids outside all three; explicit points all).
struct Counts {
  double walls = 0, bodies = 0, elastic = 0, fluids = 0;
};
Counts exact_counts(const v1::Case& c) {
  const int d = c.dimension();
  const double shell = default_shell_thickness(c);
  const LatticeSpec spec{d, c.dx(), to_point(c.lattice_origin())};
  Aabb clip{to_point(c.domain().lo()), to_point(c.domain().hi())};
  if (d == 2) clip.lo.z() = clip.hi.z() = 0;
  std::vector<std::unique_ptr<Shape>> walls, bodies, elastic, buffers;
  for (const auto& w : c.walls()) walls.push_back(compile_shape(w.shape(), d, shell));
  for (const auto& b : c.bodies()) bodies.push_back(compile_shape(b.shape(), d, shell));
  for (const auto& b : c.elastic_bodies()) elastic.push_back(compile_shape(b.shape(), d, shell));
  for (const auto& o : c.open_boundaries()) {
    v1::Shape box;
    *box.mutable_box() = o.region();
    buffers.push_back(compile_shape(box, d, shell));
  }
  auto taken = [](const std::vector<const std::vector<std::unique_ptr<Shape>>*>& by,
                  const Point3& p) {
    for (const auto* group : by)
      for (const auto& s : *group)
        if (s->contains(p)) return true;
    return false;
  };
  auto count = [&](const Shape& s,
                   const std::vector<const std::vector<std::unique_ptr<Shape>>*>& by,
                   const LatticeSpec* own = nullptr) {
    double n = 0;
    const bool all = s.explicit_points() != nullptr;
    for_each_lattice_point(s, own ? *own : spec, clip,
                           [&](const Point3& p) { n += all || !taken(by, p) ? 1 : 0; });
    return n;
  };
  Counts n;
  for (const auto& w : walls) n.walls += count(*w, {});
  for (const auto& b : bodies) n.bodies += count(*b, {&walls});
  for (std::size_t k = 0; k < elastic.size(); ++k) {
    // An anisotropic body's own lattice (case/anisotropy.h).
    const LatticeSpec own = elastic_lattice_spec(c, c.elastic_bodies(static_cast<int>(k)));
    n.elastic += count(*elastic[k], {&walls, &bodies}, &own);
  }
  for (const auto& o : buffers) n.fluids += count(*o, {&walls, &bodies, &elastic});
  for (const auto& f : c.fluids())
    n.fluids += count(*compile_shape(f.shape(), d, shell), {&walls, &bodies, &elastic, &buffers});
  return n;
}

std::vector<std::filesystem::path> shipped_cases() {
  std::vector<std::filesystem::path> files;
  std::vector<std::string> dirs = {"/cases", "/cases/studies"};
  for (const auto& e : std::filesystem::directory_iterator(std::string(SPHD_SOURCE_DIR) + "/tests"))
    if (std::filesystem::is_directory(e.path() / "cases"))
      dirs.push_back("/tests/" + e.path().filename().string() + "/cases");
  for (const auto& dir : dirs)
    for (const auto& e : std::filesystem::directory_iterator(std::string(SPHD_SOURCE_DIR) + dir))
      if (e.path().extension() == ".textproto") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The shipped cases need a small part of each budget, so their estimates are exact counts and
// what validation decides for them is decided on every lattice point.
TEST(CaseValidationCost, ShippedCasesAreCountedExactly) {
  double most = 0;
  std::string costliest;
  for (const auto& f : shipped_cases()) {
    const v1::Case c = load_case_file(f.string());
    const double work0 = lattice_work_done();
    const CaseEstimate e = estimate_case(c);
    const double work = lattice_work_done() - work0;
    if (work > most) most = work, costliest = f.filename().string();
    const Counts n = exact_counts(c);
    EXPECT_EQ(e.wall_particles, n.walls) << f.filename();
    EXPECT_EQ(e.rigid_particles, n.bodies) << f.filename();
    EXPECT_EQ(e.elastic_particles, n.elastic) << f.filename();
    EXPECT_EQ(e.fluid_particles, n.fluids) << f.filename();
  }
  std::printf("the costliest shipped estimate: %s, %.3g units (budget %.3g)\n", costliest.c_str(),
              most, kEstimateWork);
  EXPECT_LT(most, 0.5 * kEstimateWork);
}

// A case of 1.4e7 particles (a tank, the fluid in it and five balls) is counted on a sample; the
// estimate stays within half a percent of the exact count of each kind.
TEST(CaseValidationCost, SampledEstimatesAreClose) {
  std::string text = head(3, 1.0 / 256) +
                     wall("shell{inner{" + box3(0.05, 0.05, 0.05, 0.95, 0.95, 0.95) + "}}") +
                     fluid(box3(0.05, 0.05, 0.05, 0.95, 0.95, 0.8));
  for (int i = 0; i < 5; ++i) {
    char b[200];
    std::snprintf(b, sizeof b,
                  "bodies{material:\"steel\" shape{ball{center{x:%g y:0.5 z:0.4} radius:0.07}}}\n",
                  0.15 + 0.17 * i);
    text += b;
  }
  const v1::Case c = parse_case_text(text);
  const Cost cost = submit_cost(c, "a tank of 1.4e7 particles");
  EXPECT_TRUE(cost.errors.empty()) << join_errors(cost.errors);
  const Counts n = exact_counts(c);
  const CaseEstimate& e = cost.estimate;
  std::printf("walls %.0f (exact %.0f), bodies %.0f (%.0f), fluid %.0f (%.0f)\n", e.wall_particles,
              n.walls, e.rigid_particles, n.bodies, e.fluid_particles, n.fluids);
  EXPECT_NEAR(e.wall_particles, n.walls, 0.005 * n.walls);
  EXPECT_NEAR(e.rigid_particles, n.bodies, 0.005 * n.bodies);
  EXPECT_NEAR(e.fluid_particles, n.fluids, 0.005 * n.fluids);
  EXPECT_NEAR(e.total(), n.walls + n.bodies + n.fluids, 0.002 * e.total());
}

// Counted on a sample, a fluid mostly outside the domain is still refused, and one that
// overhangs it by a quarter is not.
TEST(CaseValidationCost, SampledRegionsAreStillCheckedAgainstTheDomain) {
  const std::string base = head(3, 1.0 / 300);
  auto errs = validate_case(parse_case_text(base + fluid(box3(0.1, 0.1, 0.1, 0.9, 0.9, 0.6)) +
                                            fluid(box3(0.1, 0.1, 0.7, 0.9, 0.9, 2.5))));
  EXPECT_EQ(errs.size(), 1u) << join_errors(errs);
  EXPECT_TRUE(!errs.empty() && errs[0].field == "fluids[1].shape" &&
              errs[0].message.find("lies mostly outside the domain") != std::string::npos &&
              errs[0].message.find("(counted on a sample)") != std::string::npos)
      << join_errors(errs);
  errs = validate_case(parse_case_text(base + fluid(box3(0.1, 0.1, 0.1, 0.9, 0.9, 0.6)) +
                                       fluid(box3(0.1, 0.1, 0.7, 0.9, 0.9, 1.1))));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
}

}  // namespace
}  // namespace sph
