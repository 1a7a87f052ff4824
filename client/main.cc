// sphctl: the command-line client of sph-server. See `sphctl help` and docs/service.md.
#include <cstdio>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "cli/options.h"
#include "commands/commands.h"

namespace sph::ctl {

constexpr const char* kHelp =
    R"(usage: sphctl [--server HOST:PORT] [--token-file FILE] [--json] [--timeout S] COMMAND ...

commands:
  submit CASE [--watch] [--dry-run] [--request-id ID]
                         validate a case locally and submit it (--dry-run: print particle
                         counts, time steps and memory, submit nothing)
  study CASE (--refine N [--ratio R] | --dx A,B,C) [--watch] [--dry-run] [--request-id ID]
                         a convergence study: the case at a ladder of resolutions, each
                         measured against the case's reference; the result holds study.csv,
                         study.md, study.png and every level's result (docs/accuracy.md)
  status JOB [--case]    state, progress, checkpoint, result files and attempts of a job
  list [--state S]... [--limit N]
                         jobs, newest first (states: QUEUED RUNNING SUCCEEDED FAILED CANCELLED)
  watch JOB [--from SEQ] follow a job until it ends (a progress bar on a terminal)
  logs JOB [--attempt N] [--follow]
                         the worker pool's log lines for the job (progress, warnings, the
                         guard's diagnosis); --follow streams them until the job ends
  cancel JOB [--reason TEXT]
                         cancel a job (idempotent); a running job keeps its partial output
  fetch JOB [-o DIR] [--file NAME]
                         download the result files (default into ./JOB) and verify sha256
  delete JOB             free a finished job's disk on the server (every attempt's results
                         and checkpoints); its record and history stay
  health                 the server's health status

options (anywhere on the line):
  --server HOST:PORT     server address (default $SPHCTL_SERVER, else 127.0.0.1:7070)
  --token-file FILE      file with the access token (default $SPHCTL_TOKEN_FILE)
  --json                 machine-readable output (watch: one JSON event per line)
  --timeout SECONDS      deadline for each call (default 30)

exit codes: 0 ok, 1 error, 2 usage, 3 invalid case, 4 not found, 5 server unavailable,
  6 authentication, 7 verification/IO failure, 8 conflict or no result yet,
  10 job FAILED, 11 job CANCELLED (watch, submit --watch, logs --follow)
)";

bool expect_positionals(ArgScanner& args, size_t count, const char* usage,
                        std::vector<std::string>& out) {
  std::string error;
  if (!args.positionals(out, error)) {
    std::fprintf(stderr, "sphctl: %s\n%s\n", error.c_str(), usage);
    return false;
  }
  if (out.size() != count) {
    std::fprintf(stderr, "%s\n", usage);
    return false;
  }
  return true;
}

int run(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const auto g = take_global_options(args);
  if (!g) return kUsage;
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kHelp, args.empty() ? stderr : stdout);
    return args.empty() ? kUsage : kOk;
  }
  const std::string command = args[0];
  ArgScanner rest(std::vector<std::string>(args.begin() + 1, args.end()));
  if (command == "submit") return cmd_submit(*g, std::move(rest));
  if (command == "study") return cmd_study(*g, std::move(rest));
  if (command == "status") return cmd_status(*g, std::move(rest));
  if (command == "list") return cmd_list(*g, std::move(rest));
  if (command == "watch") return cmd_watch(*g, std::move(rest));
  if (command == "logs") return cmd_logs(*g, std::move(rest));
  if (command == "cancel") return cmd_cancel(*g, std::move(rest));
  if (command == "fetch") return cmd_fetch(*g, std::move(rest));
  if (command == "delete") return cmd_delete(*g, std::move(rest));
  if (command == "health") return cmd_health(*g, std::move(rest));
  std::fprintf(stderr, "sphctl: unknown command '%s'\n%s", command.c_str(), kHelp);
  return kUsage;
}

}  // namespace sph::ctl

int main(int argc, char** argv) {
  return sph::ctl::run(argc, argv);
}
