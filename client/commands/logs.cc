// sphctl logs JOB [--attempt N] [--follow]
// The worker pool's log lines for a job, kept by the server per attempt (progress lines,
// the server going away and back, a cancel, a stability guard's diagnosis).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/job_state.h"
#include "common/time_text.h"
#include "render/json.h"

namespace sph::ctl {
namespace {

constexpr const char* kUsageText = "usage: sphctl logs JOB [--attempt N] [--follow]";
// As watch: while the server is away keep trying this long, and poll a running job this often.
constexpr auto kReconnectFor = std::chrono::seconds(120);
constexpr auto kPollEvery = std::chrono::milliseconds(500);

void print_line(const GlobalOptions& g, const v1::LogLine& l) {
  if (g.json) {
    std::printf("%s\n", to_json(l).c_str());
  } else {
    std::printf("%s.%03d [attempt %d] %s\n",
                service::format_unix_seconds(l.time_unix_ms() / 1000).c_str(),
                static_cast<int>(l.time_unix_ms() % 1000), l.attempt(), l.text().c_str());
  }
}

}  // namespace

int cmd_logs(const GlobalOptions& g, ArgScanner args) {
  const bool follow = args.take_flag("--follow") || args.take_flag("-f");
  std::string attempt_text = "0";
  args.take_value("--attempt", attempt_text);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, kUsageText, pos)) return kUsage;
  char* end = nullptr;
  const long attempt = std::strtol(attempt_text.c_str(), &end, 10);
  if (end == attempt_text.c_str() || *end != '\0' || attempt < 0 || attempt > 1000000) {
    std::fprintf(stderr, "sphctl: --attempt needs an attempt number >= 1 (0: all)\n%s\n",
                 kUsageText);
    return kUsage;
  }
  auto conn = Connection::open(g);
  if (!conn) return kUsage;

  v1::GetJobLogsRequest req;
  req.set_job_id(pos[0]);
  req.set_attempt(static_cast<int>(attempt));
  bool dropped_said = false;
  bool in_outage = false;
  auto outage_since = std::chrono::steady_clock::now();
  while (true) {
    v1::GetJobLogsResponse resp;
    const auto status = conn->jobs().GetJobLogs(conn->unary_context().get(), req, &resp);
    if (!status.ok()) {
      if (!follow || !is_transient(status))
        return report_error(status, "logs " + pos[0], conn->address());
      const auto now = std::chrono::steady_clock::now();
      if (!in_outage) {
        in_outage = true;
        outage_since = now;
        if (!g.json)
          std::fprintf(stderr, "sphctl: lost the server (%s); reconnecting...\n",
                       status.error_message().c_str());
      } else if (now - outage_since > kReconnectFor) {
        return report_error(status, "logs " + pos[0], conn->address());
      }
      std::this_thread::sleep_for(std::chrono::seconds(1));
      continue;
    }
    in_outage = false;
    if (resp.dropped_lines() > 0 && !dropped_said && !g.json) {
      std::fprintf(stderr,
                   "sphctl: the server kept the newest 256 KiB of each attempt's log; %lld "
                   "older lines were dropped\n",
                   static_cast<long long>(resp.dropped_lines()));
      dropped_said = true;
    }
    for (const auto& l : resp.lines()) {
      print_line(g, l);
      req.set_after_sequence(l.sequence());
    }
    std::fflush(stdout);
    if (resp.lines_size() > 0) continue;  // there may be more at once
    // Everything so far is printed. A finished job's log is complete (the Finish carried its
    // last lines, in the same transaction as the final state).
    if (!follow) return kOk;
    if (service::is_terminal(resp.state())) return exit_code_for_state(resp.state());
    std::this_thread::sleep_for(kPollEvery);
  }
}

}  // namespace sph::ctl
