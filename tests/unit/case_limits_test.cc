// The bounds of case/case_limits.h: text no program may recurse, loop or allocate without
// limit on is refused by name, with the limit in the message, and cases at the limits are
// still accepted (issue #41).
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "case/case_bounds.h"
#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/load.h"
#include "case/validate.h"
#include "tests/support/field_errors.h"

namespace sph {
namespace {

const char* kHead = R"(name: "t"
dimension: 2
dx: 0.1
domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }
materials { name: "water" density: 1000 eos { sound_speed: 10 } }
time { end_time: 1 }
)";
const char* kBox = "box{lo{x:0.5 y:0.5}hi{x:1.5 y:1.5}}";

// `depth` shapes nested with `open`/`close` (e.g. "union{shapes{" and "}}") around a box,
// written compactly: the form whose canonical text grows most.
std::string nested(int depth, const std::string& open, const std::string& close) {
  std::string s;
  for (int i = 1; i < depth; ++i) s += open;
  s += kBox;
  for (int i = 1; i < depth; ++i) s += close;
  return s;
}

std::string fluid_case(const std::string& shape) {
  return std::string(kHead) + "fluids{name:\"f\" material:\"water\" shape{" + shape + "}}\n";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

using testing::has_error;

// The message of the CaseLoadError `fn` throws ("" and a test failure if none).
template <class Fn>
std::string load_error(Fn&& fn) {
  try {
    fn();
  } catch (const CaseLoadError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a CaseLoadError";
  return "";
}

std::filesystem::path temp_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("case_limits_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// Before the parser had a recursion limit this text crashed sph-server, sph-worker and sphctl
// with SIGSEGV.
TEST(CaseLimits, DeepUnionIsRefusedByNameWhenParsed) {
  const std::string text = fluid_case(nested(4000, "union{shapes{", "}}"));
  std::printf("4000-deep union: %zu bytes of text\n", text.size());
  const std::string msg = load_error([&] { parse_case_text(text); });
  std::printf("parse_case_text: %s\n", msg.c_str());
  EXPECT_NE(msg.find("fluids[0].shape: shapes nest 4000 deep; the limit is 32"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("limit of " + std::to_string(kMaxTextNesting)), std::string::npos) << msg;
}

// The refusal names the region wherever it is and however the text writes the nesting (lists
// of messages, angle brackets, comments).
TEST(CaseLimits, DeepNestingIsNamedInAnyRegionAndSyntax) {
  std::string chain;
  for (int i = 0; i < 100; ++i) chain += i % 2 ? "union <shapes: [{ # {\n" : "union{shapes:[{";
  chain += kBox;
  for (int i = 0; i < 100; ++i) chain += i % 2 ? "}]>" : "}]}";
  const std::string text = fluid_case(kBox) + "walls{name:\"a\" shape{" + kBox + "}}\n" +
                           "walls{name:\"b{\" shape{" + chain + "}}\n";
  const std::string msg = load_error([&] { parse_case_text(text); });
  EXPECT_NE(msg.find("walls[1].shape: shapes nest 101 deep; the limit is 32"), std::string::npos)
      << msg;
}

TEST(CaseLimits, DeepUnionIsRefusedByNameWhenLoadedFromAFile) {
  const auto path = temp_dir() / "deep.textproto";
  std::ofstream(path) << fluid_case(nested(4000, "union{shapes{", "}}"));
  const std::string msg = load_error([&] { load_case_file(path.string()); });
  EXPECT_NE(msg.find("fluids[0].shape: shapes nest 4000 deep; the limit is 32"), std::string::npos)
      << msg;
  std::filesystem::remove_all(path.parent_path());
}

// Every kind of combination parses at the depth limit (kMaxTextNesting leaves room for each),
// one level more is refused by validation with the depth, and text far deeper by the parser.
TEST(CaseLimits, ShapesNestUpToTheLimit) {
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"union{shapes{", "}}"},
      {"intersection{shapes{", "}}"},
      {"difference{base{", "}}"},
      {"difference{base{box{lo{x:0 y:0}hi{x:2 y:2}}}subtract{", "}}"},
      {"shell{thickness:0.1 inner{", "}}"}};
  for (const auto& [open, close] : kinds) {
    const v1::Case at = parse_case_text(fluid_case(nested(kMaxShapeDepth, open, close)));
    EXPECT_TRUE(check_case_bounds(at).empty()) << open << join_errors(check_case_bounds(at));
    EXPECT_EQ(measure_shape(at.fluids(0).shape()).depth, kMaxShapeDepth) << open;
    const v1::Case over = parse_case_text(fluid_case(nested(kMaxShapeDepth + 1, open, close)));
    EXPECT_TRUE(
        has_error(validate_case(over), "fluids[0].shape", "shapes nest 33 deep; the limit is 32"))
        << open << join_errors(validate_case(over));
    const std::string msg =
        load_error([&] { parse_case_text(fluid_case(nested(2 * kMaxShapeDepth, open, close))); });
    EXPECT_NE(msg.find("fluids[0].shape: shapes nest 64 deep; the limit is 32"), std::string::npos)
        << open << msg;
  }
  // A union 32 deep is a valid case (the fluid is the box).
  const auto errs = validate_case(parse_case_text(fluid_case(nested(32, "union{shapes{", "}}"))));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
}

std::string balls(int n) {
  std::string s = "union{";
  for (int i = 0; i < n; ++i) s += "shapes{ball{center{x:1 y:1} radius:0.3}}";
  return s + "}";
}

TEST(CaseLimits, TooManyShapes) {
  // The union and its parts: kMaxShapes exactly, then one more.
  auto errs = validate_case(parse_case_text(fluid_case(balls(kMaxShapes - 1))));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
  errs = validate_case(parse_case_text(fluid_case(balls(kMaxShapes))));
  EXPECT_TRUE(has_error(errs, "fluids[0].shape",
                        "the case has 1025 shapes up to here (nested ones included); the limit "
                        "is 1024"))
      << join_errors(errs);
  std::printf("%s\n", join_errors(errs).c_str());
}

TEST(CaseLimits, LongNamesAndDescriptions) {
  v1::Case c = parse_case_text(fluid_case(kBox));
  c.set_name(std::string(10 << 20, 'n'));
  c.set_description(std::string(kMaxDescriptionBytes + 1, 'd'));
  c.mutable_materials(0)->set_name(std::string(kMaxNameBytes + 1, 'w'));
  c.mutable_fluids(0)->set_material(std::string(kMaxNameBytes + 1, 'w'));
  c.mutable_reference()->mutable_series_data()->set_series(std::string(300, 's'));
  c.mutable_fluids(0)->mutable_shape()->mutable_points()->set_file(std::string(5000, 'f'));
  const auto errs = validate_case(c);
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "name", "is 10485760 bytes long; the limit is 256"));
  EXPECT_TRUE(has_error(errs, "description", "is 16385 bytes long; the limit is 16384"));
  EXPECT_TRUE(has_error(errs, "materials[0].name", "is 257 bytes long; the limit is 256"));
  EXPECT_TRUE(has_error(errs, "fluids[0].material", "is 257 bytes long"));
  EXPECT_TRUE(has_error(errs, "reference.series_data.series", "is 300 bytes long"));
  EXPECT_TRUE(
      has_error(errs, "fluids[0].shape.points.file", "is 5000 bytes long; the limit is 4096"));
  // Only the bounds are reported: the other checks would quote the 10 MiB name.
  std::size_t longest = 0;
  for (const auto& e : errs) longest = std::max(longest, e.to_string().size());
  EXPECT_LT(longest, 200u);
  // At the limits: accepted.
  c = parse_case_text(fluid_case(kBox));
  c.set_name(std::string(kMaxNameBytes, 'n'));
  c.set_description(std::string(kMaxDescriptionBytes, 'd'));
  EXPECT_TRUE(validate_case(c).empty()) << join_errors(validate_case(c));
}

