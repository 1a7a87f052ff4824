// The error evaluators of convergence studies (analysis/) against inputs whose errors are
// known: exact fields give zero, a known perturbation gives its size.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/channel_flow.h"
#include "analysis/conduction.h"
#include "analysis/hydrostatic.h"
#include "analysis/order_fit.h"
#include "analysis/richardson.h"
#include "analysis/series_data.h"
#include "analysis/taylor_green.h"
#include "case/load.h"

namespace sph::analysis {
namespace {

// A snapshot with particles at the given (x, y), kinds and zero velocity.
Snapshot snapshot_at(const std::vector<std::pair<double, double>>& xy, std::uint8_t kind,
                     double t) {
  Snapshot s;
  s.time = t;
  for (std::size_t i = 0; i < xy.size(); ++i) {
    s.position.insert(s.position.end(), {xy[i].first, xy[i].second, 0});
    s.velocity.insert(s.velocity.end(), {0, 0, 0});
    s.density.push_back(1);
    s.pressure.push_back(0);
    s.mass.push_back(0);
    s.id.push_back(static_cast<std::int64_t>(i));
    s.kind.push_back(kind);
  }
  return s;
}

void append(Snapshot& s, const Snapshot& w) {
  s.position.insert(s.position.end(), w.position.begin(), w.position.end());
  s.velocity.insert(s.velocity.end(), w.velocity.begin(), w.velocity.end());
  s.density.insert(s.density.end(), w.density.begin(), w.density.end());
  s.pressure.insert(s.pressure.end(), w.pressure.begin(), w.pressure.end());
  s.mass.insert(s.mass.end(), w.mass.begin(), w.mass.end());
  for (std::size_t i = 0; i < w.size(); ++i) s.id.push_back(static_cast<std::int64_t>(s.id.size()));
  s.kind.insert(s.kind.end(), w.kind.begin(), w.kind.end());
}

v1::ChannelFlowReference poiseuille_reference() {
  v1::ChannelFlowReference r;
  r.set_lower_wall(0);
  r.set_height(1);
  r.set_kinematic_viscosity(0.01);
  r.set_body_force(0.1);
  return r;
}

TEST(ReferenceEvaluators, StartupChannelFlowsTendToTheSteadyProfiles) {
  // Poiseuille: u = F y (L - y) / (2 nu); Couette: u = V y / L; both start from rest.
  EXPECT_NEAR(poiseuille_startup(0.5, 1e4, 0.1, 0.01, 1), 1.25, 1e-9);
  EXPECT_NEAR(poiseuille_startup(0.25, 1e4, 0.1, 0.01, 1), 0.1 * 0.25 * 0.75 / 0.02, 1e-9);
  EXPECT_NEAR(poiseuille_startup(0.5, 0, 0.1, 0.01, 1), 0, 1e-4);
  EXPECT_NEAR(couette_startup(0.3, 1e4, 1.25, 0.01, 1), 0.375, 1e-9);
  EXPECT_NEAR(couette_startup(0.3, 1e-3, 1.25, 0.01, 1), 0, 1e-3);
  EXPECT_DOUBLE_EQ(channel_flow_velocity_scale(poiseuille_reference()), 1.25);
}

TEST(ReferenceEvaluators, ChannelFlowErrorIsTheMeanDeviationOverFluid) {
  const auto r = poiseuille_reference();
  std::vector<std::pair<double, double>> xy;
  for (int i = 0; i < 20; ++i) xy.emplace_back(0.1, (i + 0.5) / 20);
  Snapshot s = snapshot_at(xy, 0, 10.0);
  for (std::size_t i = 0; i < s.size(); ++i)
    s.velocity[3 * i] = channel_flow_velocity(r, s.position[3 * i + 1], s.time);
  EXPECT_NEAR(channel_flow_error(s, r).error, 0, 1e-12);
  for (std::size_t i = 0; i < s.size(); ++i) s.velocity[3 * i] += (i % 2 ? 1 : -1) * 0.0125;
  EXPECT_NEAR(channel_flow_error(s, r).error, 0.01, 1e-12);  // 0.0125 / 1.25
  // Wall particles do not count.
  s.kind[0] = 1;
  s.velocity[0] = 100;
  EXPECT_NEAR(channel_flow_error(s, r).error, 0.01, 1e-12);
}

TEST(ReferenceEvaluators, HydrostaticBottomPressureAgainstDepthFromMass) {
  // Fluid of depth H = 0.9 in a tank 2 wide (rho = 1): mass 1.8; wall layer at y = -dx/2.
  const double dx = 0.1, g = 1, H = 0.9;
  Snapshot s = snapshot_at({{0.5, 0.45}, {1.5, 0.45}}, 0, 8);
  s.mass = {0.9, 0.9};
  Snapshot w = snapshot_at({{0.9, -0.05}, {1.1, -0.05}, {1.1, -0.15}, {3.0, -0.05}}, 1, 8);
  const double expected = g * (H + dx / 2);
  w.pressure = {expected * 1.02, expected * 1.02, 99, 99};  // deeper layer and outside the band
  append(s, w);
  v1::HydrostaticReference r;
  r.set_bottom(0);
  r.set_width(2);
  r.set_x_min(0.5);
  r.set_x_max(1.5);
  const Measurement m = hydrostatic_error(s, r, 1.0, g, dx);
  EXPECT_NEAR(m.error, 0.02, 1e-12) << m.detail;
  r.set_x_min(2.5);
  r.set_x_max(2.6);
  EXPECT_THROW(hydrostatic_error(s, r, 1.0, g, dx), std::runtime_error);
}

TEST(ReferenceEvaluators, TaylorGreenDecayRateFit) {
  v1::TaylorGreenReference r;
  r.set_kinematic_viscosity(0.01);
  r.set_wavelength(1);
  r.set_fit_start(0.1);
  const double exact = -8 * std::numbers::pi * std::numbers::pi * 0.01;
  EXPECT_NEAR(taylor_green_decay_rate(r), exact, 1e-12);
  std::vector<double> t, v;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(0.02 * k);
    // A start-up transient before t = 0.1 that the fit must skip, then 3% too slow a decay.
    v.push_back(t.back() < 0.1 ? 5.0 : std::exp(0.97 * exact * t.back()));
  }
  const Measurement m = taylor_green_error(t, v, r);
  EXPECT_NEAR(m.error, 0.03, 1e-9) << m.detail;
  EXPECT_NEAR(m.quantity, 0.97 * exact, 1e-9);
}

TEST(ReferenceEvaluators, TaylorGreenVelocityFieldError) {
  v1::TaylorGreenReference r;
  r.set_kinematic_viscosity(0.01);
  r.set_wavelength(1);
  r.set_amplitude(2);
  r.set_measure(v1::TaylorGreenReference::VELOCITY_FIELD);
  std::vector<std::pair<double, double>> xy;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) xy.emplace_back((i + 0.5) / 10, (j + 0.5) / 10);
  Snapshot s = snapshot_at(xy, 0, 0.5);
  const double k = 2 * std::numbers::pi, a = 2 * std::exp(taylor_green_decay_rate(r) * 0.5);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    // 3% too weak everywhere: the error is 3% of the amplitude times the mean |profile|.
    s.velocity[3 * i] = -0.97 * a * std::cos(k * x) * std::sin(k * y);
    s.velocity[3 * i + 1] = 0.97 * a * std::sin(k * x) * std::cos(k * y);
  }
  double mean_profile = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double x = s.position[3 * i], y = s.position[3 * i + 1];
    mean_profile +=
        std::hypot(std::cos(k * x) * std::sin(k * y), std::sin(k * x) * std::cos(k * y));
  }
  mean_profile /= static_cast<double>(s.size());
  const Measurement m = taylor_green_field_error(s, r, -0.8);
  EXPECT_NEAR(m.error, 0.03 * mean_profile, 1e-12) << m.detail;
  EXPECT_EQ(m.quantity, -0.8);
}

