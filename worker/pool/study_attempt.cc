#include "worker/pool/study_attempt.h"

#include <mpi.h>

#include "case/study_ladder.h"
#include "case/study_spec_text.h"
#include "common/log.h"
#include "study/run_study.h"

namespace sph::worker::pool {

RunOutcome run_study_attempt(const v1::Case& c, const v1::ClaimResponse& claim,
                             const RunOptions& run, AttemptReporter* reporter) {
  RunOutcome out;
  // The server checked the ladder at Submit; a pool from other sources may disagree.
  if (const auto errors = validate_study(c, claim.study()); !errors.empty()) {
    out.status = RunStatus::kError;
    out.message = "invalid study: " + join_errors(errors);
    return out;
  }
  const std::vector<double> ladder = study_ladder(c, claim.study());
  study::StudyOptions o;
  o.output_dir = run.output_dir;
  o.previous_dirs.assign(claim.previous_output_dirs().begin(), claim.previous_output_dirs().end());
  o.resume_from = claim.resume_from();
  o.ladder_description = describe_study(claim.study());
  o.metadata = run.metadata;
  o.metadata["mode"] = "pool-study";
  o.progress_interval_seconds = run.progress_interval_seconds;
  o.cancel_requested = run.cancel_requested;
  o.on_checkpoint = run.on_checkpoint;
  o.interrupt = run.interrupt;
  o.checkpoint_requested = run.checkpoint_requested;
  o.prune_checkpoints = run.prune_checkpoints;
  o.quiet = run.quiet;
  if (reporter != nullptr) {
    o.on_progress = [reporter](const study::StudyProgress& p) {
      v1::ProgressInfo info = to_proto(p.run);
      auto* s = info.mutable_study();
      s->set_level(p.level);
      s->set_levels(p.levels);
      s->set_dx(p.dx);
      s->set_fraction(p.fraction);
      s->set_eta_seconds(p.eta_seconds);
      reporter->on_progress(info);
    };
    o.on_level = [&claim](const study::LevelResult& l) {
      service::log_line("%s level %d dx = %.6g: %s%s, error %.4g%%, %.1f s wall",
                        claim.job_id().c_str(), l.level, l.dx, l.status.c_str(),
                        l.reused ? " (reused)" : "", 100 * l.measurement.error, l.wall_seconds);
    };
  }
  const study::StudyOutcome r = study::run_study(c, ladder, MPI_COMM_WORLD, o);
  out.status = r.status;
  out.message =
      r.message + (r.plot_problem.empty() ? "" : " (no study.png: " + r.plot_problem + ")");
  out.files = r.files;
  out.last_checkpoint = r.last_checkpoint;
  for (const auto& l : r.levels) {
    out.steps += l.steps;
    out.wall_seconds += l.wall_seconds;
    if (l.simulated_time > 0) out.time = l.simulated_time;
  }
  return out;
}

}  // namespace sph::worker::pool