void write_points(const std::filesystem::path& path, int n) {
  std::ofstream out(path);
  for (int i = 0; i < n; ++i) out << "0.5 0.5\n";
}

TEST(CaseLimits, OversizedPointFiles) {
  const auto dir = temp_dir();
  write_points(dir / "full.xy", kMaxPointsPerFile);
  write_points(dir / "over.xy", kMaxPointsPerFile + 1);
  const auto case_with = [&](const std::vector<std::string>& files) {
    std::string text = kHead;
    for (const auto& f : files)
      text += "fluids{material:\"water\" shape{points{file:\"" + f + "\"}}}\n";
    std::ofstream(dir / "case.textproto") << text;
    return (dir / "case.textproto").string();
  };
  std::string msg = load_error([&] { load_case_file(case_with({"over.xy"})); });
  std::printf("%s\n", msg.c_str());
  EXPECT_NE(msg.find("fluids[0].shape.points.file: " + (dir / "over.xy").string() +
                     " has more than 1000000 points; the limit is 1000000 points per file"),
            std::string::npos)
      << msg;
  // Two full files reach the case's limit; a third point goes over it.
  const v1::Case two = load_case_file(case_with({"full.xy", "full.xy"}));
  EXPECT_EQ(measure_shape(two.fluids(1).shape()).points, kMaxPointsPerFile);
  write_points(dir / "one.xy", 1);
  msg = load_error([&] { load_case_file(case_with({"full.xy", "full.xy", "one.xy"})); });
  std::printf("%s\n", msg.c_str());
  EXPECT_NE(msg.find("fluids[2].shape.points.file: " + (dir / "one.xy").string() +
                     " has more than 0 points; the limit is 2000000 points per case and 2000000 "
                     "are already in it"),
            std::string::npos)
      << msg;
  // A file without line breaks is refused at the line limit, not read whole.
  {
    std::ofstream out(dir / "one_line.xy");
    out << std::string(1 << 20, '1');
  }
  msg = load_error([&] { load_case_file(case_with({"one_line.xy"})); });
  EXPECT_NE(msg.find("a line longer than 4096 bytes"), std::string::npos) << msg;
  // Points inlined in the text count too (validation: the text may come from anyone).
  v1::Case c = parse_case_text(fluid_case(kBox));
  auto* ps = c.add_fluids();
  ps->set_material("water");
  for (int i = 0; i < kMaxPointsPerCase + 1; ++i) {
    auto* p = ps->mutable_shape()->mutable_points()->add_points();
    p->set_x(0.5);
    p->set_y(0.5);
  }
  EXPECT_TRUE(has_error(validate_case(c), "fluids[1].shape",
                        "2000001 explicit points up to here; the limit is 2000000"));
  std::filesystem::remove_all(dir);
}

