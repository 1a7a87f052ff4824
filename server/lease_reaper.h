#pragma once
// A background thread that puts jobs whose pool stopped reporting back in the queue.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>

#include "server/store/job_store.h"

namespace sph::server {

class LeaseReaper {
 public:
  LeaseReaper(store::JobStore& store, std::chrono::milliseconds interval);
  ~LeaseReaper();
  LeaseReaper(const LeaseReaper&) = delete;
  LeaseReaper& operator=(const LeaseReaper&) = delete;
  void stop();

  // One round at wall time `now_ms` (what the thread does every interval). Lease deadlines
  // are wall-clock times (they must survive a restart); when the wall clock has moved more
  // than kMaxClockStepMs further or less than the monotonic clock since the previous round (an
  // NTP step, a manual change), every running job first gets a fresh lease, as after a
  // restart: a step forward would otherwise expire every lease at once, a step back keep a
  // dead pool's job for as long as the step.
  void check(std::int64_t now_ms, std::chrono::steady_clock::time_point steady_now);

  static constexpr std::int64_t kMaxClockStepMs = 1000;

 private:
  void run();
  store::JobStore& store_;
  // The previous round's wall and monotonic times.
  std::optional<std::pair<std::int64_t, std::chrono::steady_clock::time_point>> last_;
  std::chrono::milliseconds interval_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sph::server
