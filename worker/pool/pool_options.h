#pragma once
// Command line of pool mode: `mpirun -np N sph-worker --server ADDR [options]`.
#include <optional>
#include <string>

namespace sph::worker::pool {

struct PoolOptions {
  std::string server;            // --server HOST:PORT
  std::string token_file;        // --token-file FILE
  std::string pool_name;         // --pool-name NAME (default host:pid)
  int max_jobs = 0;              // --max-jobs N: exit after N jobs (0 = no limit)
  double idle_exit_seconds = 0;  // --idle-exit S: exit after S seconds without work (0 = never)
  double checkpoint_interval_seconds = 300;  // --checkpoint-interval S (0 = only on SIGTERM)
  double stall_timeout_seconds = 900;        // --stall-timeout S (0 = never give up on a hung run)
  bool verbose = false;                      // --verbose: the solver's own progress lines on stdout
};

// Parses argv on every rank (mpirun gives all ranks the same arguments). Prints the problem
// on rank 0 and returns nullopt on a bad command line.
std::optional<PoolOptions> parse_pool_options(int argc, char** argv, int rank);

}  // namespace sph::worker::pool
