#include "render/job_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "common/job_state.h"
#include "common/time_text.h"

namespace sph::ctl {
namespace {

using service::outcome_name;
using service::state_name;

std::string g(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Fixed-point with `digits` decimals and a suffix ("12.3%", "1.23M").
std::string fixed(double v, int digits, const char* suffix) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f%s", digits, v, suffix);
  return buf;
}

}  // namespace

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (bytes >= 1024 && u < 4) {
    bytes /= 1024;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return buf;
}

std::string format_duration(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  char buf[64];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  return buf;
}

std::string format_count(double n) {
  if (n >= 1e9) return fixed(n / 1e9, 2, "G");
  if (n >= 1e6) return fixed(n / 1e6, 2, "M");
  if (n >= 1e4) return fixed(n / 1e3, 0, "k");
  return fixed(n, 0, "");
}

std::string format_time_ms(std::int64_t unix_ms) {
  if (unix_ms <= 0) return "-";
  return service::format_unix_seconds(unix_ms / 1000);
}

std::string study_summary(const v1::StudySpec& spec) {
  if (spec.dx_size() > 0) {
    std::string s = std::to_string(spec.dx_size()) + " levels, dx =";
    for (double dx : spec.dx()) s.append(" ").append(g(dx));
    return s;
  }
  return std::to_string(spec.refine()) + " levels, refined by " +
         g(spec.has_ratio() ? spec.ratio() : std::sqrt(2.0)) + " from the case's dx";
}

std::string progress_summary(const v1::ProgressInfo& p) {
  std::string s;
  if (p.has_study() && p.study().levels() > 0)
    s.append("level ")
        .append(std::to_string(p.study().level()))
        .append("/")
        .append(std::to_string(p.study().levels()))
        .append(" (dx = ")
        .append(g(p.study().dx()))
        .append(", ladder ")
        .append(fixed(100 * p.study().fraction(), 1, "%"))
        .append(p.study().eta_seconds() >= 0 ? ", ETA " + format_duration(p.study().eta_seconds())
                                             : std::string())
        .append(")  ");
  s += "step " + std::to_string(p.step()) + "  t = " + g(p.time());
  if (p.end_time() > 0)
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    s.append("/")
        .append(g(p.end_time()))
        .append(" s (")
        .append(fixed(100 * p.time() / p.end_time(), 1, "%)"));
  else
    s += " s";
  if (p.dt() > 0) s += "  dt = " + g(p.dt());
  if (p.particles() > 0)
    s += "  " + format_count(static_cast<double>(p.particles())) + " particles";
  if (p.particle_steps_per_second() > 0)
    s += "  " + format_count(p.particle_steps_per_second()) + " particle-steps/s";
  if (p.eta_seconds() >= 0) s += "  ETA " + format_duration(p.eta_seconds());
  return s;
}

std::string describe_job(const v1::Job& j) {
  std::string s = j.id() + "  " + j.name() + (j.has_study() ? " (convergence study)" : "") + "  " +
                  state_name(j.state());
  if (j.attempt() > 0) s += "  attempt " + std::to_string(j.attempt());
  if (j.cancel_requested() && !service::is_terminal(j.state())) s += "  (cancel requested)";
  s += "\n";
  if (!j.reason().empty()) s += "  reason:     " + j.reason() + "\n";
  s += "  created:    " + format_time_ms(j.created_unix_ms());
  if (j.started_unix_ms() > 0) s += "   started: " + format_time_ms(j.started_unix_ms());
  if (j.finished_unix_ms() > 0) s += "   finished: " + format_time_ms(j.finished_unix_ms());
  if (j.has_study()) s += "\n  study:      " + study_summary(j.study());
  s += "\n  particles:  about " + format_count(j.estimated_particles()) +
       (j.has_study() ? " at the finest level\n" : "\n");
  if (j.has_progress()) s += "  progress:   " + progress_summary(j.progress()) + "\n";
  if (j.has_checkpoint())
    s += "  checkpoint: step " + std::to_string(j.checkpoint().step()) +
         ", t = " + g(j.checkpoint().time()) + " (attempt " +
         std::to_string(j.checkpoint().attempt()) + ") " + j.checkpoint().path() + "\n";
  if (j.files_deleted_unix_ms() > 0)
    s += "  files:      deleted " + format_time_ms(j.files_deleted_unix_ms()) + " (" +
         format_bytes(static_cast<double>(j.files_deleted_bytes())) +
         " freed): its result files and checkpoints no longer exist\n";
  if (j.has_result()) {
    s += "  result:     attempt " + std::to_string(j.result().attempt()) + ", " +
         j.result().output_dir() + "\n";
    for (const auto& f : j.result().files())
      s += "    " + f.name() + "  " + format_bytes(static_cast<double>(f.size())) + "  sha256 " +
           f.sha256() + "\n";
  }
  if (j.attempts_size() > 0) {
    s += "  attempts:\n";
    for (const auto& a : j.attempts()) {
      s += "    " + std::to_string(a.number()) + "  " + a.pool() + "  " +
           std::to_string(a.ranks()) + " ranks  " + outcome_name(a.outcome());
      if (!a.resumed_from().empty()) s += "  resumed from " + a.resumed_from();
      if (!a.reason().empty()) s += "  " + a.reason();
      s += "\n";
      if (a.unit_seconds_size() > 0) {
        // The physics units that took the most time, largest first.
        std::vector<std::pair<double, std::string>> units;
        for (const auto& [name, seconds] : a.unit_seconds()) units.emplace_back(seconds, name);
        std::sort(units.rbegin(), units.rend());
        s += "       time:";
        for (size_t i = 0; i < units.size() && i < 6; ++i)
          s += (i ? ", " : " ") + units[i].second + " " + fixed(units[i].first, 2, " s");
        s += "\n";
      }
    }
  }
  return s;
}

std::string job_table_header() {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%-12s %-10s %7s %8s  %-19s  %s", "JOB", "STATE", "ATTEMPT",
                "PROGRESS", "CREATED", "NAME");
  return buf;
}

