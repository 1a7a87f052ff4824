// The period reference of convergence studies (reference.series_period, analysis/
// series_period.h) against sampled analytic oscillations, and its validation, which names the
// field and the limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/series_period.h"
#include "case/load.h"
#include "case/validate.h"
#include "tests/support/field_errors.h"

namespace sph::analysis {
namespace {

using sph::testing::has_error;
constexpr double kPi = std::numbers::pi;

struct Sampled {
  std::vector<double> t, v;
};

// f sampled every dt on [0, end].
template <class F>
Sampled sample(F f, double dt, double end) {
  Sampled s;
  for (int k = 0; k * dt <= end; ++k) {
    s.t.push_back(k * dt);
    s.v.push_back(f(k * dt));
  }
  return s;
}

v1::SeriesPeriodReference reference(double period) {
  v1::SeriesPeriodReference r;
  r.set_series("elastic/plate/displacement");
  r.set_component(1);
  r.set_period(period);
  return r;
}

TEST(SeriesPeriod, CosineAboutAMeanWithinTheInterpolationBound) {
  // y = 0.3 + 2 cos(2 pi t / T): crossings of 0.3 at T/4, 3T/4, 5T/4, ...; the first period
  // runs from the first to the third. Linear interpolation misplaces the zero of a sine
  // sampled every dt by at most 0.016 (omega dt)^3 / omega (the chord's cubic term, largest at
  // a = 0.21 of the interval), so the period is off by at most 2 x 0.016 (omega dt)^3 / (2 pi).
  const double T = 0.254032, mean = 0.3;
  auto r = reference(T);
  r.set_mean(mean);
  for (const int per_period : {10, 25, 50, 200}) {
    const double dt = T / per_period / 1.0371;  // not commensurate with T
    const Sampled s =
        sample([&](double t) { return mean + 2 * std::cos(2 * kPi * t / T); }, dt, 1.6 * T);
    const Measurement m = series_period_error(s.t, s.v, r);
    const double theta = 2 * kPi * dt / T;
    const double bound = 2 * 0.0161 * std::pow(theta, 3) / (2 * kPi);
    std::printf("cosine, %3d samples per period: T = %.9f vs %.9f, error %.3e (bound %.3e); %s\n",
                per_period, m.quantity, T, m.error, bound, m.detail.c_str());
    EXPECT_LE(m.error, bound);
    EXPECT_NEAR(m.quantity, T, bound * T);
  }
}

TEST(SeriesPeriod, DampedOscillationKeepsItsZeroCrossings) {
  // A Kelvin-Voigt-like decay, y = exp(-zeta omega t) sin(omega_d t): the zeros stay exactly
  // pi / omega_d apart however fast the amplitude falls. Cycles 2 to 4, from a start on a
  // crossing.
  const double omega = 2 * kPi / 0.25, zeta = 0.05, omega_d = omega * std::sqrt(1 - zeta * zeta);
  const double Td = 2 * kPi / omega_d;
  auto r = reference(Td);
  r.set_starts_at_crossing(true);
  r.set_first_cycle(2);
  r.set_cycles(3);
  const Sampled s = sample(
      [&](double t) { return std::exp(-zeta * omega * t) * std::sin(omega_d * t); }, 5e-4, 1.2);
  const Measurement m = series_period_error(s.t, s.v, r);
  std::printf("damped sine: T = %.9f vs %.9f (error %.3e); %s\n", m.quantity, Td, m.error,
              m.detail.c_str());
  EXPECT_LT(m.error, 1e-7);
}

TEST(SeriesPeriod, CrossingsCountTheStartAndSamplesOnTheMean) {
  // Exactly representable crossings: samples on the mean are the crossings themselves.
  const std::vector<double> t = {0, 0.5, 1.0, 1.6, 2.2, 2.6, 3.0, 3.5, 4.4, 4.7, 5.0};
  const std::vector<double> v = {0, 1, 0, -1, 0, 1, 0, -2, 0, 1, 1};
  EXPECT_EQ(mean_crossings(t, v, 0, true), (std::vector<double>{0, 1.0, 2.2, 3.0, 4.4}));
  // Without starts_at_crossing the first sample (on the mean) takes no side.
  EXPECT_EQ(mean_crossings(t, v, 0, false), (std::vector<double>{1.0, 2.2, 3.0, 4.4}));
  // Cycle 1 from the start: 0 to 2.2; cycle 2: 2.2 to 4.4; their mean 2.2.
  auto r = reference(2.0);
  r.set_starts_at_crossing(true);
  EXPECT_DOUBLE_EQ(series_period_error(t, v, r).quantity, 2.2);
  EXPECT_NEAR(series_period_error(t, v, r).error, 0.1, 1e-12);
  r.set_cycles(2);
  EXPECT_DOUBLE_EQ(series_period_error(t, v, r).quantity, 2.2);
  // Without the start, cycle 1 runs from 1.0 to 3.0.
  r.set_starts_at_crossing(false);
  r.clear_cycles();
  EXPECT_DOUBLE_EQ(series_period_error(t, v, r).quantity, 2.0);
  EXPECT_DOUBLE_EQ(series_period_error(t, v, r).error, 0.0);
  // Linear interpolation between a sample above and one below: 1 at t = 0, -3 at t = 1.
  EXPECT_EQ(mean_crossings({0, 1}, {1, -3}, 0, false), (std::vector<double>{0.25}));
  // The sample-0 value is ignored when the series starts on a crossing (no duplicate).
  EXPECT_EQ(mean_crossings({0, 1, 2}, {0.5, 1, -1}, 0, true), (std::vector<double>{0, 1.5}));
}

TEST(SeriesPeriod, TooFewCrossingsNameTheReferenceAndTheEndTime) {
  const double T = 0.25;
  auto r = reference(T);
  r.set_starts_at_crossing(true);
  r.set_first_cycle(2);
  const Sampled s = sample([&](double t) { return std::sin(2 * kPi * t / T); }, 1e-3, 0.4);
  try {
    series_period_error(s.t, s.v, r);
    FAIL() << "expected an error: the run covers 1.6 periods, cycle 2 needs 2";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("reference.series_period"), std::string::npos) << what;
    EXPECT_NE(what.find("time.end_time"), std::string::npos) << what;
  }
  EXPECT_THROW(series_period_error({}, {}, r), std::runtime_error);
}

v1::Case plate_study() {
  return load_case_file(std::string(SPHD_SOURCE_DIR) +
                        "/cases/studies/oscillating_plate_2d.textproto");
}

TEST(SeriesPeriod, ValidationNamesTheFieldAndTheLimit) {
  const v1::Case ok = plate_study();
  auto errs = validate_case(ok);
  EXPECT_TRUE(errs.empty()) << join_errors(errs);

  auto with = [&](const std::string& text) {
    v1::Case c = ok;
    c.mutable_reference()->clear_series_period();
    v1::Case patch = parse_case_text("reference { series_period { " + text + " } }");
    c.mutable_reference()->MergeFrom(patch.reference());
    return validate_case(c);
  };
  const std::string plate = "series: \"elastic/plate/displacement\" ";
  errs = with(plate + "component: 2 period: 0.254");
  EXPECT_TRUE(has_error(errs, "reference.series_period.component", "must be below 2"))
      << join_errors(errs);
  errs = with(plate + "component: -1 period: 0");
  EXPECT_TRUE(has_error(errs, "reference.series_period.component", ">= 0"));
  EXPECT_TRUE(has_error(errs, "reference.series_period.period", "must be > 0"));
  errs = with("series: \"elastic/beam/displacement\" period: 0.254");
  EXPECT_TRUE(has_error(errs, "reference.series_period.series", "elastic bodies"))
      << join_errors(errs);
  errs = with("series: \"elastic/plate/velocity\" period: 0.254");
  EXPECT_TRUE(has_error(errs, "reference.series_period.series", "strain_energy"));
  errs = with("series: \"elastic/plate/strain_energy\" component: 1 period: 0.254");
  EXPECT_TRUE(has_error(errs, "reference.series_period.component", "must be below 1"));
  errs = with(plate + "period: 0.254 first_cycle: 0 cycles: 2000000");
  EXPECT_TRUE(has_error(errs, "reference.series_period.first_cycle", "[1, 1000000]"));
  EXPECT_TRUE(has_error(errs, "reference.series_period.cycles", "[1, 1000000] (got 2000000)"));
  // The run must last the periods asked for: 2 x 0.254 > end_time 0.35.
  errs = with(plate + "period: 0.254 cycles: 2");
  EXPECT_TRUE(has_error(errs, "time.end_time", "at least 0.508")) << join_errors(errs);
  // Ten samples per period at least.
  errs = with(plate + "period: 0.004");
  EXPECT_TRUE(has_error(errs, "output.series_interval", "at most")) << join_errors(errs);
  // A series of the other groups is checked as for the other references.
  errs = with("series: \"bodies/velocity\" period: 0.254");
  EXPECT_TRUE(has_error(errs, "reference.series_period.series", "needs rigid bodies"));
  v1::Case none = ok;
  none.mutable_elastic_bodies(0)->clear_observation_points();
  errs = validate_case(none);
  EXPECT_TRUE(has_error(errs, "reference.series_period.series", "observation_points"))
      << join_errors(errs);
}

}  // namespace
}  // namespace sph::analysis
