#pragma once
// A background thread that puts jobs whose pool stopped reporting back in the queue.
#include <chrono>
#include <condition_variable>
#include <mutex>
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

 private:
  void run();
  store::JobStore& store_;
  std::chrono::milliseconds interval_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sph::server