std::string job_table_row(const v1::Job& j) {
  std::string progress = "-";
  if (j.state() == v1::JOB_STATE_SUCCEEDED)
    progress = "100%";
  else if (j.has_progress() && j.progress().has_study())
    progress = fixed(100 * j.progress().study().fraction(), 1, "%");
  else if (j.has_progress() && j.progress().end_time() > 0)
    progress = fixed(100 * j.progress().time() / j.progress().end_time(), 1, "%");
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-12s %-10s %7d %8s  %-19s  %s", j.id().c_str(),
                state_name(j.state()), j.attempt(), progress.c_str(),
                format_time_ms(j.created_unix_ms()).c_str(),
                (j.has_study() ? j.name() + " (study)" : j.name()).c_str());
  return buf;
}

std::string event_line(const v1::JobEvent& e) {
  std::string s = "[";
  s.append(std::to_string(e.sequence())).append("] ");
  switch (e.kind_case()) {
    case v1::JobEvent::kStateChange: {
      const auto& c = e.state_change();
      s += state_name(c.state());
      if (c.state() == v1::JOB_STATE_RUNNING) s += " attempt " + std::to_string(c.attempt());
      if (!c.reason().empty()) s += ": " + c.reason();
      break;
    }
    case v1::JobEvent::kProgress:
      s += "progress " + progress_summary(e.progress());
      break;
    case v1::JobEvent::kCheckpoint:
      s += "checkpoint step " + std::to_string(e.checkpoint().step()) +
           ", t = " + g(e.checkpoint().time()) + ": " + e.checkpoint().path();
      break;
    case v1::JobEvent::kResultReady: {
      s += "result ready (attempt " + std::to_string(e.result_ready().attempt()) + "):";
      for (const auto& f : e.result_ready().files())
        s += " " + f.name() + " (" + format_bytes(static_cast<double>(f.size())) + ")";
      break;
    }
    case v1::JobEvent::kCancelRequested:
      s += "cancel requested: " + e.cancel_requested().reason();
      break;
    default:
      s += "(unknown event)";
  }
  return s;
}

}  // namespace sph::ctl
