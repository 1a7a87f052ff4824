// sphctl cancel JOB [--reason TEXT]
#include <cstdio>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/job_state.h"
#include "render/json.h"

namespace sph::ctl {

int cmd_cancel(const GlobalOptions& g, ArgScanner args) {
  v1::CancelJobRequest req;
  std::string reason;
  if (args.take_value("--reason", reason)) req.set_reason(reason);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, "usage: sphctl cancel JOB [--reason TEXT]", pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  req.set_job_id(pos[0]);
  v1::Job job;
  const auto status = conn->jobs().CancelJob(conn->unary_context().get(), req, &job);
  if (!status.ok()) return report_error(status, "cancel " + pos[0], conn->address());
  if (g.json) {
    std::printf("%s\n", to_json(job).c_str());
  } else if (job.state() == v1::JOB_STATE_RUNNING) {
    std::printf(
        "%s: cancel requested; it stops at its next step boundary and keeps its partial "
        "output (sphctl watch %s)\n",
        job.id().c_str(), job.id().c_str());
  } else {
    std::printf("%s: %s (%s)\n", job.id().c_str(), service::state_name(job.state()),
                job.reason().c_str());
  }
  return kOk;
}

}  // namespace sph::ctl