TEST(ReferenceEvaluators, ConductionMaxErrorRelativeToTheTemperatureJump) {
  v1::ConductionReference r;
  r.set_boundary(0);
  r.set_boundary_value(1);
  r.set_initial_value(0);
  r.set_diffusivity(1);
  r.set_x_max(0.5);
  EXPECT_NEAR(conduction_profile(r, 0.1, 0.01), std::erfc(0.1 / (2 * 0.1)), 1e-12);
  std::vector<std::pair<double, double>> xy;
  for (int i = 0; i < 50; ++i) xy.emplace_back((i + 0.5) / 50, 0.1);
  const Snapshot s = snapshot_at(xy, 0, 0.01);
  std::vector<double> T;
  for (std::size_t i = 0; i < s.size(); ++i)
    T.push_back(conduction_profile(r, s.position[3 * i], s.time));
  EXPECT_NEAR(conduction_error(s, T, r).error, 0, 1e-15);
  T[3] += 0.004;  // inside x_max: counts
  T[40] += 0.5;   // beyond x_max: ignored
  EXPECT_NEAR(conduction_error(s, T, r).error, 0.004, 1e-12);
  r.set_boundary_value(3);  // a jump of 3 scales the error down
  for (std::size_t i = 0; i < s.size(); ++i)
    T[i] = conduction_profile(r, s.position[3 * i], s.time);
  T[3] += 0.003;
  EXPECT_NEAR(conduction_error(s, T, r).error, 0.001, 1e-12);
}

