// sph-server: the job service. Clients submit cases (JobService), worker pools pull and run
// them (WorkerService); jobs, attempts and events live in SQLite. See docs/service.md.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/log.h"
#include "server/config.h"
#include "server/service_host.h"

namespace {

using namespace sph::server;

void write_address_file(const std::string& path, const std::string& address) {
  // Written to a temporary name and renamed, so a reader never sees half an address.
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << address << "\n";
  }
  std::filesystem::rename(tmp, path);
}

bool is_loopback(const std::string& address) {
  return address.rfind("127.", 0) == 0 || address.rfind("localhost:", 0) == 0 ||
         address.rfind("[::1]:", 0) == 0 || address.rfind("unix:", 0) == 0;
}

int run(const ServerConfig& config) {
  if (config.token_file.empty() && !is_loopback(config.address))
    sph::service::log_line(
        "WARNING: listening on %s without --token-file: anyone who can reach it can "
        "submit and cancel jobs",
        config.address.c_str());
  ServiceHost host(config);
  if (!config.address_file.empty()) write_address_file(config.address_file, host.bound_address());
  if (!config.metrics_address_file.empty() && !host.metrics_address().empty())
    write_address_file(config.metrics_address_file, host.metrics_address());
  if (!host.metrics_address().empty())
    sph::service::log_line("metrics on http://%s/metrics", host.metrics_address().c_str());
  sph::service::log_line("listening on %s (database %s, results %s, lease %g s%s)",
                         host.bound_address().c_str(), config.db_path.c_str(),
                         host.layout().root().c_str(), config.lease_seconds,
                         host.token_required() ? ", token required" : "");

  // SIGTERM/SIGINT were blocked before any thread started; this thread takes them.
  std::thread signals([&] {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGINT);
    int sig = 0;
    sigwait(&set, &sig);
    sph::service::log_line("%s: shutting down (grace %g s)", sig == SIGTERM ? "SIGTERM" : "SIGINT",
                           config.shutdown_grace_seconds);
    host.shutdown(
        std::chrono::milliseconds(static_cast<std::int64_t>(config.shutdown_grace_seconds * 1000)));
  });
  host.wait();
  signals.join();
  sph::service::log_line("stopped");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sph::service::set_log_name("sph-server");
  int exit_code = 0;
  const auto config = parse_server_args(argc, argv, exit_code);
  if (!config) return exit_code;
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  try {
    return run(*config);
  } catch (const std::exception& e) {
    sph::service::log_line("fatal: %s", e.what());
    return 1;
  }
}