TEST(CaseLimits, OversizedReferenceData) {
  const auto dir = temp_dir();
  {
    std::ofstream out(dir / "data.csv");
    out << "t,v\n";
    for (int i = 0; i <= kMaxReferenceRows; ++i) out << i << ",1\n";
  }
  std::ofstream(dir / "case.textproto")
      << fluid_case(kBox) << "reference{series_data{file:\"data.csv\" series:\"max_speed\"}}\n";
  const std::string msg = load_error([&] { load_case_file((dir / "case.textproto").string()); });
  std::printf("%s\n", msg.c_str());
  EXPECT_NE(msg.find("reference.series_data.file: " + (dir / "data.csv").string() +
                     ": more than 100000 data rows; the limit is 100000"),
            std::string::npos)
      << msg;
  std::filesystem::remove_all(dir);
}

// Before: accepted, and the run "completed" without any fluid.
TEST(CaseLimits, RegionsOutsideTheDomainAreNamed) {
  const std::string outside = "box{lo{x:5 y:5}hi{x:6 y:6}}";
  auto errs = validate_case(parse_case_text(
      fluid_case(kBox) + "fluids{name:\"lost\" material:\"water\" shape{" + outside + "}}"));
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "fluids[1].shape",
                        "fluid 'lost' places no particles: it has no lattice points (dx = 0.1) "
                        "inside the domain (x in [0, 2], y in [0, 2]); the shape spans x in [5, "
                        "6], y in [5, 6]"))
      << join_errors(errs);
  // A wall half a domain away; a wall mostly outside is a slab clipped by the domain (allowed,
  // here three layers thick inside), a fluid mostly outside (3 of its 20 rows inside) is not.
  errs = validate_case(parse_case_text(
      fluid_case(kBox) + "walls{name:\"far\" shape{box{lo{x:0 y:-1.5}hi{x:2 y:-1}}}}\n" +
      "walls{name:\"low\" shape{box{lo{x:0 y:-1.7}hi{x:2 y:0.3}}}}\n" +
      "fluids{name:\"high\" material:\"water\" shape{box{lo{x:0 y:1.7}hi{x:2 y:3.7}}}}"));
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "walls[0].shape", "wall 'far' places no particles: none of its 100"))
      << join_errors(errs);
  EXPECT_TRUE(has_error(errs, "fluids[1].shape",
                        "fluid 'high' lies mostly outside the domain (x in [0, 2], y in [0, 2]): "
                        "60 of its 400 lattice points are inside; at least 50% must be"))
      << join_errors(errs);
  EXPECT_EQ(errs.size(), 2u) << join_errors(errs);
  // Along a periodic axis the domain clips a longer fluid box on purpose.
  errs = validate_case(parse_case_text(replace(fluid_case("box{lo{x:0.5 y:-5}hi{x:1.5 y:5}}"),
                                               "dimension: 2", "dimension: 2 periodic_y: true")));
  EXPECT_TRUE(errs.empty()) << join_errors(errs);
  // A body entirely outside.
  errs = validate_case(parse_case_text(
      fluid_case(kBox) + "materials{name:\"steel\" phase:SOLID density:7800}\n" +
      "bodies{name:\"ball\" material:\"steel\" shape{ball{center{x:3 y:1} radius:0.3}}}"));
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "bodies[0].shape", "body 'ball' places no particles"))
      << join_errors(errs);
  // Explicit points outside.
  errs = validate_case(parse_case_text(
      fluid_case(kBox) + "fluids{material:\"water\" shape{points{points{x:3 y:3}}}}"));
  EXPECT_TRUE(has_error(errs, "fluids[1].shape", "fluid places no particles: none of its 1 points"))
      << join_errors(errs);
}

