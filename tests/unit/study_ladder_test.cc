// Convergence-study ladders and references: the dx of each level, snapping to the lattice
// period, and validation errors that name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "case/load.h"
#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "case/validate.h"
#include "tests/support/field_errors.h"

namespace sph {
namespace {

const char* kStrip = R"(
name: "strip"
dimension: 2
dx: 0.02
domain { lo { x: -0.06 y: 0 } hi { x: 1.06 y: 0.16 } }
periodic_y: true
materials { name: "f" density: 1 eos { sound_speed: 10 } heat_capacity: 1 thermal_conductivity: 1 }
fluids { material: "f" shape { box { lo { x: 0 y: 0 } hi { x: 1 y: 1 } } } initial_temperature: 0 }
walls { name: "hot" shape { box { lo { x: -1 y: 0 } hi { x: 0 y: 1 } } } temperature { value { constant: 1 } } }
thermal { initial_temperature: 0 }
time { end_time: 0.01 }
)";

const char* kConduction = R"(
reference { conduction { boundary: 0 boundary_value: 1 initial_value: 0 diffusivity: 1 } }
)";

v1::Case strip(const std::string& extra) {
  return parse_case_text(std::string(kStrip) + extra);
}

v1::StudySpec refine(int n, double ratio = 0) {
  v1::StudySpec s;
  s.set_refine(n);
  if (ratio > 0) s.set_ratio(ratio);
  return s;
}

using testing::has_error;

