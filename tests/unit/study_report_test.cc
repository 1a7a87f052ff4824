// The tables of a convergence study: fitted order, wall-time slope and target resolutions from
// levels with known errors and costs, the CSV and Markdown files, and level records.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/level_result.h"
#include "study/study_report.h"
#include "study/study_summary.h"

namespace sph::study {
namespace {

namespace fs = std::filesystem;

// Levels with error 2 dx^2 and wall time 1e-3 dx^-3 (2D, acoustic time step), one rank,
// simulated time 2.
std::vector<LevelResult> second_order_levels() {
  std::vector<LevelResult> out;
  int k = 1;
  for (double dx : {0.04, 0.04 / std::sqrt(2.0), 0.02, 0.02 / std::sqrt(2.0)}) {
    LevelResult l;
    l.level = k++;
    l.dx = dx;
    l.status = "completed";
    l.simulated_time = 2;
    l.steps = static_cast<std::int64_t>(1 / dx);
    l.particles = 1 / (dx * dx);
    l.particle_steps = l.particles * static_cast<double>(l.steps);
    l.wall_seconds = 1e-3 * std::pow(dx, -3);
    l.peak_rss_bytes = 64 << 20;
    l.ranks = 1;
    l.measurement.error = 2 * dx * dx;
    out.push_back(l);
  }
  return out;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(StudyReport, OrderWallSlopeAndTargets) {
  auto levels = second_order_levels();
  LevelResult failed;
  failed.level = 5;
  failed.dx = 0.005;
  failed.status = "unstable";
  levels.push_back(failed);  // not fitted
  const StudySummary s = summarize_study(levels);
  ASSERT_TRUE(s.error_vs_dx.ok);
  EXPECT_EQ(s.error_vs_dx.points, 4);
  EXPECT_NEAR(s.error_vs_dx.slope, 2, 1e-9);
  EXPECT_NEAR(s.error_vs_wall.slope, -2.0 / 3, 1e-9);
  EXPECT_NEAR(s.cost_vs_dx.slope, -3, 1e-9);
  ASSERT_EQ(s.targets.size(), 3u);
  // The measured errors span 0.04% .. 0.32%: every level meets 1%, so the coarsest level's
  // own numbers answer it.
  EXPECT_TRUE(s.targets[0].reachable);
  EXPECT_TRUE(s.targets[0].met_by_every_level);
  EXPECT_DOUBLE_EQ(s.targets[0].dx, 0.04);
  EXPECT_DOUBLE_EQ(s.targets[0].particles, levels[0].particles);
  EXPECT_DOUBLE_EQ(s.targets[0].core_seconds_per_simulated_second,
                   levels[0].core_seconds_per_simulated_second());
  // With ten times the error, 1% lies between the levels (interpolated) and the fits give
  // dx, particles and cost.
  auto tenfold = second_order_levels();
  for (auto& l : tenfold) l.measurement.error *= 10;  // 0.4% .. 3.2%
  const StudySummary st = summarize_study(tenfold);
  ASSERT_TRUE(st.targets[0].reachable);
  EXPECT_FALSE(st.targets[0].met_by_every_level);
  EXPECT_FALSE(st.targets[0].extrapolated);
  EXPECT_NEAR(st.targets[0].dx, std::sqrt(0.0005), 1e-9);
  EXPECT_NEAR(st.targets[0].particles, 1 / 0.0005, 1e-6);
  EXPECT_NEAR(st.targets[0].core_seconds_per_simulated_second,
              1e-3 * std::pow(std::sqrt(0.0005), -3) / 2, 1e-6);
  // A target below the finest level's error is extrapolated.
  for (auto& l : tenfold) l.measurement.error *= 10;  // 4% .. 32%
  const StudySummary sf = summarize_study(tenfold);
  EXPECT_TRUE(sf.targets[0].extrapolated);
  EXPECT_NEAR(sf.targets[0].dx, std::sqrt(0.0005) / std::sqrt(10.0), 1e-9);
  // An error that grows with resolution cannot be bought: with errors of 25% .. 71% no
  // target is reachable; with 1% .. 2.8% everywhere the coarsest level meets 5% and 10%.
  auto bad = second_order_levels();
  for (auto& l : bad) l.measurement.error = 0.01 / l.dx;
  const StudySummary sb = summarize_study(bad);
  EXPECT_LT(sb.error_vs_dx.slope, 0);
  EXPECT_FALSE(sb.targets[1].reachable);
  EXPECT_FALSE(sb.targets[2].reachable);
  for (auto& l : bad) l.measurement.error = 0.0004 / l.dx;
  const StudySummary flat = summarize_study(bad);
  EXPECT_FALSE(flat.targets[0].reachable);
  ASSERT_TRUE(flat.targets[1].reachable);
  EXPECT_TRUE(flat.targets[1].met_by_every_level);
  EXPECT_DOUBLE_EQ(flat.targets[1].dx, 0.04);
  EXPECT_DOUBLE_EQ(flat.targets[1].particles, bad[0].particles);
}

TEST(StudyReport, CsvAndMarkdownHaveOneRowPerLevel) {
  const fs::path dir = fs::path(SPHD_BINARY_DIR) / "test-output" / "study_report";
  fs::create_directories(dir);
  const auto levels = second_order_levels();
  const StudySummary s = summarize_study(levels);
  StudyDescription d{"demo", "A demo", "max |T - T_exact|", "--refine 4 (ratio 1.41421)", ""};
  write_study_csv((dir / "study.csv").string(), d, levels, s);
  write_study_markdown((dir / "study.md").string(), d, levels, s, "study.png");
  const std::string csv = read(dir / "study.csv");
  EXPECT_NE(csv.find("# observed_order_dx: 2"), std::string::npos) << csv;
  EXPECT_NE(csv.find("level,dx,particles,steps"), std::string::npos);
  int rows = 0;
  std::istringstream lines(csv);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) ++rows;
  EXPECT_EQ(rows, 4);
  const std::string md = read(dir / "study.md");
  EXPECT_NE(md.find("**Observed order 2.00**"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1.00% | 0.04 | 625 |"), std::string::npos) << md;
  EXPECT_NE(md.find("every level is within it"), std::string::npos);
  EXPECT_NE(md.find("![error against dx and against wall time, log-log](study.png)"),
            std::string::npos);
}

TEST(StudyReport, LevelRecordsRoundTrip) {
  const fs::path dir = fs::path(SPHD_BINARY_DIR) / "test-output" / "level_record";
  fs::create_directories(dir);
  fs::remove(dir / "level.txt");
  EXPECT_FALSE(load_level_record(dir.string()));
  LevelResult l = second_order_levels()[1];
  l.message = "two\nlines";
  l.resumed = true;
  save_level_record(dir.string(), l);
  const auto back = load_level_record(dir.string());
  ASSERT_TRUE(back);
  EXPECT_EQ(back->level, 2);
  EXPECT_DOUBLE_EQ(back->dx, l.dx);
  EXPECT_DOUBLE_EQ(back->wall_seconds, l.wall_seconds);
  EXPECT_EQ(back->steps, l.steps);
  EXPECT_TRUE(back->resumed);
  EXPECT_EQ(back->message, "two lines");
  EXPECT_EQ(format_seconds(30), "30 s");
  EXPECT_EQ(format_seconds(600), "10 min");
  EXPECT_EQ(format_seconds(7200 * 3), "6 h");
}

}  // namespace
}  // namespace sph::study
