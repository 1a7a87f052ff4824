#include "study/run_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/evaluate_reference.h"
#include "case/estimate.h"
#include "case/load.h"
#include "case/study_ladder.h"
#include "solver/parallel/comm.h"
#include "study/peak_memory.h"
#include "study/study_plot.h"
#include "study/study_report.h"

namespace sph::study {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kLevelCase = "case.textproto";
constexpr const char* kWallSuffix = ".wall";  // next to a checkpoint: wall seconds up to it

std::string level_dir_name(int k) {
  return "level_" + std::to_string(k);
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const fs::path& p, const std::string& text) {
  const fs::path tmp = p.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, p);
}

// What decides a level's run: its case without the reference, which only the evaluators
// read. A changed reference re-evaluates finished levels instead of running them again.
std::string run_text(const std::string& level_text) {
  try {
    v1::Case c = parse_case_text(level_text);
    c.clear_reference();
    return case_to_text(c);
  } catch (const CaseLoadError&) {
    return {};
  }
}

// The level directory ran (or runs) this level case.
bool same_case(const fs::path& dir, const std::string& level_text) {
  const std::string stored = run_text(read_file(dir / kLevelCase));
  return !stored.empty() && stored == run_text(level_text);
}

std::string newest_checkpoint(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> all;
  for (const auto& e : fs::directory_iterator(dir / "checkpoints", ec))
    if (e.path().extension() == ".h5") all.push_back(e.path());
  if (all.empty()) return {};
  return std::max_element(all.begin(), all.end())->string();  // names hold the zero-padded step
}

double read_wall_sidecar(const std::string& checkpoint) {
  std::ifstream in(checkpoint + kWallSuffix);
  double wall = 0;
  return (in >> wall) ? wall : 0;
}

// Rank 0's decision for one level.
struct LevelPlan {
  bool reuse = false;
  fs::path reuse_from;  // directory with a level.txt for this level case
  std::string resume_from;
  std::string previous_result;
  double wall_before = 0;
};

LevelPlan plan_level(const fs::path& here, const std::vector<std::string>& previous_dirs,
                     const std::string& level_name, const std::string& level_text,
                     const std::string& claimed_checkpoint) {
  std::vector<fs::path> dirs = {here};
  for (const auto& p : previous_dirs) dirs.push_back(fs::path(p) / level_name);
  LevelPlan plan;
  for (const auto& d : dirs)
    if (same_case(d, level_text) && load_level_record(d.string())) {
      plan.reuse = true;
      plan.reuse_from = d;
      return plan;
    }
  // A checkpoint of this level: the one the server handed over, else the newest found.
  std::vector<std::string> candidates;
  if (!claimed_checkpoint.empty()) {
    const fs::path level_dir = fs::path(claimed_checkpoint).parent_path().parent_path();
    for (const auto& d : dirs) {
      std::error_code ec;
      if (fs::equivalent(level_dir, d, ec) && same_case(d, level_text))
        candidates.push_back(claimed_checkpoint);
    }
  }
  for (const auto& d : dirs)
    if (same_case(d, level_text))
      if (auto cp = newest_checkpoint(d); !cp.empty()) candidates.push_back(cp);
  for (const auto& cp : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(cp, ec)) continue;
    plan.resume_from = cp;
    plan.previous_result = (fs::path(cp).parent_path().parent_path() / "result.h5").string();
    plan.wall_before = read_wall_sidecar(cp);
    break;
  }
  return plan;
}

// Copies a finished level from an earlier attempt's directory into this one (the manifest
// may only name files inside the attempt directory).
void copy_level(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (fs::equivalent(from, to, ec)) return;
  fs::create_directories(to);
  for (const char* name : {"result.h5", "result.xmf", kLevelCase})
    if (fs::exists(from / name))
      fs::copy_file(from / name, to / name, fs::copy_options::overwrite_existing);
  // level.txt last: it marks the level as complete.
  fs::copy_file(from / "level.txt", to / "level.txt", fs::copy_options::overwrite_existing);
}