// Before: an int64 overflow in the lattice walk estimated 1 particle and failed at step 1.
TEST(CaseLimits, TinyDxIsRefusedBeforeLatticeArithmetic) {
  const auto errs =
      validate_case(parse_case_text(replace(fluid_case(kBox), "dx: 0.1", "dx: 1e-300")));
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "dx", "is 1e-300 m; the smallest particle spacing is 1e-12 m"));
  EXPECT_TRUE(
      has_error(errs, "domain.hi.x",
                "lies 2e300 cells of dx = 1e-300 from lattice_origin.x; the limit is 2^31"));
  for (const char* bad : {"dx: inf", "dx: nan"}) {
    const auto e = validate_case(parse_case_text(replace(fluid_case(kBox), "dx: 0.1", bad)));
    EXPECT_TRUE(has_error(e, "dx", "every number must be finite")) << bad << ": " << join_errors(e);
  }
  const auto e = validate_case(parse_case_text(replace(fluid_case(kBox), "dx: 0.1", "dx: -1")));
  EXPECT_TRUE(has_error(e, "dx", "must be > 0")) << join_errors(e);
}

// Found by the case-text fuzzer: a body's initial temperature of NaN was accepted (the checks
// compare numbers, and NaN fails no comparison), and NaN never equals itself.
TEST(CaseLimits, EveryNumberMustBeFinite) {
  const std::string base = fluid_case(kBox);
  struct Probe {
    const char* from;
    const char* to;
    const char* field;
  };
  for (const Probe& p :
       {Probe{"density: 1000", "density: nan", "materials[0].density"},
        Probe{"end_time: 1", "end_time: inf", "time.end_time"},
        Probe{"lo{x:0.5", "lo{x:-inf", "fluids[0].shape.box.lo.x"},
        Probe{"sound_speed: 10", "sound_speed: -nan", "materials[0].eos.sound_speed"}}) {
    const auto errs = validate_case(parse_case_text(replace(base, p.from, p.to)));
    std::printf("%s -> %s\n", p.to, join_errors(errs).c_str());
    EXPECT_TRUE(has_error(errs, p.field, "every number must be finite")) << join_errors(errs);
  }
  EXPECT_TRUE(validate_case(parse_case_text(base)).empty());

  // Points are checked in place and named only when one is wrong; a million bad ones give
  // a hundred lines and a note, not a million.
  v1::Case many = parse_case_text(base);
  auto* points = many.mutable_fluids(0)->mutable_shape()->mutable_points();
  for (int i = 0; i < 1000000; ++i) {
    auto* p = points->add_points();
    p->set_x(i == 4 ? std::nan("") : 0.5 + 1e-6 * (i % 1000));
    p->set_y(i >= 900000 ? std::numeric_limits<double>::infinity() : 0.5);
  }
  const auto bounds = check_case_bounds(many);
  std::printf("1e6 points, 100001 not finite: %zu errors, first '%s'\n", bounds.size(),
              bounds.front().to_string().c_str());
  EXPECT_EQ(bounds.front().field, "fluids[0].shape.points.points[4].x");
  EXPECT_EQ(bounds.size(), 101u);
  EXPECT_NE(bounds.back().message.find("only the first 100"), std::string::npos);
}

