#include "common/log.h"

#include <atomic>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <string>

#include "common/time_text.h"

namespace sph::service {
namespace {
const char* g_name = "sphd";
std::atomic<bool> g_enabled{true};
std::mutex g_sink_mu;
std::function<void(const std::string&)> g_sink;
}  // namespace

void set_log_sink(std::function<void(const std::string&)> sink) {
  std::lock_guard lock(g_sink_mu);
  g_sink = std::move(sink);
}

void set_log_name(const char* name) {
  g_name = name;
}

void set_log_enabled(bool enabled) {
  g_enabled.store(enabled, std::memory_order_relaxed);
}

void log_line(const char* format, ...) {
  if (!g_enabled.load(std::memory_order_relaxed)) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()) % 1000;
  const std::string stamp = format_unix_seconds(t);
  char msg[2048];
  va_list args;
  va_start(args, format);
  std::vsnprintf(msg, sizeof msg, format, args);
  va_end(args);
  // One fprintf per line so lines from different threads do not interleave.
  std::fprintf(stderr, "%s.%03d %s: %s\n", stamp.c_str(), static_cast<int>(ms.count()), g_name,
               msg);
  std::lock_guard lock(g_sink_mu);
  if (g_sink) g_sink(msg);
}

}  // namespace sph::service
