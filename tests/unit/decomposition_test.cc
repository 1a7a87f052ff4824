// Recursive coordinate bisection: boxes tile the grid and balance particle counts.
#include <gtest/gtest.h>

#include <random>

#include "solver/parallel/decomposition.h"

namespace sph {
namespace {

TEST(Decomposition, BoxesTileAndBalance) {
  CellGrid<2> grid(Vec<2>(0, 0), Vec<2>(10, 4), 0.1, {false, false});
  std::vector<std::int64_t> counts(static_cast<size_t>(grid.total()), 0);
  // A dam-break-like distribution: everything in the lower-left corner.
  std::mt19937 rng(3);
  for (int k = 0; k < 200000; ++k) {
    ICoord<2> c{static_cast<int>(rng() % 100), static_cast<int>(rng() % 20)};
    ++counts[static_cast<size_t>(grid.linear(c))];
  }
  for (int ranks : {1, 2, 3, 4, 7}) {
    Decomposition<2> d(grid, ranks, counts);
    std::vector<std::int64_t> per(static_cast<size_t>(ranks), 0);
    long long cells = 0;
    for (int r = 0; r < ranks; ++r) cells += d.box(r).cells();
    EXPECT_EQ(cells, grid.total());
    for (int i = 0; i < grid.n[0]; ++i)
      for (int j = 0; j < grid.n[1]; ++j) {
        const int o = d.owner({i, j});
        ASSERT_TRUE(d.box(o).contains({i, j}));
        per[static_cast<size_t>(o)] += counts[static_cast<size_t>(grid.linear({i, j}))];
      }
    const double mean = 200000.0 / ranks;
    // Cell slabs limit the granularity: within 10% up to 4 ranks, 20% for 7.
    for (auto n : per) EXPECT_LT(n, (ranks <= 4 ? 1.10 : 1.20) * mean) << ranks << " ranks";
  }
}

}  // namespace
}  // namespace sph
