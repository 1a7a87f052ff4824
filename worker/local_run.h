#pragma once
// `sph-worker --case FILE --out DIR`: run a case with no server, under mpirun or not.

namespace sph::worker {

// Exit codes shared by local and pool mode (documented in README.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitError = 1,        // I/O failure, bad arguments
  kExitInvalidCase = 2,  // the case failed validation
  kExitUnstable = 3,     // a stability guard stopped the run
  kExitInterrupted = 4,  // SIGTERM/SIGINT: checkpoint written, run incomplete
};

// Parses the local-mode arguments from argv (after MPI_Init) and runs the case.
int run_local(int argc, char** argv);

}  // namespace sph::worker
