#pragma once
// One open FetchResult stream on gRPC's callback API: the files of a finished job's result
// manifest in chunks of 1 MiB, one chunk in flight at a time, read from disk as the client
// takes them. Only names the manifest lists are served, and each file is checked against
// the manifest's size before it is sent (DATA_LOSS otherwise). On server shutdown the stream
// ends with UNAVAILABLE, saying at which offset to resume.
#include <grpcpp/support/server_callback.h>

#include <atomic>
#include <cstdint>
#include <fstream>
#include <optional>
#include <vector>

#include "server/api/stream_limiter.h"
#include "server/events/event_feed.h"
#include "server/results/result_layout.h"
#include "server/store/job_store.h"
#include "sph/v1/service.pb.h"

namespace sph::server::api {

class FetchResultReactor final : public grpc::ServerWriteReactor<v1::FileChunk> {
 public:
  // Reads the job and starts sending; a job without a result, or a file the manifest does
  // not list, ends the stream before anything is sent. `file` empty: every file; `offset`
  // applies to each file sent.
  FetchResultReactor(store::JobStore& store, EventFeed& feed, const ResultLayout& layout,
                     StreamLimiter::Slot slot, std::int64_t job, std::string file,
                     std::int64_t offset);

  void OnWriteDone(bool ok) override;
  void OnCancel() override { cancelled_ = true; }
  void OnDone() override;

 private:
  ~FetchResultReactor() override = default;
  // Reads the job and picks the files to send, or returns the status that refuses the call.
  std::optional<grpc::Status> check_job();
  // Starts the next chunk's write, or ends the stream when there is none or something is
  // wrong. There is always a write in flight or a call of this running, so the stream never
  // waits without one of them and OnCancel needs only to leave a flag.
  void send_next();
  // The next write, or the status the stream ends with.
  std::optional<grpc::Status> prepare_next();
  std::optional<grpc::Status> open_next_file();
  grpc::Status deleted();

  store::JobStore& store_;
  EventFeed& feed_;
  const ResultLayout& layout_;
  StreamLimiter::Slot slot_;  // given back when OnDone deletes the reactor
  const std::int64_t job_id_;
  const std::string file_;
  const std::int64_t start_offset_;
  std::atomic<bool> cancelled_{false};

  v1::Job job_;
  std::vector<const v1::ResultFile*> files_;  // into job_'s manifest
  std::size_t file_index_ = 0;                // files_[file_index_ - 1] is being sent
  std::ifstream in_;
  std::int64_t offset_ = 0;  // of the chunk being prepared or written
  std::int64_t size_ = 0;
  bool file_started_ = false;  // a file gets at least one chunk, also when empty
  v1::FileChunk chunk_;        // the stream's one chunk buffer
};

}  // namespace sph::server::api
