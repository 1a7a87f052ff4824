// sphctl status JOB [--case]
#include <cstdio>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {

int cmd_status(const GlobalOptions& g, ArgScanner args) {
  const bool with_case = args.take_flag("--case");
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, "usage: sphctl status JOB [--case]", pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  v1::GetJobRequest req;
  req.set_job_id(pos[0]);
  req.set_include_case(with_case);
  v1::Job job;
  const auto status = conn->jobs().GetJob(conn->unary_context().get(), req, &job);
  if (!status.ok()) return report_error(status, "status " + pos[0], conn->address());
  if (g.json) {
    std::printf("%s\n", to_json(job).c_str());
  } else {
    std::fputs(describe_job(job).c_str(), stdout);
    if (with_case) std::printf("  case:\n%s", job.case_text().c_str());
  }
  return kOk;
}

}  // namespace sph::ctl
