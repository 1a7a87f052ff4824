#pragma once
// `sph-worker --case FILE --out DIR --study-refine N` (or --study-dx a,b,c): a convergence
// study with no server, under mpirun or not. Running it again into the same directory skips
// the levels that are over and continues an interrupted one from its checkpoint.
#include <atomic>
#include <string>

#include "sph/v1/case.pb.h"
#include "sph/v1/study.pb.h"

namespace sph::worker {

// Collective. `c` is a valid case; returns the process exit code (worker/local_run.h).
int run_local_study(const v1::Case& c, const v1::StudySpec& spec, const std::string& out_dir,
                    bool quiet, const std::atomic<bool>* interrupt);

}  // namespace sph::worker
