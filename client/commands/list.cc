// sphctl list [--state S]... [--limit N]
#include <cstdio>
#include <cstdlib>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/job_state.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {

int cmd_list(const GlobalOptions& g, ArgScanner args) {
  constexpr const char* kUsageText =
      "usage: sphctl list [--state STATE]... [--limit N (default 50, 0 = all)]";
  v1::ListJobsRequest req;
  std::string value;
  while (args.take_value("--state", value)) {
    const auto s = service::parse_state(value);
    if (!s) {
      std::fprintf(stderr,
                   "sphctl: unknown state '%s' (QUEUED, RUNNING, SUCCEEDED, FAILED, "
                   "CANCELLED)\n",
                   value.c_str());
      return kUsage;
    }
    req.add_states(*s);
  }
  long limit = 50;
  if (args.take_value("--limit", value)) {
    char* end = nullptr;
    limit = std::strtol(value.c_str(), &end, 10);
    if (end == value.c_str() || *end != '\0' || limit < 0) {
      std::fprintf(stderr, "sphctl: --limit needs a number >= 0\n%s\n", kUsageText);
      return kUsage;
    }
  }
  std::vector<std::string> pos;
  if (!expect_positionals(args, 0, kUsageText, pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;

  v1::ListJobsResponse all;
  while (true) {
    if (limit > 0)
      req.set_page_size(static_cast<int>(std::min<long>(limit - all.jobs_size(), 1000)));
    v1::ListJobsResponse page;
    const auto status = conn->jobs().ListJobs(conn->unary_context().get(), req, &page);
    if (!status.ok()) return report_error(status, "list", conn->address());
    for (auto& j : *page.mutable_jobs()) *all.add_jobs() = std::move(j);
    all.set_next_page_token(page.next_page_token());
    if (page.next_page_token().empty() || (limit > 0 && all.jobs_size() >= limit)) break;
    req.set_page_token(page.next_page_token());
  }
  if (g.json) {
    std::printf("%s\n", to_json(all).c_str());
    return kOk;
  }
  std::printf("%s\n", job_table_header().c_str());
  for (const auto& j : all.jobs()) std::printf("%s\n", job_table_row(j).c_str());
  if (!all.next_page_token().empty()) std::printf("(more jobs: --limit 0 lists all)\n");
  return kOk;
}

}  // namespace sph::ctl
