// Poiseuille and Couette flow against the transient analytic solutions (Adami 2012
// sec. 5.1). Adami reports a mean error at t = 10 of 0.16% (Poiseuille) and 0.16%
// (Couette) at 30 particles across; we require < 0.5%.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/support/result_reader.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

constexpr double kPi = std::numbers::pi;

// Startup Poiseuille flow between plates at y = 0 and y = L driven by a body force F.
double poiseuille(double y, double t, double F, double nu, double L) {
  double u = F / (2 * nu) * y * (L - y);
  for (int n = 0; n < 200; ++n) {
    const double k = 2 * n + 1;
    u -= 4 * F * L * L / (nu * kPi * kPi * kPi * k * k * k) * std::sin(kPi * y * k / L) *
         std::exp(-k * k * kPi * kPi * nu * t / (L * L));
  }
  return u;
}

// Startup Couette flow: the plate at y = L moves at V from t = 0.
double couette(double y, double t, double V, double nu, double L) {
  double u = V * y / L;
  for (int n = 1; n < 400; ++n)
    u += 2 * V / (n * kPi) * (n % 2 ? -1.0 : 1.0) * std::sin(n * kPi * y / L) *
         std::exp(-n * n * kPi * kPi * nu * t / (L * L));
  return u;
}

// Mean |u - u_exact| over fluid particles, relative to the steady maximum velocity.
template <class Exact>
double mean_error(const test::Snapshot& s, Exact exact, double u_ref) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != 0) continue;
    sum += std::abs(s.velocity[3 * i] - exact(s.position[3 * i + 1], s.time));
    ++n;
  }
  return sum / n / u_ref;
}

TEST(ChannelFlow, PoiseuilleMatchesAnalyticAtT10) {
  const auto c = test::load_case("poiseuille_2d");
  const std::string out = test::output_dir("poiseuille");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const test::Snapshot s = test::ResultReader(out + "/result.h5").last();
  ASSERT_NEAR(s.time, 10.0, 1e-12);
  const double err = mean_error(
      s, [](double y, double t) { return poiseuille(y, t, 0.1, 0.01, 1.0); }, 1.25);
  std::printf(
      "Poiseuille, 30 particles across, t = 10: mean error %.3f%% of u_max (Adami 2012: 0.16%%)\n",
      100 * err);
  EXPECT_LT(err, 0.005);
}

TEST(ChannelFlow, CouetteMatchesAnalyticAtT10) {
  const auto c = test::load_case("couette_2d");
  const std::string out = test::output_dir("couette");
  const RunOutcome r = test::run(c, out);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  const test::Snapshot s = test::ResultReader(out + "/result.h5").last();
  const double err = mean_error(
      s, [](double y, double t) { return couette(y, t, 1.25, 0.01, 1.0); }, 1.25);
  std::printf(
      "Couette, 30 particles across, t = 10: mean error %.3f%% of v_wall (Adami 2012: 0.16%%)\n",
      100 * err);
  EXPECT_LT(err, 0.005);
}

}  // namespace
}  // namespace sph