std::string status_word(RunStatus s) {
  return to_string(s);
}

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Weight of each level in the ladder's progress: estimated particle-steps.
std::vector<double> level_weights(const v1::Case& c, const std::vector<double>& ladder) {
  std::vector<double> w;
  for (double dx : ladder) {
    const CaseEstimate e = estimate_case(level_case(c, dx));
    w.push_back(std::max(1.0, e.total() * std::max(1.0, e.steps)));
  }
  return w;
}

}  // namespace

StudyOutcome run_study(const v1::Case& c, const std::vector<double>& ladder, MPI_Comm comm_raw,
                       const StudyOptions& options) {
  const Comm comm(comm_raw);
  StudyOutcome out;
  StudyOptions o = options;
  o.output_dir = comm.broadcast(o.output_dir);
  const fs::path root = fs::absolute(o.output_dir);
  if (comm.root()) {
    std::error_code ec;
    fs::create_directories(root, ec);
  }
  comm.barrier();

  const int n = static_cast<int>(ladder.size());
  const std::vector<double> weights = level_weights(c, ladder);
  double total_weight = 0;
  for (double w : weights) total_weight += w;
  double done_weight = 0;      // levels over (run or reused)
  double run_here_weight = 0;  // work this process did on finished levels, for the ETA
  const auto study_start = Clock::now();
  bool stop = false;
  RunStatus stop_status = RunStatus::kCompleted;
  std::string stop_message;

  for (int k = 1; k <= n; ++k) {
    LevelResult lr;
    lr.level = k;
    lr.dx = ladder[static_cast<std::size_t>(k - 1)];
    if (stop) {
      out.levels.push_back(lr);
      continue;
    }
    // Cancel and interrupt between levels too, not only at step boundaries.
    int halt = 0;
    if (comm.root() && o.cancel_requested && o.cancel_requested()) halt = 1;
    if (o.interrupt != nullptr && o.interrupt->load()) halt = std::max(halt, 2);
    halt = static_cast<int>(comm.max(static_cast<std::int64_t>(halt)));
    if (halt != 0) {
      stop = true;
      stop_status = halt == 1 ? RunStatus::kCancelled : RunStatus::kInterrupted;
      stop_message = halt == 1 ? "cancelled before level " + std::to_string(k)
                               : "interrupted before level " + std::to_string(k);
      out.levels.push_back(lr);
      continue;
    }

    const v1::Case level = level_case(c, lr.dx);
    const std::string level_text = case_to_text(level);
    const std::string name = level_dir_name(k);
    const fs::path here = root / name;
    LevelPlan plan;
    if (comm.root()) plan = plan_level(here, o.previous_dirs, name, level_text, o.resume_from);
    const bool reuse = comm.broadcast(plan.reuse ? "1" : "") == "1";
    const double w = weights[static_cast<std::size_t>(k - 1)];

    if (reuse) {
      if (comm.root()) {
        try {
          copy_level(plan.reuse_from, here);
          lr = *load_level_record(here.string());
          lr.reused = true;
        } catch (const std::exception& e) {
          lr.status = "error";
          lr.message = std::string("cannot reuse the finished level: ") + e.what();
        }
      }
      comm.barrier();
      done_weight += w;
    } else {
      plan.resume_from = comm.broadcast(plan.resume_from);
      plan.previous_result = comm.broadcast(plan.previous_result);
      if (comm.root()) {
        std::error_code ec;
        fs::create_directories(here, ec);
        fs::remove(here / "level.txt", ec);
        write_file(here / kLevelCase, level_text);
      }
      comm.barrier();
      reset_peak_resident();
      const double cpu_start = process_cpu_seconds();
      const auto level_start = Clock::now();
      const double wall_before = plan.wall_before;
      double start_fraction = -1;  // the level's progress when this run of it began
      Progress last_progress;

      RunOptions ro;
      ro.output_dir = here.string();
      ro.resume_from = plan.resume_from;
      ro.previous_result = plan.previous_result;
      ro.case_text = level_text;
      ro.metadata = o.metadata;
      ro.metadata["study_level"] = std::to_string(k);
      ro.metadata["study_levels"] = std::to_string(n);
      ro.metadata["study_dx"] = g(lr.dx);
      ro.progress_interval_seconds = o.progress_interval_seconds;
      ro.quiet = o.quiet;
      ro.interrupt = o.interrupt;
      if (comm.root()) {
        ro.on_progress = [&](const Progress& p) {
          last_progress = p;
          const double f = p.end_time > 0 ? std::clamp(p.time / p.end_time, 0.0, 1.0) : 0;
          if (start_fraction < 0) start_fraction = f;
          if (!o.on_progress) return;
          StudyProgress sp;
          sp.level = k;
          sp.levels = n;
          sp.dx = lr.dx;
          sp.run = p;
          sp.fraction = (done_weight + w * f) / total_weight;
          // Work this process did (finished levels plus this one since it began) over the
          // wall time it took gives the rate for the rest of the ladder.
          const double here_work = run_here_weight + w * (f - start_fraction);
          const double elapsed = std::chrono::duration<double>(Clock::now() - study_start).count();
          if (here_work > 0 && elapsed > 0)
            sp.eta_seconds = (total_weight - done_weight - w * f) * elapsed / here_work;
          o.on_progress(sp);
        };
        ro.cancel_requested = o.cancel_requested;
        ro.checkpoint_requested = o.checkpoint_requested;
        ro.prune_checkpoints = o.prune_checkpoints;
        ro.on_checkpoint = [&](const std::string& path, std::int64_t step, double time) {
          // The wall time up to this checkpoint, so a level resumed from it reports its
          // whole cost.
          const double wall =
              wall_before + std::chrono::duration<double>(Clock::now() - level_start).count();
          std::ofstream(path + kWallSuffix) << wall << "\n";
          std::error_code ec;
          for (const auto& e : fs::directory_iterator(fs::path(path).parent_path(), ec)) {
            const std::string p = e.path().string();
            if (p.size() > 5 && p.ends_with(kWallSuffix) && !fs::exists(p.substr(0, p.size() - 5)))
              fs::remove(e.path(), ec);
          }
          if (o.on_checkpoint) o.on_checkpoint(path, step, time);
        };
      }
      const RunOutcome r = run_case(level, comm.raw(), ro);
      const double peak = comm.max(peak_resident_bytes());
      const double cpu = comm.sum(process_cpu_seconds() - cpu_start);
      if (comm.root()) {
        lr.status = status_word(r.status);
        lr.message = r.message;
        lr.simulated_time = r.time;
        lr.steps = r.steps;
        lr.particles = static_cast<double>(last_progress.particles);
        lr.particle_steps = static_cast<double>(r.steps) * lr.particles;
        lr.wall_seconds = wall_before + r.wall_seconds;
        lr.cpu_seconds = cpu;
        lr.peak_rss_bytes = peak;
        lr.ranks = comm.size();
        lr.resumed = !plan.resume_from.empty();
        if (!r.last_checkpoint.empty()) out.last_checkpoint = r.last_checkpoint;
        // Completed and unstable levels are final: a rerun would give the same.
        if (r.status == RunStatus::kCompleted || r.status == RunStatus::kUnstable) {
          try {
            save_level_record(here.string(), lr);
          } catch (const std::exception& e) {
            lr.message += std::string("; ") + e.what();
          }
        }
      }
      const int status = static_cast<int>(
          comm.max(static_cast<std::int64_t>(comm.root() ? static_cast<int>(r.status) : 0)));
      const auto rs = static_cast<RunStatus>(status);
      if (rs == RunStatus::kCancelled || rs == RunStatus::kInterrupted || rs == RunStatus::kError) {
        stop = true;
        stop_status = rs;
        stop_message = "level " + std::to_string(k) + " (dx = " + g(lr.dx) + ") " +
                       status_word(rs) + (r.message.empty() ? "" : ": " + r.message);
      } else {
        done_weight += w;
        run_here_weight += w * (1 - std::max(0.0, start_fraction));
      }
    }
    if (comm.root() && lr.completed()) {
      try {
        lr.measurement = analysis::evaluate_reference(level, (here / "result.h5").string());
      } catch (const std::exception& e) {
        lr.message = std::string("no error: ") + e.what();
      }
    }
    if (comm.root() && o.on_level) o.on_level(lr);
    out.levels.push_back(lr);
  }

  // The report (rank 0), also after a cancel: it shows what was measured so far.
  int final_status = static_cast<int>(RunStatus::kCompleted);
  if (comm.root()) {
    std::vector<analysis::Measurement> m;
    for (const auto& l : out.levels) m.push_back(l.measurement);
    StudyDescription d;
    d.case_name = c.name();
    d.case_description = c.description();
    d.error_definition = analysis::describe_reference(c);
    d.ladder = o.ladder_description;
    d.note = analysis::complete_richardson(c, ladder, m);
    for (std::size_t k = 0; k < out.levels.size(); ++k) out.levels[k].measurement = m[k];
    out.summary = summarize_study(out.levels);
    int with_error = 0;
    for (const auto& l : out.levels)
      if (l.completed() && std::isfinite(l.measurement.error)) ++with_error;
    try {
      const std::string csv = (root / "study.csv").string(), md = (root / "study.md").string();
      const std::string png = (root / "study.png").string();
      write_study_csv(csv, d, out.levels, out.summary);
      out.files.push_back(csv);
      std::error_code ec;
      fs::remove(png, ec);
      if (o.plot && with_error > 0) {
        out.plot_problem = plot_study(o.python.empty() ? default_python() : o.python, csv, png);
        if (out.plot_problem.empty()) out.files.push_back(png);
      } else if (o.plot) {
        out.plot_problem = "no level has an error to plot";
      }
      write_study_markdown(md, d, out.levels, out.summary,
                           out.plot_problem.empty() && o.plot ? "study.png" : "");
      out.files.insert(out.files.begin() + 1, md);
      for (const auto& l : out.levels)
        for (const char* f : {"result.h5", "result.xmf"}) {
          const fs::path p = root / level_dir_name(l.level) / f;
          if (l.status != "not run" && fs::is_regular_file(p, ec)) out.files.push_back(p.string());
        }
    } catch (const std::exception& e) {
      stop = true;
      stop_status = RunStatus::kError;
      stop_message = std::string("cannot write the study report: ") + e.what();
    }
    const double wall = std::chrono::duration<double>(Clock::now() - study_start).count();
    if (stop) {
      out.status = stop_status;
      out.message = stop_message;
    } else if (with_error < 2) {
      out.status = RunStatus::kError;
      out.message = "fewer than two levels have an error, so no order" +
                    (d.note.empty() ? std::string() : " (" + d.note + ")");
      for (const auto& l : out.levels)
        if (!l.message.empty() && !l.completed())
          out.message += "; level " + std::to_string(l.level) + ": " + l.message;
    } else {
      out.status = RunStatus::kCompleted;
      out.message = "study of " + std::to_string(n) + " levels: observed order " +
                    (out.summary.error_vs_dx.ok ? g(out.summary.error_vs_dx.slope) : "n/a") +
                    ", error " + g(100 * out.summary.error_max) + "% .. " +
                    g(100 * out.summary.error_min) + "%, " + format_seconds(wall) + " wall";
    }
    final_status = static_cast<int>(out.status);
  }
  out.status = static_cast<RunStatus>(comm.max(static_cast<std::int64_t>(final_status)));
  return out;
}

}  // namespace sph::study
