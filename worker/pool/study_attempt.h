#pragma once
// A pool's run of a claimed study job: the ladder of the claim's StudySpec in the attempt's
// output directory, with progress reported across the whole ladder, finished levels of
// earlier attempts reused, and the report files (study.csv, study.md, study.png, per-level
// results) as the result.
#include "solver/run/run_case.h"
#include "sph/v1/service.pb.h"
#include "worker/pool/attempt_reporter.h"

namespace sph::worker::pool {

// Collective. `run` carries the attempt's settings and rank 0's callbacks (cancel,
// checkpoints, interrupt) as for a single run; `reporter` is rank 0's (null elsewhere).
// Returns the outcome in run_case's terms (status, message, files, last checkpoint).
RunOutcome run_study_attempt(const v1::Case& c, const v1::ClaimResponse& claim,
                             const RunOptions& run, AttemptReporter* reporter);

}  // namespace sph::worker::pool
