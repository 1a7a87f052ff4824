// sphctl study CASE (--refine N [--ratio R] | --dx A,B,C) [--watch] [--dry-run]
//               [--request-id ID]
// A convergence study: the case run at a ladder of resolutions, each measured against the
// case's reference (docs/accuracy.md).
#include <google/protobuf/struct.pb.h>

#include <cstdio>

#include "case/estimate.h"
#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {
namespace {

constexpr const char* kUsageText =
    "usage: sphctl study CASE.textproto (--refine N [--ratio R] | --dx A,B,C) [--watch] "
    "[--dry-run] [--request-id ID]";

int print_ladder(const GlobalOptions& g, const v1::Case& c, const v1::StudySpec& spec,
                 const std::string& path) {
  const auto ladder = study_ladder(c, spec);
  if (g.json) {
    google::protobuf::Struct s;
    auto& f = *s.mutable_fields();
    f["case"].set_string_value(path);
    f["name"].set_string_value(c.name());
    f["ladder"].set_string_value(describe_study(spec));
    auto* levels = f["levels"].mutable_list_value();
    for (double dx : ladder) {
      const CaseEstimate e = estimate_case(level_case(c, dx));
      auto& l = *levels->add_values()->mutable_struct_value()->mutable_fields();
      l["dx"].set_number_value(dx);
      l["total_particles"].set_number_value(e.total());
      l["estimated_steps"].set_number_value(e.steps);
      l["estimated_bytes"].set_number_value(e.bytes);
    }
    std::printf("%s\n", to_json(s).c_str());
    return kOk;
  }
  std::printf("study of %s (%dD, %s): valid, not submitted (--dry-run)\n", c.name().c_str(),
              c.dimension(), describe_study(spec).c_str());
  std::printf("  %-5s %-12s %12s %12s %14s %10s\n", "level", "dx", "particles", "steps",
              "particle-steps", "memory");
  double total = 0;
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    const CaseEstimate e = estimate_case(level_case(c, ladder[k]));
    total += e.total() * e.steps;
    std::printf("  %-5zu %-12.6g %12s %12s %14s %10s\n", k + 1, ladder[k],
                format_count(e.total()).c_str(), format_count(e.steps).c_str(),
                format_count(e.total() * e.steps).c_str(), format_bytes(e.bytes).c_str());
  }
  std::printf("  total about %s particle-steps\n", format_count(total).c_str());
  return kOk;
}

}  // namespace

int cmd_study(const GlobalOptions& g, ArgScanner args) {
  const bool watch = args.take_flag("--watch");
  const bool dry_run = args.take_flag("--dry-run");
  std::string request_id, refine, ratio, dx;
  args.take_value("--request-id", request_id);
  const bool has_refine = args.take_value("--refine", refine);
  const bool has_ratio = args.take_value("--ratio", ratio);
  const bool has_dx = args.take_value("--dx", dx);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, kUsageText, pos)) return kUsage;
  if (!has_refine && !has_dx) {
    std::fprintf(stderr, "sphctl: study needs --refine N or --dx A,B,C\n%s\n", kUsageText);
    return kUsage;
  }
  v1::StudySpec spec;
  std::string error;
  if ((has_refine && !set_study_field(spec, "refine", refine, error)) ||
      (has_ratio && !set_study_field(spec, "ratio", ratio, error)) ||
      (has_dx && !set_study_field(spec, "dx", dx, error))) {
    std::fprintf(stderr, "sphctl: %s\n%s\n", error.c_str(), kUsageText);
    return kUsage;
  }
  const std::string& path = pos[0];
  v1::Case c;
  if (const int rc = load_and_validate(path, c); rc != kOk) return rc;
  if (const auto errors = validate_study(c, spec); !errors.empty()) {
    std::fprintf(stderr, "sphctl: invalid study of %s:\n", path.c_str());
    for (const auto& e : errors) std::fprintf(stderr, "  %s\n", e.to_string().c_str());
    return kInvalidCase;
  }
  if (dry_run) return print_ladder(g, c, spec, path);
  return submit_job(g, c, path, &spec, watch, request_id);
}

}  // namespace sph::ctl
