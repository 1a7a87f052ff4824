#include "server/lease_reaper.h"

#include <cstdlib>

#include "common/log.h"
#include "server/clock.h"

namespace sph::server {

LeaseReaper::LeaseReaper(store::JobStore& store, std::chrono::milliseconds interval)
    : store_(store), interval_(interval), thread_([this] { run(); }) {}

LeaseReaper::~LeaseReaper() {
  stop();
}

void LeaseReaper::stop() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void LeaseReaper::check(std::int64_t now_ms, std::chrono::steady_clock::time_point steady_now) {
  try {
    if (last_) {
      const auto steady_ms =
          std::chrono::duration_cast<std::chrono::milliseconds>(steady_now - last_->second).count();
      const std::int64_t step = (now_ms - last_->first) - steady_ms;
      if (std::llabs(step) > kMaxClockStepMs) {
        service::log_line("the wall clock stepped by %+.1f s; every running job gets a fresh lease",
                          static_cast<double>(step) / 1000);
        store_.renew_all_leases(now_ms);
      }
    }
    last_.emplace(now_ms, steady_now);
    if (const int n = store_.expire_leases(now_ms); n > 0)
      service::log_line("%d job(s) lost their pool (lease expired)", n);
  } catch (const std::exception& e) {
    // The next round tries again; a database error must not stop lease handling for good.
    service::log_line("lease check failed: %s", e.what());
  }
}

void LeaseReaper::run() {
  std::unique_lock lock(mu_);
  while (!cv_.wait_for(lock, interval_, [this] { return stop_; })) {
    lock.unlock();
    check(now_unix_ms(), std::chrono::steady_clock::now());
    lock.lock();
  }
}

}  // namespace sph::server
