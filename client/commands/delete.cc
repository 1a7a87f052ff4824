// sphctl delete JOB
#include <algorithm>
#include <cstdio>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {

int cmd_delete(const GlobalOptions& g, ArgScanner args) {
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, "usage: sphctl delete JOB", pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  v1::DeleteJobFilesRequest req;
  req.set_job_id(pos[0]);
  v1::DeleteJobFilesResponse resp;
  // Removing a large job's files on a network filesystem can take minutes: the deadline is
  // at least 10 minutes.
  const auto status = conn->jobs().DeleteJobFiles(
      conn->context(std::max(g.timeout_seconds, 600.0)).get(), req, &resp);
  if (!status.ok()) return report_error(status, "delete " + pos[0], conn->address());
  const v1::Job& job = resp.job();
  if (g.json) {
    std::printf("%s\n", to_json(resp).c_str());
  } else if (resp.deleted_now()) {
    const int n = job.attempts_size();
    std::printf(
        "%s: deleted its files (%s, %d attempt%s); its record and history stay (sphctl status "
        "%s)\n",
        job.id().c_str(), format_bytes(static_cast<double>(job.files_deleted_bytes())).c_str(), n,
        n == 1 ? "" : "s", job.id().c_str());
  } else {
    std::printf("%s: its files were deleted on %s; nothing of them is left\n", job.id().c_str(),
                format_time_ms(job.files_deleted_unix_ms()).c_str());
  }
  return kOk;
}

}  // namespace sph::ctl
