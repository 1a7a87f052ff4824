#pragma once
// One-line, timestamped log messages on stderr for the server and the pools (journald and
// Slurm add their own metadata).
#include <functional>
#include <string>

namespace sph::service {

// The program name printed on every line ("sph-server", "sph-worker pool").
void set_log_name(const char* name);

// Off: log_line prints nothing (the RPC fuzzer makes millions of calls).
void set_log_enabled(bool enabled);

[[gnu::format(printf, 1, 2)]] void log_line(const char* format, ...);

// While set, every log_line's message (without time and name) also goes to `sink`, from
// whichever thread logs it: a pool keeps an attempt's lines for the server (sphctl logs).
// An empty function removes it.
void set_log_sink(std::function<void(const std::string&)> sink);

}  // namespace sph::service
