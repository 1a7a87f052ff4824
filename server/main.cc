// sph-server: the job service. Clients submit cases (JobService), worker pools pull and run
// them (WorkerService); jobs, attempts and events live in SQLite. See docs/service.md.
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server.h>
#include <grpcpp/server_builder.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "server/api/auth.h"
#include "server/api/job_service.h"
#include "server/api/worker_service.h"
#include "server/clock.h"
#include "server/common/auth_token.h"
#include "server/common/log.h"
#include "server/common/message_limits.h"
#include "server/config.h"
#include "server/events/event_feed.h"
#include "server/lease_reaper.h"
#include "server/results/result_layout.h"
#include "server/results/results_owner.h"
#include "server/store/database_lock.h"
#include "server/store/job_store.h"

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
  std::string token;
  if (!config.token_file.empty()) token = sph::service::read_token_file(config.token_file);
  if (token.empty() && !is_loopback(config.address))
    sph::service::log_line(
        "WARNING: listening on %s without --token-file: anyone who can reach it can "
        "submit and cancel jobs",
        config.address.c_str());

  std::filesystem::create_directories(config.results_dir);
  const ResultLayout layout(config.results_dir);
  const store::DatabaseLock db_lock(config.db_path);
  EventFeed feed;
  const auto lease_ms = static_cast<std::int64_t>(config.lease_seconds * 1000);
  store::JobStore store(config.db_path, layout,
                        store::StoreOptions{lease_ms, config.max_lost_leases}, feed);
  claim_results_directory(layout, store.database_id(), store.has_jobs());
  // Pools could not report while the server was down; they get a full lease to reconnect.
  store.renew_all_leases(now_unix_ms());

  const api::TokenCheck auth(token);
  api::JobServiceImpl jobs(store, feed, layout, auth, api::JobServiceLimits{config.max_particles});
  api::WorkerServiceImpl workers(store, feed, layout, auth);

  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(config.address, grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&jobs);
  builder.RegisterService(&workers);
  builder.SetMaxReceiveMessageSize(sph::service::kMaxMessageBytes);  // inlined point sets
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    sph::service::log_line("cannot listen on %s", config.address.c_str());
    return 1;
  }
  const std::string bound =
      config.address.substr(0, config.address.rfind(':') + 1) + std::to_string(port);
  LeaseReaper reaper(store,
                     std::chrono::milliseconds(std::clamp<std::int64_t>(lease_ms / 4, 50, 1000)));
  if (!config.address_file.empty()) write_address_file(config.address_file, bound);
  sph::service::log_line("listening on %s (database %s, results %s, lease %g s%s)", bound.c_str(),
                         config.db_path.c_str(), layout.root().c_str(), config.lease_seconds,
                         auth.enabled() ? ", token required" : "");

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
    server->GetHealthCheckService()->SetServingStatus(false);
    // Open streams and long polls see this and end at once; then no call outlives the grace.
    feed.shutdown();
    server->Shutdown(
        std::chrono::system_clock::now() +
        std::chrono::milliseconds(static_cast<std::int64_t>(config.shutdown_grace_seconds * 1000)));
  });
  server->Wait();
  signals.join();
  reaper.stop();
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
