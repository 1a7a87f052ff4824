#include "worker/local_study.h"

#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "study/run_study.h"
#include "study/study_report.h"
#include "worker/local_run.h"

namespace sph::worker {

int run_local_study(const v1::Case& c, const v1::StudySpec& spec, const std::string& out_dir,
                    bool quiet, const std::atomic<bool>* interrupt) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const auto errors = validate_study(c, spec);
  if (!errors.empty()) {
    if (rank == 0) {
      std::fprintf(stderr, "sph-worker: invalid study:\n");
      for (const auto& e : errors) std::fprintf(stderr, "  %s\n", e.to_string().c_str());
    }
    return kExitInvalidCase;
  }
  const std::vector<double> ladder = study_ladder(c, spec);
  study::StudyOptions o;
  o.output_dir = std::filesystem::absolute(out_dir).string();
  o.ladder_description = describe_study(spec);
  o.metadata["mode"] = "local-study";
  o.quiet = quiet;
  o.interrupt = interrupt;
  if (rank == 0) {
    std::printf("study of %s: %zu levels, dx =", c.name().c_str(), ladder.size());
    for (double dx : ladder) std::printf(" %.6g", dx);
    std::printf("\n");
    std::fflush(stdout);
    o.on_level = [&](const study::LevelResult& l) {
      std::printf("level %d/%zu dx = %.6g: %s%s", l.level, ladder.size(), l.dx, l.status.c_str(),
                  l.reused    ? " (done before, reused)"
                  : l.resumed ? " (resumed)"
                              : "");
      if (std::isfinite(l.measurement.error))
        std::printf(", error %.4g%%", 100 * l.measurement.error);
      else if (!l.measurement.detail.empty())
        std::printf(", %s", l.measurement.detail.c_str());
      std::printf(", %s wall, %.0f particles x %lld steps, peak %.0f MiB, %d rank(s)%s%s\n",
                  study::format_seconds(l.wall_seconds).c_str(), l.particles,
                  static_cast<long long>(l.steps), l.peak_rss_bytes / 1048576.0, l.ranks,
                  l.message.empty() ? "" : ": ", l.message.c_str());
      std::fflush(stdout);
    };
  }
  const study::StudyOutcome r = study::run_study(c, ladder, MPI_COMM_WORLD, o);
  if (rank == 0) {
    std::printf("%s: %s\n", to_string(r.status), r.message.c_str());
    if (!r.plot_problem.empty()) std::printf("  no study.png: %s\n", r.plot_problem.c_str());
    for (const auto& f : r.files)
      if (f.ends_with("study.md") || f.ends_with("study.csv") || f.ends_with("study.png"))
        std::printf("  wrote %s\n", f.c_str());
    std::fflush(stdout);
  }
  switch (r.status) {
    case RunStatus::kCompleted:
      return kExitOk;
    case RunStatus::kInterrupted:
    case RunStatus::kCancelled:
      return kExitInterrupted;
    default:
      return kExitError;
  }
}

}  // namespace sph::worker
