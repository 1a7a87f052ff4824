#include "server/events/event_feed.h"

namespace sph::server {

std::uint64_t EventFeed::listen(std::int64_t job, Wake wake) {
  std::lock_guard lock(mu_);
  const std::uint64_t key = next_key_++;
  if (shutdown_) wake();
  listeners_[job].emplace(key, std::move(wake));
  listener_jobs_.emplace(key, job);
  return key;
}

void EventFeed::unlisten(std::uint64_t key) {
  std::lock_guard lock(mu_);
  const auto it = listener_jobs_.find(key);
  if (it == listener_jobs_.end()) return;
  const auto job = listeners_.find(it->second);
  job->second.erase(key);
  if (job->second.empty()) listeners_.erase(job);
  listener_jobs_.erase(it);
  if (shutdown_ && listener_jobs_.empty()) drained_cv_.notify_all();
}

void EventFeed::published(std::int64_t job, std::int64_t /*sequence*/) {
  // Every listener of the job is called: each knows which sequence it has sent, and one
  // that is still sending reads again anyway.
  std::lock_guard lock(mu_);
  const auto it = listeners_.find(job);
  if (it == listeners_.end()) return;
  for (auto& [key, wake] : it->second) wake();
}

std::uint64_t EventFeed::queue_generation() {
  std::lock_guard lock(mu_);
  return queue_generation_;
}

void EventFeed::job_queued() {
  std::lock_guard lock(mu_);
  ++queue_generation_;
  queue_cv_.notify_all();
}

void EventFeed::wait_for_queue(std::uint64_t seen_generation, Clock::time_point deadline) {
  std::unique_lock lock(mu_);
  queue_cv_.wait_until(lock, deadline,
                       [&] { return queue_generation_ != seen_generation || shutdown_; });
}

void EventFeed::shutdown(std::chrono::milliseconds drain) {
  std::unique_lock lock(mu_);
  if (!shutdown_) {
    shutdown_ = true;
    for (auto& [job, wakes] : listeners_)
      for (auto& [key, wake] : wakes) wake();
    queue_cv_.notify_all();
  }
  drained_cv_.wait_for(lock, drain, [&] { return listener_jobs_.empty(); });
}

bool EventFeed::shutting_down() {
  std::lock_guard lock(mu_);
  return shutdown_;
}

}  // namespace sph::server
