#include "server/api/watch_job_reactor.h"

#include "common/job_state.h"
#include "server/api/errors.h"

namespace sph::server::api {
namespace {

// Events read from the store at once; a watcher that resumes far behind gets them in batches.
constexpr int kEventBatch = 500;

bool is_terminal_event(const v1::JobEvent& e) {
  return e.has_state_change() && service::is_terminal(e.state_change().state());
}

}  // namespace

WatchJobReactor::WatchJobReactor(store::JobStore& store, EventFeed& feed, WorkQueue& queue,
                                 StreamLimiter::Slot slot, std::int64_t job,
                                 std::int64_t after_sequence)
    : store_(store),
      feed_(feed),
      queue_(queue),
      slot_(std::move(slot)),
      job_(job),
      last_(after_sequence) {
  // Listening comes before the first read, so that an event committed in between still
  // wakes the stream.
  listen_key_ = feed_.listen(job_, [this] { wake(); });
  try {
    pump();
  } catch (...) {
    // gRPC frees a reactor whose constructor throws; the feed must not keep calling it.
    feed_.unlisten(listen_key_);
    throw;
  }
}

void WatchJobReactor::pump() {
  while (true) {
    {
      std::lock_guard lock(mu_);
      woken_ = false;
      if (cancelled_) break;
    }
    std::vector<v1::JobEvent> events;
    try {
      events = store_.events_after(job_, last_, kEventBatch);
      // Nothing newer: a finished job has nothing more to say (its terminal event is its
      // last). The events are read again after the state, for a job that finished between
      // the two reads: its terminal event is committed with the state.
      if (events.empty() && service::is_terminal(store_.state(job_))) {
        events = store_.events_after(job_, last_, kEventBatch);
        if (events.empty()) return end(grpc::Status::OK);
      }
    } catch (...) {
      return end(status_from_current_exception());
    }
    if (!events.empty()) {
      batch_ = std::move(events);
      next_ = 0;
      return StartWrite(&batch_[next_]);
    }
    if (feed_.shutting_down())
      return end(grpc::Status(
          grpc::StatusCode::UNAVAILABLE,
          "server shutting down; resume with after_sequence=" + std::to_string(last_)));
    std::lock_guard lock(mu_);
    if (cancelled_) break;
    if (!woken_) {
      turn_taken_ = false;  // wait for the feed
      return;
    }
  }
  end(grpc::Status(grpc::StatusCode::CANCELLED, "cancelled"));
}

void WatchJobReactor::OnWriteDone(bool ok) {
  if (!ok) return end(grpc::Status(grpc::StatusCode::CANCELLED, "client went away"));
  const v1::JobEvent& sent = batch_[next_];
  last_ = sent.sequence();
  if (is_terminal_event(sent)) return end(grpc::Status::OK);
  if (++next_ < batch_.size()) return StartWrite(&batch_[next_]);
  // A short batch was all there was when it was read; anything committed since has called
  // wake() (woken_ was cleared before the read), so without that there is nothing to read.
  const bool maybe_more = batch_.size() == static_cast<std::size_t>(kEventBatch);
  batch_.clear();
  if (!maybe_more) {
    std::lock_guard lock(mu_);
    if (!woken_ && !cancelled_) {
      turn_taken_ = false;  // wait for the feed
      return;
    }
  }
  pump();
}

void WatchJobReactor::wake() {
  {
    std::lock_guard lock(mu_);
    if (ended_ || cancelled_) return;
    if (turn_taken_) {
      woken_ = true;
      return;
    }
    turn_taken_ = true;
  }
  queue_.post([this] { pump(); });
}

void WatchJobReactor::OnCancel() {
  {
    std::lock_guard lock(mu_);
    cancelled_ = true;
    // A write in flight fails and a pump sees the flag: the holder of the turn ends it.
    if (turn_taken_) return;
    turn_taken_ = true;
  }
  end(grpc::Status(grpc::StatusCode::CANCELLED, "cancelled"));
}

void WatchJobReactor::end(grpc::Status status) {
  {
    std::lock_guard lock(mu_);
    ended_ = true;
  }
  feed_.unlisten(listen_key_);
  Finish(std::move(status));
}

void WatchJobReactor::OnDone() {
  delete this;
}

}  // namespace sph::server::api
