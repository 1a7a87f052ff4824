#pragma once
// A real sph-server (and real worker pools, and sphctl) on loopback with an ephemeral port and
// a temporary directory, for one test. Logs stay in the directory, which is kept when the test
// fails.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <grpcpp/client_context.h>

#include "harness/process.h"
#include "sph/v1/service.grpc.pb.h"

namespace sph::testing {

using namespace std::chrono_literals;

struct ServerSettings {
  double lease_seconds = 3;
  std::string token;                    // non-empty: written to a file and passed as --token-file
  double max_particles = -1;            // < 0: the server's default
  double shutdown_grace = -1;           // < 0: the server's default
  std::vector<std::string> extra_args;  // more sph-server flags

  ServerSettings& lease(double seconds) {
    lease_seconds = seconds;
    return *this;
  }
  ServerSettings& with_token(std::string t) {
    token = std::move(t);
    return *this;
  }
  ServerSettings& grace(double seconds) {
    shutdown_grace = seconds;
    return *this;
  }
  ServerSettings& particle_limit(double n) {
    max_particles = n;
    return *this;
  }
  ServerSettings& flag(const std::string& name, const std::string& value) {
    extra_args.insert(extra_args.end(), {name, value});
    return *this;
  }
};

class ServiceHarness {
 public:
  ServiceHarness();
  ~ServiceHarness();
  ServiceHarness(const ServiceHarness&) = delete;
  ServiceHarness& operator=(const ServiceHarness&) = delete;

  // Starts the server and waits until it listens; later starts reuse the first address, the
  // database and the results directory (a restart).
  void start_server(const ServerSettings& settings = {});
  Process& server() { return server_; }

  // `mpirun -np RANKS sph-worker --server ADDR ...` in its own session.
  Process start_pool(int ranks, const std::vector<std::string>& extra_args,
                     const std::string& log_name = "pool");
  // The local-mode solver run of a case (for reference results).
  int run_local(int ranks, const std::string& case_path, const std::string& out_dir);

  // sphctl with --server (and the token file when the server has one) added.
  CommandResult sphctl(const std::vector<std::string>& args,
                       std::chrono::milliseconds timeout = 60s);

  v1::JobService::Stub& jobs() { return *jobs_; }
  v1::WorkerService::Stub& workers() { return *workers_; }
  // A call context with the token and a deadline.
  std::unique_ptr<grpc::ClientContext> context(std::chrono::milliseconds timeout = 10s) const;

  // Claims the next job as a fake pool (claim_next_job with this server and context(20s)).
  v1::ClaimResponse claim(const std::string& pool = "test-pool", int ranks = 2);

  v1::Job get_job(const std::string& id);
  // Polls until the job is in `state`; false on timeout.
  bool wait_for_state(const std::string& id, v1::JobState state, std::chrono::milliseconds timeout);
  // Polls until `pred(job)` holds; false on timeout.
  template <typename Pred>
  bool wait_for_job(const std::string& id, std::chrono::milliseconds timeout, Pred pred) {
    return eventually(timeout, [&] {
      try {
        return pred(get_job(id));
      } catch (const std::exception&) {
        return false;  // server restarting
      }
    });
  }
  // Every event of a finished job (WatchJob from the start).
  std::vector<v1::JobEvent> history(const std::string& id);

  // Submits the case text; fails the test on an error.
  v1::Job submit_text(const std::string& case_text, const std::string& request_id = "");

  const std::string& dir() const { return dir_; }
  const std::string& address() const { return address_; }
  const std::string& token_file() const { return token_file_; }
  // Server and pool logs, for failure messages.
  std::string logs() const;

 private:
  void connect();
  std::string dir_;
  std::string address_;
  std::string token_file_;
  std::string token_;
  ServerSettings settings_;
  Process server_;
  int server_starts_ = 0;
  std::vector<std::string> log_files_;
  std::unique_ptr<v1::JobService::Stub> jobs_;
  std::unique_ptr<v1::WorkerService::Stub> workers_;
};

// Claims the next job as a fake pool `pool` of `ranks` ranks, waiting up to 5 s for one; a
// failed call fails the test and returns an empty response (no job).
v1::ClaimResponse claim_next_job(v1::WorkerService::Stub& workers, grpc::ClientContext& context,
                                 const std::string& pool, int ranks);

// Test inputs.
std::string test_case_path(const std::string& name);  // tests/service/cases/NAME
std::string read_test_case(const std::string& name);
// The case text with time.end_time replaced.
std::string with_end_time(const std::string& case_text, double end_time);
// Runs tests/service/h5check.py; returns its exit code, output in `out`.
int h5check(const std::vector<std::string>& args, const std::string& work_dir, std::string& out);

}  // namespace sph::testing