// Before: estimated 406 particles and ran with 6.
TEST(CaseLimits, HugeDomainIsRefusedBeforeLatticeArithmetic) {
  const auto errs = validate_case(
      parse_case_text(replace(fluid_case(kBox), "domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }",
                              "domain { lo { x: -1e300 y: -1e300 } hi { x: 1e300 y: 1e300 } }")));
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "domain.lo.x", "is -1e300 m; coordinates must lie within +-1e12 m"));
  EXPECT_TRUE(has_error(errs, "domain.hi.y", "is 1e300 m"));
  // Within the coordinate range but too many cells for the lattice.
  const auto wide = validate_case(
      parse_case_text(replace(fluid_case(kBox), "domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }",
                              "domain { lo { x: 0 y: 0 } hi { x: 1e9 y: 2 } }")));
  EXPECT_TRUE(has_error(wide, "domain.hi.x", "lies 1e10 cells of dx = 0.1")) << join_errors(wide);
  // A shape far out: refused by name, not walked.
  const auto far =
      validate_case(parse_case_text(fluid_case("ball{center{x:1 y:1e200} radius:1e200}")));
  EXPECT_TRUE(has_error(far, "fluids[0].shape.ball.center.y", "is 1e200 m")) << join_errors(far);
  EXPECT_TRUE(has_error(far, "fluids[0].shape.ball.radius", "is 1e200 m")) << join_errors(far);
}

TEST(CaseLimits, ParticleAndMemoryLimitsQuoteTheNumbers) {
  v1::Case c = parse_case_text(fluid_case(kBox));
  c.set_dx(0.001);  // 1000 x 1000 particles in the 1 x 1 box
  const CaseEstimate e = estimate_case(c);
  std::printf("dx 0.001: %.0f particles, %.3g GiB\n", e.total(), e.bytes / 1073741824.0);
  ValidationLimits lim;
  lim.max_particles = 2e5;
  auto errs = validate_case(c, lim);
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "dx",
                        "case too large: estimated 1e6 particles; this server's limit is 200000 "
                        "(--max-particles)"))
      << join_errors(errs);
  lim.max_particles = 0;
  lim.max_memory_bytes = 0.25 * 1073741824.0;
  lim.source = "sph-worker's";
  errs = validate_case(c, lim);
  std::printf("%s\n", join_errors(errs).c_str());
  EXPECT_TRUE(has_error(errs, "dx",
                        "GiB of memory for 1e6 particles; sph-worker's limit is 0.25 "
                        "GiB (--max-memory-gib)"))
      << join_errors(errs);
  lim.max_memory_bytes = 1.01 * e.bytes;
  lim.max_particles = 1e6;
  EXPECT_TRUE(validate_case(c, lim).empty()) << join_errors(validate_case(c, lim));
}

