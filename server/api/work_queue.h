#pragma once
// A few threads that run posted tasks in order of posting. Stream reactors use it to leave a
// thread that must not do their work: the event feed wakes them in the publishing thread,
// which holds the job store's lock, so reading the store there would deadlock.
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sph::server::api {

class WorkQueue {
 public:
  explicit WorkQueue(int threads);
  // Runs the tasks already posted, then joins the threads.
  ~WorkQueue();
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  void post(std::function<void()> task);

 private:
  void run();
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace sph::server::api
