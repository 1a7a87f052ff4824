#pragma once
// One open WatchJob stream on gRPC's callback API: it sends the job's events after a sequence
// and, when it has sent all there are, waits without a thread for the event feed to say that
// there are more. It ends after the job's terminal event, when the client goes away, or when
// the server shuts down (UNAVAILABLE, saying where to resume).
#include <grpcpp/support/server_callback.h>

#include <cstdint>
#include <mutex>
#include <vector>

#include "server/api/stream_limiter.h"
#include "server/api/work_queue.h"
#include "server/events/event_feed.h"
#include "server/store/job_store.h"
#include "sph/v1/service.pb.h"

namespace sph::server::api {

class WatchJobReactor final : public grpc::ServerWriteReactor<v1::JobEvent> {
 public:
  // Starts sending at once; the first read of the store happens here, so a job that does not
  // exist ends the stream with NOT_FOUND before anything is sent. `queue` runs the reads that
  // a wake-up from the feed asks for (the feed calls in a thread that holds the store's lock).
  WatchJobReactor(store::JobStore& store, EventFeed& feed, WorkQueue& queue,
                  StreamLimiter::Slot slot, std::int64_t job, std::int64_t after_sequence);

  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  ~WatchJobReactor() override = default;
  // Whoever holds the turn reads the store and writes; the turn passes from the constructor
  // to pump(), to each write until OnWriteDone, and is given up only while the stream waits
  // for the feed. So one write is in flight at a time and only the holder ends the stream.
  void pump();
  void wake();
  // Ends the stream (called by the holder of the turn): no wake-up reaches this reactor
  // afterwards, and nothing touches it once Finish has been called.
  void end(grpc::Status status);

  store::JobStore& store_;
  EventFeed& feed_;
  WorkQueue& queue_;
  StreamLimiter::Slot slot_;  // given back when OnDone deletes the reactor
  const std::int64_t job_;
  std::uint64_t listen_key_ = 0;

  // Owned by the holder of the turn.
  std::int64_t last_;  // the sequence sent last
  std::vector<v1::JobEvent> batch_;
  std::size_t next_ = 0;  // batch_[next_] is being written

  std::mutex mu_;
  bool turn_taken_ = true;  // the constructor holds it
  bool woken_ = false;      // the feed called while the turn was taken: read again
  bool cancelled_ = false;
  bool ended_ = false;
};

}  // namespace sph::server::api
