#pragma once
// Wake-ups for long-running calls: WatchJob streams wait for new events of their job, Claim
// long polls wait for a job to be queued. The events themselves are read from the database
// (the single source of truth); this only says when to look.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>

namespace sph::server {

class EventFeed {
  struct Topic {
    std::int64_t latest = 0;  // newest sequence published while someone watched
    int watchers = 0;
    std::condition_variable cv;
  };

 public:
  using Clock = std::chrono::steady_clock;

  // Registers interest in one job's events for its lifetime. Subscribe before reading the
  // database so that an event committed in between still wakes the wait.
  class Subscription {
   public:
    Subscription(EventFeed& feed, std::int64_t job);
    ~Subscription();
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;
    // Waits until an event with sequence > after is published, `timeout` passes or the
    // feed shuts down.
    void wait(std::int64_t after, std::chrono::milliseconds timeout);

   private:
    EventFeed& feed_;
    std::int64_t job_;
    Topic* topic_;
  };

  // Called after a commit that appended events of `job` up to `sequence`.
  void published(std::int64_t job, std::int64_t sequence);

  // Queue wake-ups: a generation number that grows whenever a job becomes claimable.
  std::uint64_t queue_generation();
  void job_queued();
  void wait_for_queue(std::uint64_t seen_generation, Clock::time_point deadline);

  // Wakes every waiter; later waits return at once.
  void shutdown();
  bool shutting_down();

 private:
  std::mutex mu_;
  std::map<std::int64_t, std::unique_ptr<Topic>> topics_;
  std::uint64_t queue_generation_ = 0;
  std::condition_variable queue_cv_;
  bool shutdown_ = false;
};

}  // namespace sph::server
