#include "server/lease_reaper.h"

#include "server/clock.h"
#include "server/common/log.h"

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

void LeaseReaper::run() {
  std::unique_lock lock(mu_);
  while (!cv_.wait_for(lock, interval_, [this] { return stop_; })) {
    lock.unlock();
    try {
      if (const int n = store_.expire_leases(now_unix_ms()); n > 0)
        service::log_line("%d job(s) lost their pool (lease expired)", n);
    } catch (const std::exception& e) {
      // The next round tries again; a database error must not stop lease handling for good.
      service::log_line("lease check failed: %s", e.what());
    }
    lock.lock();
  }
}

}  // namespace sph::server
