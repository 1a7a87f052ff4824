#include "server/events/event_feed.h"

#include <algorithm>

namespace sph::server {

EventFeed::Subscription::Subscription(EventFeed& feed, std::int64_t job) : feed_(feed), job_(job) {
  std::lock_guard lock(feed_.mu_);
  auto& t = feed_.topics_[job_];
  if (!t) t = std::make_unique<Topic>();
  ++t->watchers;
  topic_ = t.get();
}

EventFeed::Subscription::~Subscription() {
  std::lock_guard lock(feed_.mu_);
  if (--topic_->watchers == 0) feed_.topics_.erase(job_);
}

void EventFeed::Subscription::wait(std::int64_t after, std::chrono::milliseconds timeout) {
  std::unique_lock lock(feed_.mu_);
  topic_->cv.wait_for(lock, timeout, [&] { return topic_->latest > after || feed_.shutdown_; });
}

void EventFeed::published(std::int64_t job, std::int64_t sequence) {
  std::lock_guard lock(mu_);
  auto it = topics_.find(job);
  if (it == topics_.end()) return;
  it->second->latest = std::max(it->second->latest, sequence);
  it->second->cv.notify_all();
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

void EventFeed::shutdown() {
  std::lock_guard lock(mu_);
  shutdown_ = true;
  for (auto& [job, topic] : topics_) topic->cv.notify_all();
  queue_cv_.notify_all();
}

bool EventFeed::shutting_down() {
  std::lock_guard lock(mu_);
  return shutdown_;
}

}  // namespace sph::server
