#include "study/study_report.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace sph::study {
namespace {

[[gnu::format(printf, 1, 2)]] std::string fmt(const char* f, ...) {
  char buf[64];
  va_list args;
  va_start(args, f);
  std::vsnprintf(buf, sizeof buf, f, args);
  va_end(args);
  return buf;
}

std::string g(double v) {
  return fmt("%.6g", v);
}

std::string count(double n) {
  if (n >= 1e9) return fmt("%.2fG", n / 1e9);
  if (n >= 1e6) return fmt("%.2fM", n / 1e6);
  if (n >= 1e4) return fmt("%.1fk", n / 1e3);
  return fmt("%.0f", n);
}

std::string percent(double e) {
  if (!std::isfinite(e)) return "n/a";
  if (e >= 0.01) return fmt("%.2f%%", 100 * e);
  return fmt("%.3g%%", 100 * e);
}

std::string csv_number(double v) {
  return std::isfinite(v) ? fmt("%.8g", v) : "nan";
}

void check(std::ofstream& out, const std::string& path) {
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::string format_seconds(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 120) return fmt("%.3g s", s);
  if (s < 7200) return fmt("%.3g min", s / 60);
  if (s < 172800) return fmt("%.3g h", s / 3600);
  return fmt("%.3g d", s / 86400);
}

void write_study_csv(const std::string& path, const StudyDescription& d,
                     const std::vector<LevelResult>& levels, const StudySummary& s) {
  std::ofstream out(path);
  out << "# sphd convergence study (docs/accuracy.md)\n"
      << "# case: " << d.case_name << "\n"
      << "# error: " << d.error_definition << "\n"
      << "# ladder: " << d.ladder << "\n";
  if (s.error_vs_dx.ok) out << "# observed_order_dx: " << csv_number(s.error_vs_dx.slope) << "\n";
  if (s.error_vs_wall.ok)
    out << "# error_vs_wall_slope: " << csv_number(s.error_vs_wall.slope) << "\n";
  if (!d.note.empty()) out << "# note: " << d.note << "\n";
  for (const auto& t : s.targets) {
    out << "# target " << csv_number(t.error) << ": ";
    if (!t.reachable) {
      out << "not reachable\n";
      continue;
    }
    out << "dx " << csv_number(t.dx) << " particles " << csv_number(t.particles)
        << " core_seconds_per_simulated_second " << csv_number(t.core_seconds_per_simulated_second)
        << (t.met_by_every_level ? " every_level"
            : t.extrapolated     ? " extrapolated_finer"
                                 : " interpolated")
        << "\n";
  }
  out << "level,dx,particles,steps,particle_steps,wall_seconds,cpu_seconds,"
         "core_seconds_per_simulated_second,peak_rss_mib,ranks,simulated_time,error,quantity,"
         "status,reused,resumed\n";
  for (const auto& l : levels)
    out << l.level << "," << csv_number(l.dx) << "," << csv_number(l.particles) << "," << l.steps
        << "," << csv_number(l.particle_steps) << "," << csv_number(l.wall_seconds) << ","
        << csv_number(l.cpu_seconds) << "," << csv_number(l.core_seconds_per_simulated_second())
        << "," << csv_number(l.peak_rss_bytes / 1048576.0) << "," << l.ranks << ","
        << csv_number(l.simulated_time) << "," << csv_number(l.measurement.error) << ","
        << csv_number(l.measurement.quantity) << ","
        << (l.status == "not run" ? "not_run" : l.status) << "," << (l.reused ? 1 : 0) << ","
        << (l.resumed ? 1 : 0) << "\n";
  check(out, path);
}

void write_study_markdown(const std::string& path, const StudyDescription& d,
                          const std::vector<LevelResult>& levels, const StudySummary& s,
                          const std::string& plot) {
  std::ofstream out(path);
  out << "## Convergence study: " << d.case_name << "\n\n";
  if (!d.case_description.empty()) out << d.case_description << ".\n\n";
  out << "Error: " << d.error_definition << ". Ladder: " << d.ladder << ".\n\n";
  out << "| level | dx | particles | steps | particle-steps | wall | CPU | "
         "core-s per unit sim. time | peak RSS | ranks | error | status |\n"
      << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& l : levels) {
    out << "| " << l.level << " | " << g(l.dx) << " | " << count(l.particles) << " | "
        << count(static_cast<double>(l.steps)) << " | " << count(l.particle_steps) << " | "
        << format_seconds(l.wall_seconds) << " | " << format_seconds(l.cpu_seconds) << " | "
        << fmt("%.4g", l.core_seconds_per_simulated_second()) << " | "
        << fmt("%.0f MiB", l.peak_rss_bytes / 1048576.0) << " | " << l.ranks << " | "
        << percent(l.measurement.error) << " | " << l.status;
    if (l.reused) out << " (reused)";
    if (l.resumed) out << " (resumed)";
    out << " |\n";
  }
  out << "\n";
  if (s.error_vs_dx.ok) {
    out << "**Observed order " << fmt("%.2f", s.error_vs_dx.slope)
        << "** (least-squares slope of log error against log dx over " << s.error_vs_dx.points
        << " levels)";
    if (s.error_vs_wall.ok)
      out << "; against wall time the error falls as wall^" << fmt("%.2f", s.error_vs_wall.slope);
    out << ".\n\n";
  } else {
    out << "No observed order: fewer than two levels have a positive error.\n\n";
  }
  if (!d.note.empty()) out << "Note: " << d.note << "\n\n";
  out << "| target error | dx needed | particles | one core, per unit of simulated time | how |\n"
      << "|---:|---:|---:|---:|---|\n";
  for (const auto& t : s.targets) {
    out << "| " << percent(t.error) << " | ";
    if (!t.reachable) {
      out << "- | - | - | not reachable: the error does not fall with dx, and not every level "
             "is within the target |\n";
      continue;
    }
    out << g(t.dx) << " | " << count(t.particles) << " | "
        << format_seconds(t.core_seconds_per_simulated_second) << " | "
        << (t.met_by_every_level ? "every level is within it: the coarsest level's own numbers"
            : t.extrapolated     ? "extrapolated beyond the finest level along the fitted order"
                                 : "interpolated between levels along the fitted order")
        << " |\n";
  }
  out << "\n";
  if (!plot.empty())
    out << "![error against dx and against wall time, log-log](" << plot << ")\n\n";
  check(out, path);
}

}  // namespace sph::study