TEST(StudyLadder, RefineDividesByTheRatioFromTheCasesDx) {
  const auto c = strip(kConduction);
  auto dx = study_ladder(c, refine(3));
  ASSERT_EQ(dx.size(), 3u);
  EXPECT_DOUBLE_EQ(dx[0], 0.02);
  EXPECT_NEAR(dx[1], 0.02 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(dx[2], 0.01, 1e-15);
  dx = study_ladder(c, refine(2, 2));
  EXPECT_NEAR(dx[1], 0.01, 1e-15);
  v1::StudySpec list;
  for (double d : {0.01, 0.02, 0.015}) list.add_dx(d);
  EXPECT_EQ(study_ladder(c, list), (std::vector<double>{0.02, 0.015, 0.01}));  // coarsest first
  EXPECT_TRUE(validate_study(c, list).empty()) << join_errors(validate_study(c, list));
}

TEST(StudyLadder, LatticePeriodKeepsBoxesWhole) {
  auto c = strip(
      "reference { conduction { boundary: 0 boundary_value: 1 initial_value: 0 diffusivity: 1 } "
      "lattice_period: 0.2 }");
  const auto dx = study_ladder(c, refine(4));
  // 0.2 / dx = 10, 14.1 -> 14, 20, 28.3 -> 28.
  EXPECT_NEAR(dx[0], 0.2 / 10, 1e-15);
  EXPECT_NEAR(dx[1], 0.2 / 14, 1e-15);
  EXPECT_NEAR(dx[2], 0.2 / 20, 1e-15);
  EXPECT_NEAR(dx[3], 0.2 / 28, 1e-15);
  EXPECT_DOUBLE_EQ(level_case(c, dx[1]).dx(), dx[1]);
  EXPECT_EQ(level_case(c, dx[1]).time().end_time(), c.time().end_time());
  // A ratio so small that two levels snap to the same dx is refused, naming the ratio.
  const auto errs = validate_study(c, refine(3, 1.01));
  EXPECT_TRUE(has_error(errs, "study.ratio", "same dx")) << join_errors(errs);
}

TEST(StudyLadder, ValidationNamesTheField) {
  const auto without = strip("");
  auto errs = validate_study(without, refine(3));
  EXPECT_TRUE(has_error(errs, "reference", "needs the case's reference")) << join_errors(errs);
  const auto c = strip(kConduction);
  EXPECT_TRUE(has_error(validate_study(c, refine(1)), "study.refine", "[2, 12]"));
  EXPECT_TRUE(has_error(validate_study(c, refine(40)), "study.refine", "[2, 12]"));
  EXPECT_TRUE(has_error(validate_study(c, refine(3, 0.5)), "study.ratio", "(1, 4]"));
  v1::StudySpec list;
  list.add_dx(0.02);
  list.add_dx(-1);
  EXPECT_TRUE(has_error(validate_study(c, list), "study.dx[1]", "must be > 0"));
  list.set_refine(3);
  EXPECT_TRUE(has_error(validate_study(c, list), "study", "either refine"));
  v1::StudySpec one;
  one.add_dx(0.02);
  EXPECT_TRUE(has_error(validate_study(c, one), "study.dx", "at least two"));
  // The finest level must fit the particle limit: ~50x8 particles at dx = 0.02.
  errs = validate_study(c, refine(5), ValidationLimits{2000});
  EXPECT_TRUE(has_error(errs, "study.refine", "level 4")) << join_errors(errs);
  // Richardson without an order needs three levels.
  const auto r = strip(R"(reference { richardson { series: "diagnostics/temperature_max" } })");
  EXPECT_TRUE(has_error(validate_study(r, refine(2)), "study.refine", "at least 3 levels"));
  EXPECT_TRUE(validate_study(r, refine(3)).empty());
}

TEST(StudyLadder, ReferencesAreValidatedWithTheCase) {
  auto errs = validate_case(strip(kConduction));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
  errs = validate_case(strip("reference { }"));
  EXPECT_TRUE(has_error(errs, "reference", "give one kind")) << join_errors(errs);
  errs = validate_case(strip("reference { channel_flow { height: 0 kinematic_viscosity: 1 } }"));
  EXPECT_TRUE(has_error(errs, "reference.channel_flow.height", "must be > 0")) << join_errors(errs);
  EXPECT_TRUE(has_error(errs, "reference.channel_flow", "body_force or wall_velocity"));
  errs = validate_case(strip(R"(reference { series_data { series: "bodies/velocity" } })"));
  EXPECT_TRUE(has_error(errs, "reference.series_data.series", "needs rigid bodies"));
  EXPECT_TRUE(has_error(errs, "reference.series_data.times", "at least two"));
  errs = validate_case(strip(R"(reference { richardson { series: "probes/nope/pressure" } })"));
  EXPECT_TRUE(has_error(errs, "reference.richardson.series", "probe")) << join_errors(errs);
  errs = validate_case(strip(R"(reference { richardson { series: "max_speed" order: -1 } })"));
  EXPECT_TRUE(has_error(errs, "reference.richardson.series", "group/name"));
  EXPECT_TRUE(has_error(errs, "reference.richardson.order", "must be > 0"));
  errs = validate_case(strip(
      "reference { conduction { diffusivity: 1 boundary_value: 1 field: \"concentration\" } }"));
  EXPECT_TRUE(has_error(errs, "reference.conduction.field", "diffusion")) << join_errors(errs);
  errs =
      validate_case(strip("reference { taylor_green { kinematic_viscosity: 1 wavelength: 1 "
                          "fit_start: 5 } }"));
  EXPECT_TRUE(has_error(errs, "reference.taylor_green.fit_start", "end_time"));
  errs = validate_case(strip("reference { hydrostatic { width: 1 x_min: 1 x_max: 0 } }"));
  EXPECT_TRUE(has_error(errs, "reference.hydrostatic", "needs gravity"));
  EXPECT_TRUE(has_error(errs, "reference.hydrostatic.x_max", "larger than x_min"));
}

TEST(StudyLadder, ReferenceDataFilesAreInlinedWhenTheCaseIsLoaded) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(SPHD_BINARY_DIR) / "test-output" / "reference_data";
  fs::create_directories(dir);
  std::ofstream(dir / "data.csv") << "# a comment\nt,a,b\n0,1,10\n0.5,2,20\n1,3,30\n";
  std::ofstream(dir / "case.textproto")
      << kStrip
      << R"(reference { series_data { file: "data.csv" column: 2 series: "diagnostics/max_speed" } })";
  const v1::Case c = load_case_file((dir / "case.textproto").string());
  const auto& d = c.reference().series_data();
  EXPECT_TRUE(d.file().empty());
  EXPECT_EQ(std::vector<double>(d.times().begin(), d.times().end()),
            (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(std::vector<double>(d.values().begin(), d.values().end()),
            (std::vector<double>{10, 20, 30}));
  EXPECT_TRUE(validate_case(c).empty()) << join_errors(validate_case(c));
  std::ofstream(dir / "bad.textproto")
      << kStrip
      << R"(reference { series_data { file: "data.csv" column: 5 series: "diagnostics/max_speed" } })";
  try {
    load_case_file((dir / "bad.textproto").string());
    FAIL() << "expected a CaseLoadError";
  } catch (const CaseLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("reference.series_data.file"), std::string::npos)
        << e.what();
  }
}

TEST(StudyLadder, CommandLineText) {
  v1::StudySpec s;
  std::string error;
  EXPECT_TRUE(set_study_field(s, "refine", "4", error));
  EXPECT_TRUE(set_study_field(s, "ratio", "2", error));
  EXPECT_EQ(describe_study(s), "--refine 4 (ratio 2)");
  v1::StudySpec l;
  EXPECT_TRUE(set_study_field(l, "dx", "0.04,0.02,0.01", error));
  EXPECT_EQ(l.dx_size(), 3);
  EXPECT_EQ(describe_study(l), "--dx 0.04,0.02,0.01");
  EXPECT_FALSE(set_study_field(l, "dx", "0.04,abc", error));
  EXPECT_NE(error.find("--dx"), std::string::npos);
  EXPECT_FALSE(set_study_field(s, "refine", "four", error));
  EXPECT_NE(error.find("--refine"), std::string::npos);
}

}  // namespace
}  // namespace sph
