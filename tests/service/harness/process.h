#pragma once
// Child processes for the service tests: real servers, pools and sphctl runs, started with
// posix_spawn (gRPC and fork() do not mix) in their own session so that a whole pool (mpirun
// and its ranks) can be killed at once.
#include <sys/types.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sph::testing {

class Process {
 public:
  // Starts argv[0] (a path) with stdout and stderr appended to log_path; `env` entries are
  // added to (or replace) the test's environment.
  static Process spawn(const std::vector<std::string>& argv, const std::string& log_path,
                       const std::map<std::string, std::string>& env = {});

  Process() = default;
  Process(Process&& other) noexcept;
  Process& operator=(Process&& other) noexcept;
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  // Kills the whole session with SIGKILL if it still runs.
  ~Process();

  pid_t pid() const { return pid_; }
  bool running();
  // The exit code (128 + signal for a killed process), or nullopt once the (scaled) timeout
  // passes.
  std::optional<int> wait(std::chrono::milliseconds timeout);
  void signal(int sig);
  // Sends `sig` to every process in the child's session (mpirun and all its ranks).
  void signal_session(int sig);
  // SIGKILL to the session, then reaps the child.
  void kill_all();
  const std::string& log_path() const { return log_path_; }

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
  std::string log_path_;
};

struct CommandResult {
  int exit_code = -1;  // -1: timed out (killed)
  std::string out;     // stdout
  std::string err;     // stderr
};

// Runs a command to completion (killed once the scaled timeout passes) and captures its output.
CommandResult run_command(const std::vector<std::string>& argv, const std::string& work_dir,
                          std::chrono::milliseconds timeout,
                          const std::map<std::string, std::string>& env = {});

std::string read_file(const std::string& path);

// A time limit of the harness as this build needs it: sanitized builds run several times
// slower, so every wait here (eventually, run_command, Process::wait) is SPHD_TEST_TIME_SCALE
// times what a test states (top-level CMakeLists.txt).
inline std::chrono::milliseconds scaled(std::chrono::milliseconds timeout) {
  return timeout * SPHD_TEST_TIME_SCALE;
}

// Polls `done` every 50 ms until it returns true or the (scaled) timeout passes.
template <typename Predicate>
bool eventually(std::chrono::milliseconds timeout, Predicate done) {
  const auto until = std::chrono::steady_clock::now() + scaled(timeout);
  while (true) {
    if (done()) return true;
    if (std::chrono::steady_clock::now() >= until) return false;
    struct timespec ts = {0, 50'000'000};
    nanosleep(&ts, nullptr);
  }
}

}  // namespace sph::testing