TEST(ReferenceEvaluators, SeriesComponentsAndSums) {
  // Three samples of rows [a, b, NaN] (an unused body slot).
  const double nan = std::nan("");
  const std::vector<double> series = {1, 10, nan, 2, 20, nan, 3, 30, nan};
  EXPECT_EQ(series_component(series, 3, 1, false, "f"), (std::vector<double>{10, 20, 30}));
  EXPECT_EQ(series_component(series, 3, 0, true, "f"), (std::vector<double>{11, 22, 33}));
  try {
    series_component(series, 3, 3, false, "reference.series_data");
    FAIL() << "expected an error naming the component";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("reference.series_data.component"), std::string::npos)
        << e.what();
  }
}

TEST(ReferenceEvaluators, SeriesAgainstDataPointwiseAndWindowMean) {
  v1::SeriesDataReference r;
  // Data in scaled units: time T = 2 t, value V = 10 v. The series is 5% above the data.
  for (int k = 0; k <= 10; ++k) {
    r.add_times(0.4 * k);
    r.add_values(1 + 0.4 * k);
  }
  r.set_time_scale(2);
  r.set_value_scale(10);
  std::vector<double> t, v;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(0.02 * k);
    v.push_back(1.05 * (1 + 2 * t.back()) / 10);
  }
  r.set_t_min(0.5);
  Measurement m = series_data_error(t, v, r);
  EXPECT_NEAR(m.error, 0.05, 1e-9) << m.detail;
  // A window symmetric about the data points and the samples: both means are 1 + 2.
  r.set_metric(v1::SeriesDataReference::WINDOW_MEAN);
  r.set_t_min(0.6);
  r.set_t_max(3.4);
  m = series_data_error(t, v, r);
  EXPECT_NEAR(m.error, 0.05, 1e-9) << m.detail;
  r.set_t_min(10);
  r.set_t_max(11);
  EXPECT_THROW(series_data_error(t, v, r), std::runtime_error);
}

TEST(ReferenceEvaluators, RichardsonRecoversTheLimitAndTheOrder) {
  // q = 2 + 0.5 dx^2 on a sqrt(2) ladder.
  const std::vector<double> dx = {0.1, 0.1 / std::sqrt(2.0), 0.05, 0.05 / std::sqrt(2.0)};
  std::vector<double> q;
  for (double h : dx) q.push_back(2 + 0.5 * h * h);
  auto est = richardson_extrapolate(dx, q, std::nullopt, std::nullopt);
  ASSERT_TRUE(est.ok) << est.problem;
  EXPECT_TRUE(est.order_estimated);
  EXPECT_NEAR(est.order, 2, 1e-6);
  EXPECT_NEAR(est.extrapolated, 2, 1e-9);
  for (std::size_t k = 0; k < dx.size(); ++k)
    EXPECT_NEAR(est.errors[k], 0.25 * dx[k] * dx[k], 1e-8);
  // Uneven spacing, assumed order, given scale.
  const std::vector<double> h2 = {0.1, 0.03};
  est = richardson_extrapolate(h2, {2 + 0.3 * 0.1, 2 + 0.3 * 0.03}, 1.0, 4.0);
  ASSERT_TRUE(est.ok);
  EXPECT_NEAR(est.extrapolated, 2, 1e-12);
  EXPECT_NEAR(est.errors[0], 0.3 * 0.1 / 4, 1e-12);
  // Oscillating values have no order.
  est = richardson_extrapolate({0.1, 0.07, 0.05}, {1.0, 1.2, 1.1}, std::nullopt, std::nullopt);
  EXPECT_FALSE(est.ok);
  EXPECT_NE(est.problem.find("monotonically"), std::string::npos) << est.problem;
  EXPECT_FALSE(richardson_extrapolate({0.1, 0.05}, {1, 2}, std::nullopt, std::nullopt).ok);
}

TEST(ReferenceEvaluators, PowerLawFitGivesOrderAndTargets) {
  std::vector<double> x = {0.1, 0.07, 0.05, 0.035}, y;
  for (double v : x) y.push_back(3 * std::pow(v, 1.5));
  y.push_back(-1);  // skipped
  x.push_back(0.01);
  const PowerFit f = fit_power_law(x, y);
  ASSERT_TRUE(f.ok);
  EXPECT_EQ(f.points, 4);
  EXPECT_NEAR(f.slope, 1.5, 1e-12);
  EXPECT_NEAR(f.value_at(0.2), 3 * std::pow(0.2, 1.5), 1e-12);
  EXPECT_NEAR(f.x_for(0.01), std::pow(0.01 / 3, 1 / 1.5), 1e-12);
  EXPECT_FALSE(fit_power_law({1}, {1}).ok);
}

}  // namespace
}  // namespace sph::analysis
