// A convergence study end to end at CI size: the 1D conduction case (cases/
// conduction_slab_2d.textproto) at three resolutions, dx = 0.04, 0.0286, 0.02 (0.8 / 20, 28,
// 40: snapped to the periodic height), measured against the erfc solution by the same
// evaluator the service's studies use. The scheme (Cleary-Monaghan conduction, mirror Dirichlet
// wall) is second order in dx; the observed order must lie within 2 +- 0.5. Running the study again
// into the same directory must reuse every level (the resume path of interrupted studies).
// And the cantilever plate (cases/studies/oscillating_plate_2d.textproto) at H/dx = 5 and 10: its
// first period against Euler-Bernoulli through reference.series_period, read from the elastic
// body's series (docs/accuracy.md has the ladder to H/dx = 40).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "study/run_study.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

namespace fs = std::filesystem;

TEST(ConvergenceStudy, ConductionSlabIsSecondOrderOnACoarseLadder) {
  const auto c = test::load_case("conduction_slab_2d");
  v1::StudySpec spec;
  for (double dx : {0.04, 0.04 / std::sqrt(2.0), 0.02}) spec.add_dx(dx);
  ASSERT_TRUE(validate_study(c, spec).empty()) << join_errors(validate_study(c, spec));
  const auto ladder = study_ladder(c, spec);
  study::StudyOptions o;
  o.output_dir = test::output_dir("study_conduction");
  o.ladder_description = describe_study(spec);
  o.quiet = true;
  const study::StudyOutcome r = study::run_study(c, ladder, MPI_COMM_WORLD, o);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  if (rank != 0) return;
  ASSERT_EQ(r.levels.size(), 3u);
  for (const auto& l : r.levels)
    std::printf(
        "conduction study level %d: dx = %.5f, error %.3e, %.2f s wall, %.0f particles, "
        "%lld steps, peak %.0f MiB\n",
        l.level, l.dx, l.measurement.error, l.wall_seconds, l.particles,
        static_cast<long long>(l.steps), l.peak_rss_bytes / 1048576.0);
  const double order = r.summary.error_vs_dx.slope;
  std::printf("observed order %.2f (expected 2), error against wall time slope %.2f; %s\n", order,
              r.summary.error_vs_wall.slope, r.message.c_str());
  for (std::size_t k = 0; k < r.levels.size(); ++k) {
    EXPECT_TRUE(r.levels[k].completed());
    EXPECT_GT(r.levels[k].steps, 0);
    EXPECT_GT(r.levels[k].peak_rss_bytes, 0);
    if (k > 0) {
      EXPECT_LT(r.levels[k].measurement.error, r.levels[k - 1].measurement.error);
    }
  }
  EXPECT_NEAR(order, 2.0, 0.5);
  for (const char* f :
       {"study.csv", "study.md", "study.png", "level_1/result.h5", "level_3/result.xmf"})
    EXPECT_TRUE(fs::is_regular_file(fs::path(o.output_dir) / f)) << f << ": " << r.plot_problem;

  // Again into the same directory: nothing runs, the numbers are the same.
  const study::StudyOutcome again = study::run_study(c, ladder, MPI_COMM_WORLD, o);
  ASSERT_EQ(again.status, RunStatus::kCompleted) << again.message;
  for (std::size_t k = 0; k < again.levels.size(); ++k) {
    EXPECT_TRUE(again.levels[k].reused) << "level " << k + 1 << " ran again";
    EXPECT_DOUBLE_EQ(again.levels[k].measurement.error, r.levels[k].measurement.error);
    EXPECT_DOUBLE_EQ(again.levels[k].wall_seconds, r.levels[k].wall_seconds);
  }
}

TEST(ConvergenceStudy, CantileverPlatePeriodOnTwoLevels) {
  const auto c = test::load_case("studies/oscillating_plate_2d");
  v1::StudySpec spec;
  for (double dx : {0.004, 0.002}) spec.add_dx(dx);
  ASSERT_TRUE(validate_study(c, spec).empty()) << join_errors(validate_study(c, spec));
  study::StudyOptions o;
  o.output_dir = test::output_dir("study_cantilever_plate");
  o.ladder_description = describe_study(spec);
  o.quiet = true;
  const study::StudyOutcome r = study::run_study(c, study_ladder(c, spec), MPI_COMM_WORLD, o);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  ASSERT_EQ(r.status, RunStatus::kCompleted) << r.message;
  if (rank != 0) return;
  ASSERT_EQ(r.levels.size(), 2u);
  for (const auto& l : r.levels)
    std::printf("cantilever plate level %d: H/dx = %.0f, first period %.5f s, error %.3f%%; %s\n",
                l.level, 0.02 / l.dx, l.measurement.quantity, 100 * l.measurement.error,
                l.measurement.detail.c_str());
  // docs/accuracy.md: +19.95% at H/dx = 5 and +6.07% at 10 (this test's H/dx = 10 run is the
  // one ElasticSolid.CantileverPlateFirstPeriod checks); both periods longer than the exact one.
  for (const auto& l : r.levels) {
    ASSERT_TRUE(l.completed());
    EXPECT_GT(l.measurement.quantity, 0.254032);
  }
  EXPECT_NEAR(r.levels[0].measurement.error, 0.1995, 0.02);
  EXPECT_NEAR(r.levels[1].measurement.error, 0.0607, 0.01);
  EXPECT_GT(r.summary.error_vs_dx.slope, 1.2);
}

}  // namespace
}  // namespace sph
