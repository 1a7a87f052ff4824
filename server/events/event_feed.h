#pragma once
// Wake-ups for long-running calls: WatchJob streams listen for new events of their job, Claim
// long polls wait for a job to be queued. The events themselves are read from the database
// (the single source of truth); this only says when to look.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>

namespace sph::server {

class EventFeed {
 public:
  using Clock = std::chrono::steady_clock;
  // Called for each commit that appended events of the listened job, and once by shutdown().
  // It runs in the publishing thread, which holds the job store's lock and this feed's, so it
  // must return quickly and must not call the store or the feed (hand the work to another
  // thread). Listen before reading the database, so that an event committed in between still
  // calls it.
  using Wake = std::function<void()>;

  // Returns the key that unlisten() takes. Listening after shutdown() calls `wake` at once.
  std::uint64_t listen(std::int64_t job, Wake wake);
  // After it returns, the listener's `wake` is not running and is never called again. Not to
  // be called from a `wake`.
  void unlisten(std::uint64_t key);

  // Called after a commit that appended events of `job` up to `sequence`.
  void published(std::int64_t job, std::int64_t sequence);

  // Queue wake-ups: a generation number that grows whenever a job becomes claimable.
  std::uint64_t queue_generation();
  void job_queued();
  void wait_for_queue(std::uint64_t seen_generation, Clock::time_point deadline);

  // Wakes every listener and waiter (later waits return at once), then waits up to `drain`
  // until every listener has stopped listening. A stream that ends only after
  // grpc::Server::Shutdown has begun can lose its status to the closing connection, so the
  // streams are given the chance to end first.
  void shutdown(std::chrono::milliseconds drain = std::chrono::seconds(1));
  bool shutting_down();

 private:
  std::mutex mu_;
  std::uint64_t next_key_ = 1;
  // Job -> key -> wake; key -> job finds a listener's job for unlisten().
  std::map<std::int64_t, std::map<std::uint64_t, Wake>> listeners_;
  std::map<std::uint64_t, std::int64_t> listener_jobs_;
  std::uint64_t queue_generation_ = 0;
  std::condition_variable queue_cv_;
  std::condition_variable drained_cv_;  // the last listener left after shutdown()
  bool shutdown_ = false;
};

}  // namespace sph::server
