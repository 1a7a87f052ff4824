#include "worker/local_run.h"

#include <mpi.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "case/load.h"
#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "case/validate.h"
#include "solver/run/run_case.h"
#include "worker/local_study.h"

namespace sph::worker {
namespace {

std::atomic<bool> g_interrupt{false};
extern "C" void on_signal(int) {
  g_interrupt.store(true);
}

constexpr const char* kUsage =
    "usage: sph-worker --case FILE --out DIR [--resume CHECKPOINT] [--quiet] [limits]\n"
    "       sph-worker --case FILE --out DIR (--study-refine N [--study-ratio R] |\n"
    "                  --study-dx A,B,C) [--quiet] [limits]   (a convergence study)\n"
    "       sph-worker --server ADDR [pool options]   (see --server ADDR --help)\n"
    "limits (as sph-server applies them at submit; 0 = no limit):\n"
    "  --max-particles N    refuse cases estimated above N particles (default 2e7)\n"
    "  --max-memory-gib G   refuse cases estimated to need more than G GiB (default 64)\n";

void usage(FILE* to) {
  std::fputs(kUsage, to);
}

// A limit from the command line: a finite number >= 0.
bool parse_limit(const std::string& text, double& value) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < 0) return false;
  value = v;
  return true;
}

// Rank 0 reads the case (point files relative to it are inlined) and broadcasts the text, so
// ranks on other nodes need no access to the file.
bool load_on_root(const std::string& path, int rank, std::string& text, std::string& error) {
  std::int64_t n = 0;
  if (rank == 0) {
    try {
      text = case_to_text(load_case_file(path));
    } catch (const std::exception& e) {
      error = e.what();
      text.clear();
    }
    n = error.empty() ? static_cast<std::int64_t>(text.size()) : -1;
  }
  MPI_Bcast(&n, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  if (n < 0) return false;
  text.resize(static_cast<size_t>(n));
  MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  return true;
}

}  // namespace

int run_local(int argc, char** argv) {
  std::string case_path, out_dir, resume;
  bool quiet = false;
  // The defaults of sph-server (server/config.h), so a case that runs here is accepted there.
  double max_particles = 2e7, max_memory_gib = 64;
  std::string bad_limit;
  bool study = false;
  v1::StudySpec spec;
  std::string study_error;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&](std::string& v) {
      if (i + 1 >= argc) return false;
      v = argv[++i];
      return true;
    };
    bool ok = true;
    if (a == "--case")
      ok = next(case_path);
    else if (a == "--out")
      ok = next(out_dir);
    else if (a == "--resume")
      ok = next(resume);
    else if (a == "--quiet")
      quiet = true;
    else if (a == "--help" || a == "-h") {
      int rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (rank == 0) usage(stdout);
      return kExitOk;
    } else if (a == "--max-particles" || a == "--max-memory-gib") {
      std::string value;
      ok = next(value);
      if (ok && !parse_limit(value, a == "--max-particles" ? max_particles : max_memory_gib))
        bad_limit = a + " needs a number >= 0 (0 = no limit), got '" + value + "'";
    } else if (a == "--study-refine" || a == "--study-ratio" || a == "--study-dx") {
      std::string value;
      ok = next(value);
      study = true;
      if (ok && study_error.empty()) set_study_field(spec, a.substr(8), value, study_error);
    } else
      ok = false;
    if (!ok) {
      usage(stderr);
      return kExitError;
    }
  }
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (case_path.empty() || out_dir.empty() || !study_error.empty() || !bad_limit.empty() ||
      (study && !resume.empty())) {
    if (rank == 0) {
      if (!study_error.empty()) std::fprintf(stderr, "sph-worker: %s\n", study_error.c_str());
      if (!bad_limit.empty()) std::fprintf(stderr, "sph-worker: %s\n", bad_limit.c_str());
      if (study && !resume.empty())
        std::fprintf(stderr,
                     "sph-worker: a study resumes by itself when run again into the same --out "
                     "directory; --resume is for single runs\n");
      usage(stderr);
    }
    return kExitError;
  }
  std::string text, error;
  if (!load_on_root(case_path, rank, text, error)) {
    if (rank == 0) std::fprintf(stderr, "sph-worker: %s\n", error.c_str());
    return kExitInvalidCase;
  }
  const v1::Case c = parse_case_text(text);
  ValidationLimits limits;
  limits.max_particles = max_particles;
  limits.max_memory_bytes = max_memory_gib * 1073741824.0;
  limits.source = "sph-worker's";
  auto errors = validate_case(c, limits);
  // A study is as large as its finest level.
  if (errors.empty() && study) errors = validate_study(c, spec, limits);
  if (!errors.empty()) {
    if (rank == 0) {
      std::fprintf(stderr, "sph-worker: invalid case %s:\n", case_path.c_str());
      for (const auto& e : errors) std::fprintf(stderr, "  %s\n", e.to_string().c_str());
    }
    return kExitInvalidCase;
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  if (study) return run_local_study(c, spec, out_dir, quiet, &g_interrupt);

  RunOptions opt;
  opt.output_dir = std::filesystem::absolute(out_dir).string();
  opt.resume_from = resume;
  if (!resume.empty())
    opt.previous_result =
        (std::filesystem::path(resume).parent_path().parent_path() / "result.h5").string();
  opt.case_text = read_text_file(case_path);
  opt.metadata["mode"] = "local";
  opt.metadata["case_file"] = std::filesystem::absolute(case_path).string();
  opt.interrupt = &g_interrupt;
  opt.quiet = quiet;
  const RunOutcome r = run_case(c, MPI_COMM_WORLD, opt);
  if (rank == 0) {
    std::printf("%s after %lld steps, t = %.6g, %.1f s wall%s%s\n", to_string(r.status),
                static_cast<long long>(r.steps), r.time, r.wall_seconds,
                r.message.empty() ? "" : ": ", r.message.c_str());
    for (const auto& f : r.files) std::printf("  wrote %s\n", f.c_str());
    std::printf("  neighbour searches: %lld in %lld steps since t = 0\n",
                static_cast<long long>(r.neighbor_searches), static_cast<long long>(r.steps));
    double total = 0;
    for (const auto& [unit, sec] : r.unit_seconds) total += sec;
    if (total > 0) {
      std::printf("  time by unit (rank 0):");
      for (const auto& [unit, sec] : r.unit_seconds)
        std::printf(" %s %.1f%%", unit.c_str(), 100 * sec / total);
      std::printf("\n  storage by unit:");
      for (const auto& [unit, b] : r.unit_bytes)
        std::printf(" %s %.1f MiB", unit.c_str(), b / 1048576.0);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
  switch (r.status) {
    case RunStatus::kCompleted:
      return kExitOk;
    case RunStatus::kUnstable:
      return kExitUnstable;
    case RunStatus::kInterrupted:
    case RunStatus::kCancelled:
      return kExitInterrupted;
    case RunStatus::kError:
      break;
  }
  return kExitError;
}

}  // namespace sph::worker
