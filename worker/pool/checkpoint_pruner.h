#pragma once
// Removes a pool's old checkpoints only once the server has heard of newer ones.
//
// A local run keeps the two newest files in checkpoints/. A pool must not: when it is cut off
// from the server (but not from the shared disk), its lease expires and the server hands the
// newest checkpoint it was told of to the job's next attempt, while this pool computes on and
// writes more checkpoints. Deleting by age would remove the very file the next attempt is
// about to resume from. So the pool's solver keeps every checkpoint and this class deletes a
// file only after the server has acknowledged two newer ones in the same folder (the newest
// acknowledged one may be truncated if the disk failed while it was written; the one before
// it is the fallback). A file the server has not acknowledged is deleted only once a newer one
// is: when the attempt's Finish naming its newest checkpoint is accepted, the files written
// before it that no Report carried count as acknowledged (AttemptReporter::finish_acknowledged),
// since the server then resumes the job, if ever, from that newest one.
#include <map>
#include <string>
#include <vector>

namespace sph::worker::pool {

class CheckpointPruner {
 public:
  // `path` (a checkpoint this attempt wrote) has been acknowledged by the server: a Report or
  // Finish carrying it returned OK. Call in the order the checkpoints were written.
  void acknowledged(const std::string& path);

  static constexpr std::size_t kKeep = 2;

 private:
  // Acknowledged checkpoints still on disk, per folder, oldest first.
  std::map<std::string, std::vector<std::string>> kept_;
};

}  // namespace sph::worker::pool
