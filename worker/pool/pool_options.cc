#include "worker/pool/pool_options.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace sph::worker::pool {
namespace {

constexpr const char* kUsage = R"(usage: mpirun -np N sph-worker --server HOST:PORT [options]

  --server HOST:PORT          sph-server to pull jobs from
  --token-file FILE           access token (when the server has --token-file)
  --pool-name NAME            name shown in job attempts (default host:pid)
  --max-jobs N                exit after N jobs (default: no limit)
  --idle-exit SECONDS         exit after this long without a job (default: never)
  --checkpoint-interval SECONDS
                              write a checkpoint this often (wall clock, default 300; the
                              case's output.checkpoint_wall_interval applies too)
  --stall-timeout SECONDS     stop renewing the lease when the solver has made no step for
                              this long, so the job moves to another pool (default 900)
  --verbose                   print the solver's progress lines

SIGTERM, SIGINT or SIGUSR1: the running job writes a checkpoint and goes back to the queue,
then the pool exits.
)";

bool number(const char* text, double& out) {
  char* end = nullptr;
  out = std::strtod(text, &end);
  return end != text && *end == '\0' && out >= 0;
}

}  // namespace

std::optional<PoolOptions> parse_pool_options(int argc, char** argv, int rank) {
  PoolOptions o;
  auto fail = [&](const std::string& problem) -> std::optional<PoolOptions> {
    if (rank == 0) std::fprintf(stderr, "sph-worker: %s\n%s", problem.c_str(), kUsage);
    return std::nullopt;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--verbose") {
      o.verbose = true;
      continue;
    }
    if (a == "--help" || a == "-h") return fail("pool mode");
    if (i + 1 >= argc) return fail(a + " needs a value");
    const char* v = argv[++i];
    double x = 0;
    if (a == "--server")
      o.server = v;
    else if (a == "--token-file")
      o.token_file = v;
    else if (a == "--pool-name")
      o.pool_name = v;
    else if (a == "--max-jobs" && number(v, x))
      o.max_jobs = static_cast<int>(x);
    else if (a == "--idle-exit" && number(v, x))
      o.idle_exit_seconds = x;
    else if (a == "--checkpoint-interval" && number(v, x))
      o.checkpoint_interval_seconds = x;
    else if (a == "--stall-timeout" && number(v, x))
      o.stall_timeout_seconds = x;
    else
      return fail("bad option or value: " + a + " " + v);
  }
  if (o.server.empty()) return fail("--server is required");
  return o;
}

}  // namespace sph::worker::pool
