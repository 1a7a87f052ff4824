#pragma once
// Group commit: requests that arrive while a batch is being committed wait, and the next batch
// commits all of them in one transaction, so that one durable commit (one fsync) serves many
// callers. There is no committer thread: the first caller that finds no batch running commits
// everything queued (the leader) and the others sleep until their batch is done or until it is
// their turn to lead. Each caller gets back only its own result or its own error.
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sph::server::store {

struct GroupCommitStats {
  std::int64_t batches = 0;  // batches committed (or failed), one transaction each
  std::int64_t requests = 0;
  std::size_t largest = 0;     // most requests in one batch
  std::size_t waiting = 0;     // requests queued for the next batch right now
  std::size_t committing = 0;  // requests in the batch being committed right now
};

template <typename Request, typename Result>
class GroupCommit {
 public:
  struct Entry {
    const Request* request = nullptr;
    std::optional<Result> result;
    std::exception_ptr error;
    bool done = false;
    std::condition_variable wake;
  };
  // Commits one batch, in arrival order: sets each entry's result or error. An exception it
  // lets out fails every entry of the batch that has no result with that exception.
  using CommitBatch = std::function<void(std::span<Entry* const> batch)>;

  // A batch holds at most max_batch requests, which bounds how long one transaction keeps the
  // database to itself.
  explicit GroupCommit(CommitBatch commit, std::size_t max_batch = 256)
      : commit_(std::move(commit)), max_batch_(std::max<std::size_t>(max_batch, 1)) {}
  GroupCommit(const GroupCommit&) = delete;
  GroupCommit& operator=(const GroupCommit&) = delete;

  // Returns once the batch holding `request` has been committed; rethrows its error.
  Result submit(const Request& request) {
    Entry entry;
    entry.request = &request;
    std::unique_lock lock(mu_);
    queue_.push_back(&entry);
    while (!entry.done) {
      if (!leading_)
        lead(lock);
      else
        entry.wake.wait(lock);
    }
    if (entry.error) std::rethrow_exception(entry.error);
    return std::move(*entry.result);
  }

  GroupCommitStats stats() const {
    std::lock_guard lock(mu_);
    GroupCommitStats s = stats_;
    s.waiting = queue_.size();
    s.committing = committing_;
    return s;
  }

 private:
  // Called with the lock held and no leader; returns with the lock held.
  void lead(std::unique_lock<std::mutex>& lock) {
    // The batch is taken before this thread becomes the leader: if taking it throws, no one
    // is left leading a batch that never ends.
    const std::size_t n = std::min(queue_.size(), max_batch_);
    std::vector<Entry*> batch(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(n));
    leading_ = true;
    queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(n));
    committing_ = n;
    lock.unlock();
    try {
      commit_(batch);
    } catch (...) {
      for (Entry* e : batch)
        if (!e->result) e->error = std::current_exception();
    }
    lock.lock();
    committing_ = 0;
    ++stats_.batches;
    stats_.requests += static_cast<std::int64_t>(n);
    stats_.largest = std::max(stats_.largest, n);
    // Notified with the lock held: a waiter can only see `done` and destroy its entry after
    // the lock is released.
    for (Entry* e : batch) {
      if (!e->result && !e->error)
        e->error =
            std::make_exception_ptr(std::logic_error("group commit left a request unanswered"));
      e->done = true;
      e->wake.notify_one();
    }
    leading_ = false;
    // The oldest waiter leads the next batch (the leader itself may be among them when the
    // queue was longer than one batch).
    if (!queue_.empty()) queue_.front()->wake.notify_one();
  }

  CommitBatch commit_;
  const std::size_t max_batch_;
  mutable std::mutex mu_;
  std::deque<Entry*> queue_;
  bool leading_ = false;
  std::size_t committing_ = 0;
  GroupCommitStats stats_;
};

}  // namespace sph::server::store
