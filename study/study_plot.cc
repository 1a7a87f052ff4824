#include "study/study_plot.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "plot_study_script.h"

extern char** environ;

namespace sph::study {

std::string default_python() {
  const char* env = std::getenv("SPHD_PYTHON");
  return env != nullptr && *env != '\0' ? env : "/usr/bin/python3";
}

std::string plot_study(const std::string& python, const std::string& csv_path,
                       const std::string& png_path, double timeout_seconds) {
  // The interpreter's output goes to a log next to the plot, for the reason of a failure.
  const std::string log_path = png_path + ".log";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> args = {python, "-c", kPlotStudyScript, csv_path, png_path};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // A headless backend whatever the caller's environment says.
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "MPLBACKEND=", 11) != 0) env_strings.emplace_back(*e);
  env_strings.emplace_back("MPLBACKEND=Agg");
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);

  pid_t pid = 0;
  const int rc = posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return "cannot start " + python + ": " + std::strerror(rc);

  const auto give_up = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(timeout_seconds));
  int status = 0;
  while (true) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0) return std::string("waiting for the plot: ") + std::strerror(errno);
    if (std::chrono::steady_clock::now() >= give_up) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return "the plot took longer than " + std::to_string(static_cast<int>(timeout_seconds)) +
             " s";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    std::remove(log_path.c_str());
    return "";
  }
  std::ifstream log(log_path);
  std::stringstream ss;
  ss << log.rdbuf();
  std::string text = ss.str();
  // The last line is the interesting one (e.g. "ModuleNotFoundError: No module named ...").
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const auto nl = text.rfind('\n');
  return python + " failed to plot (" + (nl == std::string::npos ? text : text.substr(nl + 1)) +
         "; full output in " + log_path + ")";
}

}  // namespace sph::study
