// Walls growing into the fluid (solver/boundaries/wall_growth.h; Reder et al. 2021 sec. 3.7).
// A flat floor growing at v into still fluid: the grown thickness (particles taken x dx^2 /
// width) must follow s(t) = v t within half a layer and its least-squares speed v within 5%,
// with the total mass (fluid plus grown) conserved to round-off. A disk resting above the
// floor is engulfed when the front reaches its lowest particle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "case/load.h"
#include "tests/support/growing_floor.h"
#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

// The front from the particles a growing wall took: the times at which half of the k-th
// layer has gone (the front then stands at that layer's centre, (k - 1/2) dx from the initial
// surface) and the least-squares speed through those points, which a staircase of whole
// layers does not bias.
struct FrontCrossings {
  std::vector<double> t, s;
  double speed = 0;
};

FrontCrossings front_crossings(const std::vector<double>& t, const std::vector<double>& taken,
                               double per_layer, double dx) {
  FrontCrossings f;
  int layer = 1;
  for (std::size_t k = 0; k < t.size(); ++k)
    while (taken[k] >= (layer - 0.5) * per_layer) {
      // Between the samples before and at the crossing, linearly: the count jumps within
      // the interval, so this halves the error of taking the later sample.
      const double goal = (layer - 0.5) * per_layer;
      const double w = k == 0 ? 1.0 : (goal - taken[k - 1]) / (taken[k] - taken[k - 1]);
      f.t.push_back(k == 0 ? t[k] : t[k - 1] + w * (t[k] - t[k - 1]));
      f.s.push_back((layer - 0.5) * dx);
      ++layer;
    }
  const double m = static_cast<double>(f.t.size());
  double st = 0, ss = 0, stt = 0, sts = 0;
  for (std::size_t k = 0; k < f.t.size(); ++k) {
    st += f.t[k];
    ss += f.s[k];
    stt += f.t[k] * f.t[k];
    sts += f.t[k] * f.s[k];
  }
  f.speed = m >= 2 ? (m * sts - st * ss) / (m * stt - st * st) : 0.0;
  return f;
}

// The fluid particles (ids of `fluid_ids`) a wall took inside the strip x_lo <= x < x_hi
// beyond its initial surface at y = surface (bottom: above it; top: below), per snapshot.
FrontCrossings strip_front(const test::ResultReader& rr, const std::set<std::int64_t>& fluid_ids,
                           double x_lo, double x_hi, bool bottom, double surface, double dx) {
  std::vector<double> t, taken;
  for (int k = 0; k < rr.snapshot_count(); ++k) {
    const test::Snapshot snap = rr.snapshot(k);
    double n = 0;
    for (std::size_t i = 0; i < snap.size(); ++i) {
      const double x = snap.position[3 * i], y = snap.position[3 * i + 1];
      if (snap.kind[i] != 1 || !fluid_ids.count(snap.id[i]) || x < x_lo || x >= x_hi) continue;
      if (bottom ? (y > surface && y < 0.5) : (y < surface && y > 0.5)) n += 1;
    }
    t.push_back(snap.time);
    taken.push_back(n);
  }
  return front_crossings(t, taken, std::round((x_hi - x_lo) / dx), dx);
}

struct Front {
  double speed_error = 0;  // |fitted - v| / v
  std::size_t layers = 0;  // crossings fitted
  double worst_lag = 0;    // max |h(t) - s(t)| [m]
  double mass_error = 0;   // max |fluid + grown - initial| / initial
};

// The floor's front (width `width`, one layer width/dx particles) against s(t) = v t.
Front measure_front(const test::ResultReader& rr, double v, double dx, double width,
                    double initial_mass) {
  const auto t = rr.series("wall_growth/time");
  const auto n = rr.series("wall_growth/floor/particles");
  const auto grown = rr.series("wall_growth/floor/mass");
  const auto s = rr.series("wall_growth/floor/front");
  const auto fluid = rr.series("diagnostics/mass");
  Front f;
  for (std::size_t k = 0; k < t.size(); ++k) {
    f.worst_lag = std::max(f.worst_lag, std::abs(n[k] * dx * dx / width - s[k]));
    f.mass_error =
        std::max(f.mass_error, std::abs(fluid[k] + grown[k] - initial_mass) / initial_mass);
  }
  const FrontCrossings c = front_crossings(t, n, std::round(width / dx), dx);
  f.speed_error = std::abs(c.speed - v) / v;
  f.layers = c.t.size();
  return f;
}

