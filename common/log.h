#pragma once
// One-line, timestamped log messages on stderr for the server and the pools (journald and
// Slurm add their own metadata).
namespace sph::service {

// The program name printed on every line ("sph-server", "sph-worker pool").
void set_log_name(const char* name);

// Off: log_line prints nothing (the RPC fuzzer makes millions of calls).
void set_log_enabled(bool enabled);

[[gnu::format(printf, 1, 2)]] void log_line(const char* format, ...);

}  // namespace sph::service
