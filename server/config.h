#pragma once
// sph-server's command line.
#include <optional>
#include <string>

namespace sph::server {

struct ServerConfig {
  std::string address = "127.0.0.1:7070";
  std::string address_file;  // written with the bound address (useful with port 0)
  std::string db_path = "sphd.db";
  std::string results_dir = "results";
  double lease_seconds = 30;
  std::string token_file;
  double max_particles = 2e7;
  int max_lost_leases = 5;
  double shutdown_grace_seconds = 5;
};

// Parses argv; on --help or an error prints to stderr/stdout and returns nullopt with
// exit_code set (0 for --help, 2 for a usage error).
std::optional<ServerConfig> parse_server_args(int argc, char** argv, int& exit_code);

}  // namespace sph::server
