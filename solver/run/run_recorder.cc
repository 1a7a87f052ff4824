#include "solver/run/run_recorder.h"

#include <mpi.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>

#include "solver/run/code_version.h"

namespace sph {

RunRecorder::RunRecorder(const Comm& comm, const RunOptions& opt)
    : comm_(comm), opt_(opt), result_(comm, opt.output_dir) {}

void RunRecorder::start_clock() {
  wall_start_ = MPI_Wtime();
  last_checkpoint_wall_ = wall_start_;
}

double RunRecorder::wall_seconds() const {
  return MPI_Wtime() - wall_start_;
}

bool RunRecorder::checkpoint_due(double wall_interval) const {
  return (opt_.checkpoint_requested && opt_.checkpoint_requested()) ||
         (wall_interval > 0 && MPI_Wtime() - last_checkpoint_wall_ >= wall_interval);
}

std::string RunRecorder::checkpoint_path(std::int64_t step) const {
  char name[64];
  std::snprintf(name, sizeof name, "ckpt_%012lld.h5", static_cast<long long>(step));
  return opt_.output_dir + "/checkpoints/" + name;
}

void RunRecorder::after_checkpoint(const std::string& path, std::int64_t step, double t) {
  if (comm_.root()) {
    if (opt_.prune_checkpoints) {  // keep the two newest
      std::vector<std::filesystem::path> all;
      for (const auto& e : std::filesystem::directory_iterator(opt_.output_dir + "/checkpoints"))
        if (e.path().extension() == ".h5") all.push_back(e.path());
      std::sort(all.begin(), all.end());
      for (std::size_t k = 0; k + 2 < all.size(); ++k) std::filesystem::remove(all[k]);
    }
    if (opt_.on_checkpoint) opt_.on_checkpoint(path, step, t);
  }
  last_checkpoint_ = path;
  last_checkpoint_wall_ = MPI_Wtime();
}

void RunRecorder::report_progress(Progress p, bool force) {
  if (!comm_.root()) return;
  const double now = MPI_Wtime();
  if (!force && now - last_progress_wall_ < opt_.progress_interval_seconds) return;
  p.wall_seconds = now - wall_start_;
  const double dwall = now - (last_progress_wall_ < 0 ? wall_start_ : last_progress_wall_);
  if (last_progress_wall_ > -1e299 && dwall > 0) {
    p.particle_steps_per_second = static_cast<double>(p.step - last_progress_step_) *
                                  static_cast<double>(p.particles) / dwall;
    const double rate = (p.time - last_progress_time_) / dwall;
    if (rate > 0) p.eta_seconds = (p.end_time - p.time) / rate;
  }
  last_progress_wall_ = now;
  last_progress_step_ = p.step;
  last_progress_time_ = p.time;
  if (!opt_.quiet) {
    std::printf(
        "step %8lld  t %-11.5g / %-9.4g  dt %-10.3e  N %-9lld  %9.3e particle-steps/s  imbalance "
        "%.2f  ETA %s\n",
        static_cast<long long>(p.step), p.time, p.end_time, p.dt,
        static_cast<long long>(p.particles), p.particle_steps_per_second, p.imbalance,
        p.eta_seconds < 0
            ? "-"
            : (std::to_string(static_cast<long long>(p.eta_seconds + 0.5)) + " s").c_str());
    std::fflush(stdout);
  }
  if (opt_.on_progress) opt_.on_progress(p);
}

std::map<std::string, std::string> RunRecorder::metadata(
    const std::string& case_text, int dimension, double dx, double h, double skin,
    const char* kernel, const std::vector<std::string>& units) const {
  std::map<std::string, std::string> m = opt_.metadata;
  m["case_text"] = opt_.case_text.empty() ? case_text : opt_.case_text;
  m["code_version"] = code_version();
  m["ranks"] = std::to_string(comm_.size());
  m["dimension"] = std::to_string(dimension);
  // The shortest text that reads back as the value (to_string would print 2.5e-6 as 0.000003).
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"dx", dx}, {"h", h}, {"neighbor_skin", skin}}) {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, value).ptr;
    m[key] = std::string(buf, end);
  }
  m["kernel"] = kernel;
  std::string list;
  for (const auto& u : units) list += (list.empty() ? "" : ",") + u;
  m["active_units"] = list;
  return m;
}

std::map<std::string, double> RunRecorder::finish(
    const std::string& status, const std::string& message,
    const std::map<std::string, double>& unit_seconds,
    const std::map<std::string, std::size_t>& local_bytes, std::int64_t neighbor_searches) {
  auto meta = std::map<std::string, std::string>{{"status", status}, {"message", message}};
  // What each unit cost: time (rank 0) and storage (all ranks), for "only the effects a scene
  // calls for".
  std::map<std::string, double> bytes;
  {
    std::vector<double> v;
    for (const auto& [k, b] : local_bytes) v.push_back(static_cast<double>(b));
    comm_.sum_inplace(v);  // every rank has the same units, so the same keys in the same order
    std::size_t i = 0;
    for (const auto& [k, b] : local_bytes) bytes[k] = v[i++];
  }
  std::string times, mem;
  for (const auto& [k, sec] : unit_seconds)
    times += (times.empty() ? "" : ",") + k + "=" + std::to_string(sec);
  for (const auto& [k, b] : bytes)
    mem += (mem.empty() ? "" : ",") + k + "=" + std::to_string(static_cast<long long>(b));
  meta["unit_seconds"] = times;
  meta["unit_bytes"] = mem;
  meta["neighbor_searches"] = std::to_string(neighbor_searches);
  result_.flush();
  result_.set_meta(meta);
  return bytes;
}

}  // namespace sph