TEST(GrowingWalls, AFlatWallAdvancesAtItsSpeedAndConservesMass) {
  const double v = 0.2, dx = 0.04;
  const std::string out = test::output_dir("growing_floor");
  const RunOutcome r = test::run(parse_case_text(test::growing_floor(v, 2.0)), out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const double m0 = rr.series("diagnostics/mass").front();
  const Front f = measure_front(rr, v, dx, 0.4, m0);
  const auto n = rr.series("wall_growth/floor/particles");
  const auto vmax = rr.series("diagnostics/max_speed");
  const double speed = *std::max_element(vmax.begin(), vmax.end());
  std::printf(
      "growing floor, v = %.2f m/s, dx = %.2f, to s = %.2f (%.0f layers): %.0f particles taken, "
      "front speed over %zu layer crossings off by %.2e (limit 5%%), largest |h - s| %.4f m = "
      "%.2f dx (limit 0.5 dx), mass error %.1e, largest fluid speed %.2e m/s\n",
      v, dx, v * 2.0, v * 2.0 / dx, n.back(), f.layers, f.speed_error, f.worst_lag,
      f.worst_lag / dx, f.mass_error, speed);
  EXPECT_NEAR(n.back(), 10.0 * 10.0, 0.5);  // ten layers of ten
  EXPECT_LT(f.speed_error, 0.05);
  EXPECT_LE(f.worst_lag, 0.5 * dx + 1e-9);
  EXPECT_LT(f.mass_error, 1e-13);
  EXPECT_LT(speed, 0.5 * v);  // the fluid stays nearly at rest
}

TEST(GrowingWalls, TheFrontEngulfsADiskItReaches) {
  // A neutrally buoyant disk, d = 0.2, at rest with its lowest particles at y = 0.22: the
  // front reaches them at t = 0.22 / v = 0.55 s.
  const double v = 0.4;
  const std::string out = test::output_dir("growing_floor_disk");
  const RunOutcome r = test::run(
      parse_case_text(test::growing_floor(
          v, 0.8,
          R"(bodies { name: "disk" material: "solid" shape { ball { center { x: 0.2 y: 0.3 } radius: 0.1 } } })")),
      out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot first = rr.snapshot(0), last = rr.last();
  double lowest = 1e300, body_mass = 0, total0 = 0, total1 = 0;
  std::size_t rigid_before = 0, rigid_after = 0;
  for (std::size_t i = 0; i < first.size(); ++i)
    if (first.kind[i] == 2) {
      lowest = std::min(lowest, first.position[3 * i + 1]);
      body_mass += first.mass[i];
      ++rigid_before;
    }
  for (std::size_t i = 0; i < first.size(); ++i) total0 += first.mass[i];
  for (std::size_t i = 0; i < last.size(); ++i) {
    total1 += last.mass[i];
    if (last.kind[i] == 2) ++rigid_after;
  }
  const auto t = rr.series("wall_growth/time"), e = rr.series("wall_growth/engulfed_bodies");
  std::size_t k = 0;
  while (k < e.size() && e[k] < 1) ++k;
  ASSERT_LT(k, e.size()) << "the disk was not engulfed by t = " << t.back();
  const double expected = lowest / v;
  const auto fluid = rr.series("diagnostics/mass"), grown = rr.series("wall_growth/floor/mass");
  const double fluid_mass = fluid.front();
  const double mass_error =
      std::abs(fluid.back() + grown.back() - fluid_mass - body_mass) / (fluid_mass + body_mass);
  std::printf(
      "disk on a growing floor (v = %.1f m/s): lowest disk particle at y = %.3f, engulfed "
      "between t = %.3f and %.3f s, expected %.4f s; %zu rigid particles before, %zu after; "
      "mass error %.1e, particle masses summed %.1e apart\n",
      v, lowest, k > 0 ? t[k - 1] : 0.0, t[k], expected, rigid_before, rigid_after, mass_error,
      std::abs(total1 - total0) / total0);
  EXPECT_EQ(e.back(), 1.0);
  EXPECT_EQ(rigid_after, 0u);
  // The engulfed body's particles keep their masses as wall particles.
  EXPECT_LT(std::abs(total1 - total0) / total0, 1e-13);
  EXPECT_GT(rigid_before, 0u);
  EXPECT_GE(expected, k > 0 ? t[k - 1] : 0.0);
  EXPECT_LE(expected, t[k] + 1e-9);
  EXPECT_LT(mass_error, 1e-13);
}

// The shipped lamellar channel, at its dx = H/20 or finer: the fluid again one region per
// particle row, each with the parabolic profile's velocity at the row's centre.
void check_lamellar_channel(double dx, const std::string& name) {
  v1::Case c = test::load_case("lamellar_channel_2d");
  c.mutable_output()->set_interval(0.01);  // the strips' fronts are read from the snapshots
  const double ub = 1.0, H = 1.0;
  if (dx != c.dx()) {
    const v1::FluidRegion row = c.fluids(0);
    c.clear_fluids();
    const int rows = static_cast<int>(std::lround(H / dx));
    for (int k = 0; k < rows; ++k) {
      v1::FluidRegion* f = c.add_fluids();
      *f = row;
      f->set_name("row" + std::to_string(k));
      const double y = (k + 0.5) * dx;
      f->mutable_initial_velocity()->set_x(6 * ub * y * (H - y) / (H * H));
      f->mutable_shape()->mutable_box()->mutable_lo()->set_y(k * dx);
      f->mutable_shape()->mutable_box()->mutable_hi()->set_y((k + 1) * dx);
    }
    c.set_dx(dx);
  }
  const std::string out = test::output_dir(name);
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  test::ResultReader rr(out + "/result.h5");
  const test::Snapshot first = rr.snapshot(0);
  std::set<std::int64_t> fluid_ids;
  double fluid0 = 0, bodies0 = 0;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if (first.kind[i] == 0) {
      fluid_ids.insert(first.id[i]);
      fluid0 += first.mass[i];
    }
    if (first.kind[i] == 2) bodies0 += first.mass[i];
  }
  // The middle half of the lamellae no disk starts over (the disks start over the others),
  // away from the faster phase's overgrowth of its neighbours' edges (sqrt(0.30^2 - 0.24^2)
  // = 0.18 u_b t, 0.18 H at the end, from each edge).
  struct Strip {
    const char* name;
    double x_c;
    bool bottom;
    double speed;
  };
  const Strip strips[] = {{"fast, bottom", 2.5, true, 0.30 * ub},
                          {"slow, bottom", 3.5, true, 0.24 * ub},
                          {"fast, top", 1.5, false, 0.30 * ub},
                          {"slow, top", 0.5, false, 0.24 * ub}};
  for (const Strip& st : strips) {
    const FrontCrossings f = strip_front(rr, fluid_ids, st.x_c - 0.25, st.x_c + 0.25, st.bottom,
                                         st.bottom ? 0.0 : 1.0, dx);
    const double error = (f.speed - st.speed) / st.speed;
    std::printf(
        "lamellar channel (H/dx = %.0f), %s lamella: %zu layers taken by t = %.2f, front speed "
        "%.4f u_b (prescribed %.2f u_b), error %+.2f%% (limit 5%%)\n",
        H / dx, st.name, f.t.size(), f.t.empty() ? 0.0 : f.t.back(), f.speed / ub, st.speed / ub,
        100 * error);
    EXPECT_GE(f.t.size(), 4u) << st.name;
    EXPECT_LT(std::abs(error), 0.05) << st.name;
  }
  const auto engulfed = rr.series("wall_growth/engulfed_bodies");
  const auto t = rr.series("wall_growth/time");
  std::vector<double> when;
  for (std::size_t k = 1; k < engulfed.size(); ++k)
    for (double n = engulfed[k - 1]; n < engulfed[k]; ++n) when.push_back(t[k]);
  const double fluid1 = rr.series("diagnostics/mass").back();
  const double grown =
      rr.series("wall_growth/fast/mass").back() + rr.series("wall_growth/slow/mass").back();
  const double mass_error = std::abs(fluid1 + grown - fluid0 - bodies0) / (fluid0 + bodies0);
  std::printf("lamellar channel: %.0f of 4 disks engulfed (at t =", engulfed.back());
  for (const double w : when) std::printf(" %.2f", w);
  std::printf("), mass error %.1e\n", mass_error);
  EXPECT_EQ(engulfed.back(), 4.0);
  EXPECT_LT(mass_error, 1e-13);
}

TEST(GrowingWalls, LamellarChannelFrontsAdvanceAtTheirSpeedsAndEngulfTheDisks) {
  check_lamellar_channel(0.05, "lamellar_channel");
}

// Twice as fine (H/dx = 40, 8300 particles, about half a minute): run by hand with
// --gtest_also_run_disabled_tests; docs/growing_walls.md has its numbers.
TEST(GrowingWalls, DISABLED_LamellarChannelFine) {
  check_lamellar_channel(0.025, "lamellar_channel_fine");
}

}  // namespace
}  // namespace sph
