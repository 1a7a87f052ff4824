#pragma once
// A cap on the WatchJob and FetchResult streams one client holds open at once. An open stream
// costs the server memory (a watch's listener and pending events, a fetch's chunk buffer) but
// no thread, so without a cap one client could open streams until the server runs out of it.
#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include <map>
#include <mutex>
#include <string>
#include <string_view>

namespace sph::server::api {

// A client is the peer's host, without the port, so that all of a host's connections count
// together. Not the token: without --token-file any token is accepted, so a token in the key
// would let one host open a new set of streams per made-up token; with one, every caller
// presents the same token.
struct StreamClient {
  std::string key;
  std::string host;  // for messages
};
// `peer` as grpc::ServerContextBase::peer() gives it ("ipv4:127.0.0.1:5555",
// "ipv6:[::1]:5555", "unix:/path").
StreamClient stream_client(std::string_view peer);
StreamClient stream_client(const grpc::ServerContextBase& context);

class StreamLimiter {
 public:
  explicit StreamLimiter(int max_per_client) : max_per_client_(max_per_client) {}

  // A place taken by one open stream; destroying it gives the place back.
  class Slot {
   public:
    Slot() = default;
    Slot(Slot&& other) noexcept;
    Slot& operator=(Slot&& other) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class StreamLimiter;
    StreamLimiter* limiter_ = nullptr;
    std::string key_;
  };

  // Takes a place for one stream of `method` from `client` in `slot`, or returns
  // RESOURCE_EXHAUSTED naming the limit and the flag that sets it.
  grpc::Status acquire(std::string_view method, const StreamClient& client, Slot& slot);

 private:
  void release(const std::string& key);
  const int max_per_client_;
  std::mutex mu_;
  std::map<std::string, int> open_;
};

}  // namespace sph::server::api
