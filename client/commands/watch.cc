// sphctl watch JOB [--from SEQUENCE]
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/job_state.h"
#include "render/job_text.h"
#include "render/json.h"
#include "render/progress_bar.h"

namespace sph::ctl {
namespace {

constexpr const char* kUsageText = "usage: sphctl watch JOB [--from SEQUENCE]";
// While the server is away (restart, network), keep trying this long before giving up.
constexpr auto kReconnectFor = std::chrono::seconds(120);

}  // namespace

int watch_job(Connection& conn, const GlobalOptions& g, const std::string& job_id,
              std::int64_t after_sequence) {
  const bool live = !g.json && isatty(fileno(stdout));
  std::optional<ProgressBar> bar;
  if (live) bar.emplace(stdout, job_id);
  std::int64_t last = after_sequence;
  std::optional<v1::JobState> final_state;
  auto outage_started = std::chrono::steady_clock::now();
  bool in_outage = false;
  auto pause = std::chrono::milliseconds(200);
  while (true) {
    auto ctx = conn.context(0);
    v1::WatchJobRequest req;
    req.set_job_id(job_id);
    req.set_after_sequence(last);
    auto reader = conn.jobs().WatchJob(ctx.get(), req);
    v1::JobEvent e;
    while (reader->Read(&e)) {
      in_outage = false;
      pause = std::chrono::milliseconds(200);
      last = e.sequence();
      if (e.has_state_change() && service::is_terminal(e.state_change().state()))
        final_state = e.state_change().state();
      if (g.json) {
        std::printf("%s\n", to_json(e).c_str());
        std::fflush(stdout);
      } else if (live && e.has_progress()) {
        bar->update(e.progress());
      } else if (live) {
        bar->message(event_line(e));
      } else {
        std::printf("%s\n", event_line(e).c_str());
        std::fflush(stdout);
      }
    }
    const grpc::Status status = reader->Finish();
    if (status.ok()) break;
    if (!is_transient(status)) {
      if (bar) bar->finish();
      return report_error(status, "watch " + job_id, conn.address());
    }
    // The server went away (restart, shutdown): resume from the last event seen.
    const auto now = std::chrono::steady_clock::now();
    if (!in_outage) {
      in_outage = true;
      outage_started = now;
      if (!g.json)
        std::fprintf(stderr, "sphctl: lost the server (%s); reconnecting...\n",
                     status.error_message().c_str());
    } else if (now - outage_started > kReconnectFor) {
      if (bar) bar->finish();
      return report_error(status, "watch " + job_id, conn.address());
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(2000));
  }
  if (bar) bar->finish();
  if (!final_state) {
    // The stream ended without a terminal event in what we asked for (resumed past it).
    v1::GetJobRequest req;
    req.set_job_id(job_id);
    v1::Job job;
    const auto status = conn.jobs().GetJob(conn.unary_context().get(), req, &job);
    if (!status.ok()) return report_error(status, "watch " + job_id, conn.address());
    final_state = job.state();
  }
  return exit_code_for_state(*final_state);
}

int cmd_watch(const GlobalOptions& g, ArgScanner args) {
  std::string from = "0";
  args.take_value("--from", from);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, kUsageText, pos)) return kUsage;
  char* end = nullptr;
  const long long after = std::strtoll(from.c_str(), &end, 10);
  if (end == from.c_str() || *end != '\0' || after < 0) {
    std::fprintf(stderr, "sphctl: --from needs an event sequence number >= 0\n%s\n", kUsageText);
    return kUsage;
  }
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  return watch_job(*conn, g, pos[0], after);
}

}  // namespace sph::ctl
