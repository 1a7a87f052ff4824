#pragma once
// sphctl's subcommands. Each returns the process exit code (cli/exit_codes.h).
#include <cstdint>
#include <string>

#include "cli/connection.h"
#include "cli/options.h"
#include "sph/v1/case.pb.h"
#include "sph/v1/study.pb.h"

namespace sph::ctl {

int cmd_submit(const GlobalOptions& g, ArgScanner args);
int cmd_status(const GlobalOptions& g, ArgScanner args);
int cmd_list(const GlobalOptions& g, ArgScanner args);
int cmd_watch(const GlobalOptions& g, ArgScanner args);
int cmd_cancel(const GlobalOptions& g, ArgScanner args);
int cmd_delete(const GlobalOptions& g, ArgScanner args);
int cmd_fetch(const GlobalOptions& g, ArgScanner args);
int cmd_health(const GlobalOptions& g, ArgScanner args);
int cmd_study(const GlobalOptions& g, ArgScanner args);
int cmd_logs(const GlobalOptions& g, ArgScanner args);

// Loads a case file (inlining point and reference data files) and validates it, printing the
// problems. Returns kOk or kInvalidCase.
int load_and_validate(const std::string& path, v1::Case& c);

// Submits the case (a convergence study when `study` is given) and, with `watch`, follows
// it. Returns the exit code.
int submit_job(const GlobalOptions& g, const v1::Case& c, const std::string& path,
               const v1::StudySpec* study, bool watch, const std::string& request_id);

// Follows a job's events until it ends, reconnecting (and resuming from the last event seen)
// while the server is away. Returns the exit code for the job's final state.
int watch_job(Connection& conn, const GlobalOptions& g, const std::string& job_id,
              std::int64_t after_sequence);

// Parses the positionals of a command that takes exactly `count` of them; prints usage
// problems. Returns false on a problem.
bool expect_positionals(ArgScanner& args, size_t count, const char* usage,
                        std::vector<std::string>& out);

}  // namespace sph::ctl
