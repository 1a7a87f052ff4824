#include "server/config.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace sph::server {
namespace {

constexpr const char* kUsage = R"(usage: sph-server [options]

  --address HOST:PORT     listen address (default 127.0.0.1:7070; port 0 picks a free port)
  --address-file FILE     write the bound HOST:PORT to FILE once listening
  --metrics-address HOST:PORT  serve Prometheus metrics at http://HOST:PORT/metrics (default: off;
                          no token is asked there: bind it where only the scraper reaches)
  --metrics-address-file FILE  write the bound metrics HOST:PORT to FILE once listening
  --db PATH               SQLite database (default ./sphd.db; local disk, not NFS)
  --results DIR           results root shared with the worker pools (default ./results)
  --lease SECONDS         lease a pool must renew by reporting (default 30)
  --token-file FILE       require "authorization: Bearer <token>" on every call
  --max-particles N       reject cases estimated above N particles (default 2e7, 0 = no limit)
  --max-memory-gib G      reject cases estimated to need more than G GiB (default 64, 0 = no limit)
  --max-queued-jobs N     refuse submits while N jobs are queued or running (default 10000, 0 = no limit)
  --max-queued-particles N  refuse submits that would bring the estimated particles of queued and
                          running jobs above N (default 1e9, 0 = no limit)
  --max-streams-per-client N  open WatchJob/FetchResult streams per client (default 256)
  --max-lost-leases N     fail a job after its pool was lost N times (default 5)
  --shutdown-grace SECONDS  time open calls get on SIGTERM before they are cut (default 5)
)";

bool parse_double(const char* text, double& out) {
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && *end == '\0';
}

}  // namespace

std::optional<ServerConfig> parse_server_args(int argc, char** argv, int& exit_code) {
  ServerConfig c;
  exit_code = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      exit_code = 0;
      return std::nullopt;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "sph-server: %s needs a value\n%s", a.c_str(), kUsage);
      return std::nullopt;
    }
    const char* v = argv[++i];
    double number = 0;
    bool ok = true;
    if (a == "--address")
      c.address = v;
    else if (a == "--address-file")
      c.address_file = v;
    else if (a == "--metrics-address")
      c.metrics_address = v;
    else if (a == "--metrics-address-file")
      c.metrics_address_file = v;
    else if (a == "--db")
      c.db_path = v;
    else if (a == "--results")
      c.results_dir = v;
    else if (a == "--token-file")
      c.token_file = v;
    else if (a == "--lease")
      ok = parse_double(v, c.lease_seconds) && c.lease_seconds > 0;
    else if (a == "--max-particles")
      ok = parse_double(v, c.max_particles) && c.max_particles >= 0;
    else if (a == "--max-memory-gib")
      ok = parse_double(v, c.max_memory_gib) && c.max_memory_gib >= 0;
    else if (a == "--max-queued-jobs")
      ok = parse_double(v, c.max_queued_jobs) && c.max_queued_jobs >= 0;
    else if (a == "--max-queued-particles")
      ok = parse_double(v, c.max_queued_particles) && c.max_queued_particles >= 0;
    else if (a == "--max-streams-per-client") {
      ok = parse_double(v, number) && number >= 1 && number <= 1e6;
      c.max_streams_per_client = static_cast<int>(number);
    } else if (a == "--shutdown-grace")
      ok = parse_double(v, c.shutdown_grace_seconds) && c.shutdown_grace_seconds >= 0;
    else if (a == "--max-lost-leases") {
      ok = parse_double(v, number) && number >= 1;
      c.max_lost_leases = static_cast<int>(number);
    } else {
      std::fprintf(stderr, "sph-server: unknown option %s\n%s", a.c_str(), kUsage);
      return std::nullopt;
    }
    if (!ok) {
      std::fprintf(stderr, "sph-server: bad value '%s' for %s\n", v, a.c_str());
      return std::nullopt;
    }
  }
  return c;
}

}  // namespace sph::server
