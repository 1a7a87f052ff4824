// Order-independent sums of rigid-body forces over particles and ranks (solver/parallel/
// exact_sum.h): the same terms in any order give the same double, and a non-finite term
// makes its slot non-finite instead of vanishing into the fixed-point conversion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/parallel/exact_sum.h"

namespace sph {
namespace {

std::vector<double> sum_of(const std::vector<std::pair<std::size_t, double>>& terms,
                           std::size_t slots) {
  return exact_sum(
      slots,
      [&](auto emit) {
        for (const auto& [k, x] : terms) emit(k, x);
      },
      Comm(MPI_COMM_WORLD));
}

TEST(ExactSum, SameResultInAnyOrder) {
  // Terms spanning 16 orders of magnitude with cancellation: a plain double sum depends on the
  // order; the fixed-point sum does not, and is within one rounding of the true sum.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::pair<std::size_t, double>> terms;
  long double truth = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = u(rng) * std::pow(10.0, static_cast<int>(rng() % 17) - 8);
    terms.push_back({0, x});
    truth += x;
  }
  const double first = sum_of(terms, 1)[0];
  double plain_spread = 0;
  for (int shuffle = 0; shuffle < 5; ++shuffle) {
    std::shuffle(terms.begin(), terms.end(), rng);
    EXPECT_EQ(sum_of(terms, 1)[0], first) << "shuffle " << shuffle;
    double plain = 0;
    for (const auto& t : terms) plain += t.second;
    plain_spread = std::max(plain_spread, std::abs(plain - first));
  }
  EXPECT_NEAR(first, static_cast<double>(truth),
              1e-14 * std::abs(static_cast<double>(truth)) + 1e-30);
  std::printf("exact sum %.17g, true %.17Lg, plain double sums differ by up to %.3g\n", first,
              truth, plain_spread);
}

TEST(ExactSum, NonFiniteTermMakesItsSlotNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto out =
      sum_of({{0, 1.0}, {0, nan}, {0, 2.0}, {1, 3.0}, {1, 4.0}, {2, inf}, {2, 1.0}}, 3);
  EXPECT_TRUE(std::isnan(out[0])) << out[0];
  EXPECT_EQ(out[1], 7.0);
  EXPECT_FALSE(std::isfinite(out[2])) << out[2];
}

}  // namespace
}  // namespace sph