// The server stores a case's canonical text (case_to_text); for the cases these limits still
// accept, written as compactly as the text format allows, it stays within
// kMaxCanonicalTextGrowth times the text submitted. The one-line form (as the server falls back
// to) is printed beside it.
TEST(CaseLimits, CanonicalTextGrowthIsBounded) {
  struct Form {
    std::string name, text;
  };
  std::vector<Form> forms;
  for (const auto& [open, close] : std::vector<std::pair<std::string, std::string>>{
           {"union{shapes{", "}}"}, {"shell{inner{", "}}"}, {"difference{base{", "}}"}}) {
    forms.push_back({"one " + open + " chain 32 deep", fluid_case(nested(32, open, close))});
    // As many 32-deep chains as kMaxShapes allows, in one union.
    std::string many = "union{";
    for (int i = 0; i < (kMaxShapes - 1) / kMaxShapeDepth; ++i)
      many += "shapes{" + nested(kMaxShapeDepth - 1, open, close) + "}";
    forms.push_back({"31 " + open + " chains", fluid_case(many + "}")});
  }
  std::string points = "points{points:[";
  for (int i = 0; i < 100000; ++i) points += i ? ",{x:1 y:1}" : "{x:1 y:1}";
  // Nested shells grow by their thickness at each level: a domain that holds them.
  for (auto& f : forms)
    if (f.name.find("shell") != std::string::npos)
      f.text = replace(f.text, "domain { lo { x: 0 y: 0 } hi { x: 2 y: 2 } }",
                       "domain { lo { x: -10 y: -10 } hi { x: 12 y: 12 } }");
  forms.push_back({"1e5 points as a list",
                   fluid_case(kBox) + "fluids{material:\"water\" shape{" + points + "]}}}"});
  std::string zeros = "points{points:[";
  for (int i = 0; i < 100000; ++i) zeros += i ? ",{}" : "{}";
  forms.push_back(
      {"1e5 points at the origin", replace(fluid_case(kBox), "x: 0 y: 0 } hi", "x: -1 y: -1 } hi") +
                                       "fluids{material:\"water\" shape{" + zeros + "]}}}"});
  std::string times = "output{times:[";
  for (int i = 0; i < kMaxTableEntries; ++i) times += i ? ",0" : "0";
  forms.push_back({"1e5 output times", fluid_case(kBox) + times + "]}"});
  forms.push_back({"a 256-byte name of raw bytes",
                   replace(fluid_case(kBox), "name: \"t\"",
                           "name:\"" + std::string(kMaxNameBytes, '\xff') + "\"")});
  double worst = 0;
  for (const auto& f : forms) {
    const v1::Case c = parse_case_text(f.text);
    const auto errs = validate_case(c);
    EXPECT_TRUE(errs.empty()) << f.name << ": " << join_errors(errs);
    const double canonical = static_cast<double>(case_to_text(c).size());
    google::protobuf::TextFormat::Printer one_line;
    one_line.SetSingleLineMode(true);
    one_line.SetUseUtf8StringEscaping(true);
    std::string line;
    one_line.PrintToString(c, &line);
    const double request = static_cast<double>(f.text.size());
    std::printf("%-32s request %8.0f B, canonical %9.0f B (%5.2fx), one line %9.0f B (%5.2fx)\n",
                f.name.c_str(), request, canonical, canonical / request,
                static_cast<double>(line.size()), line.size() / request);
    worst = std::max(worst, canonical / request);
    EXPECT_LE(canonical, kMaxCanonicalTextGrowth * request) << f.name;
  }
  std::printf("worst canonical growth %.2fx, bound %.0fx\n", worst, kMaxCanonicalTextGrowth);
}

}  // namespace
}  // namespace sph
