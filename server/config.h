#pragma once
// sph-server's command line.
#include <optional>
#include <string>

namespace sph::server {

struct ServerConfig {
  std::string address = "127.0.0.1:7070";
  std::string address_file;          // written with the bound address (useful with port 0)
  std::string metrics_address;       // empty: no metrics endpoint (server/metrics/)
  std::string metrics_address_file;  // written with the metrics endpoint's bound address
  std::string db_path = "sphd.db";
  std::string results_dir = "results";
  double lease_seconds = 30;
  std::string token_file;
  // Per job: cases estimated above these are refused at submit (0 = no limit).
  double max_particles = 2e7;
  double max_memory_gib = 64;
  // Per queue: what all unfinished (queued or running) jobs may add up to before a submit is
  // refused with RESOURCE_EXHAUSTED (0 = no limit).
  double max_queued_jobs = 10000;
  double max_queued_particles = 1e9;
  // Open WatchJob and FetchResult streams one client (peer host and token) may hold.
  int max_streams_per_client = 256;
  int max_lost_leases = 5;
  double shutdown_grace_seconds = 5;
};

// Parses argv; on --help or an error prints to stderr/stdout and returns nullopt with
// exit_code set (0 for --help, 2 for a usage error).
std::optional<ServerConfig> parse_server_args(int argc, char** argv, int& exit_code);

}  // namespace sph::server
