#include "server/api/stream_limiter.h"

#include <utility>

#include "common/auth_token.h"

namespace sph::server::api {

StreamClient stream_client(std::string_view peer) {
  std::string host(peer);
  const auto colon = peer.find(':');
  const std::string_view scheme = peer.substr(0, colon);
  const std::string_view address = colon == std::string_view::npos ? "" : peer.substr(colon + 1);
  if (scheme == "ipv4") {
    host = std::string(address.substr(0, address.rfind(':')));
  } else if (scheme == "ipv6") {
    // "[::1]:5555", or percent-encoded as a URI: "%5B::1%5D:5555".
    const bool encoded = address.rfind("%5B", 0) == 0;
    const std::string_view open = encoded ? "%5B" : "[", close = encoded ? "%5D" : "]";
    const auto end = address.find(close);
    if (address.rfind(open, 0) == 0 && end != std::string_view::npos)
      host = std::string(address.substr(open.size(), end - open.size()));
  }
  std::string key = host;
  return {std::move(key), std::move(host)};
}

StreamClient stream_client(const grpc::ServerContextBase& context) {
  return stream_client(context.peer());
}

StreamLimiter::Slot::Slot(Slot&& other) noexcept
    : limiter_(std::exchange(other.limiter_, nullptr)), key_(std::move(other.key_)) {}

StreamLimiter::Slot& StreamLimiter::Slot::operator=(Slot&& other) noexcept {
  if (this != &other) {
    if (limiter_ != nullptr) limiter_->release(key_);
    limiter_ = std::exchange(other.limiter_, nullptr);
    key_ = std::move(other.key_);
  }
  return *this;
}

StreamLimiter::Slot::~Slot() {
  if (limiter_ != nullptr) limiter_->release(key_);
}

grpc::Status StreamLimiter::acquire(std::string_view method, const StreamClient& client,
                                    Slot& slot) {
  std::lock_guard lock(mu_);
  int& open = open_[client.key];
  if (open >= max_per_client_) {
    const std::string count = std::to_string(open);
    if (open == 0) open_.erase(client.key);
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            std::string(method) + ": " + count + " streams already open from " + client.host +
                "; the limit is " + std::to_string(max_per_client_) +
                " (--max-streams-per-client; WatchJob and FetchResult count together)"};
  }
  ++open;
  slot = Slot();
  slot.limiter_ = this;
  slot.key_ = client.key;
  return grpc::Status::OK;
}

void StreamLimiter::release(const std::string& key) {
  std::lock_guard lock(mu_);
  const auto it = open_.find(key);
  if (it != open_.end() && --it->second <= 0) open_.erase(it);
}

}  // namespace sph::server::api
