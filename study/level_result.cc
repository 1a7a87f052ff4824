#include "study/level_result.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace sph::study {
namespace {

constexpr const char* kRecordName = "level.txt";

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Messages are one line; keep them so.
std::string one_line(std::string s) {
  for (char& ch : s)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return s;
}

}  // namespace

double LevelResult::core_seconds_per_simulated_second() const {
  if (!(simulated_time > 0)) return 0;
  const double core_seconds = cpu_seconds > 0 && !resumed ? cpu_seconds : wall_seconds * ranks;
  return core_seconds / simulated_time;
}

void save_level_record(const std::string& dir, const LevelResult& r) {
  namespace fs = std::filesystem;
  const fs::path tmp = fs::path(dir) / (std::string(kRecordName) + ".tmp");
  {
    std::ofstream out(tmp);
    out << "level=" << r.level << "\n"
        << "dx=" << exact(r.dx) << "\n"
        << "status=" << r.status << "\n"
        << "message=" << one_line(r.message) << "\n"
        << "simulated_time=" << exact(r.simulated_time) << "\n"
        << "steps=" << r.steps << "\n"
        << "particles=" << exact(r.particles) << "\n"
        << "particle_steps=" << exact(r.particle_steps) << "\n"
        << "wall_seconds=" << exact(r.wall_seconds) << "\n"
        << "cpu_seconds=" << exact(r.cpu_seconds) << "\n"
        << "peak_rss_bytes=" << exact(r.peak_rss_bytes) << "\n"
        << "ranks=" << r.ranks << "\n"
        << "resumed=" << (r.resumed ? 1 : 0) << "\n";
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, fs::path(dir) / kRecordName);
}

std::optional<LevelResult> load_level_record(const std::string& dir) {
  std::ifstream in(std::filesystem::path(dir) / kRecordName);
  if (!in) return std::nullopt;
  std::map<std::string, std::string> kv;
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  try {
    LevelResult r;
    r.level = std::stoi(kv.at("level"));
    r.dx = std::stod(kv.at("dx"));
    r.status = kv.at("status");
    r.message = kv["message"];
    r.simulated_time = std::stod(kv.at("simulated_time"));
    r.steps = std::stoll(kv.at("steps"));
    r.particles = std::stod(kv.at("particles"));
    r.particle_steps = std::stod(kv.at("particle_steps"));
    r.wall_seconds = std::stod(kv.at("wall_seconds"));
    r.cpu_seconds = kv.count("cpu_seconds") ? std::stod(kv["cpu_seconds"]) : 0;
    r.peak_rss_bytes = std::stod(kv.at("peak_rss_bytes"));
    r.ranks = std::stoi(kv.at("ranks"));
    r.resumed = kv["resumed"] == "1";
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // a record from another version or damaged: run the level again
  }
}

}  // namespace sph::study
