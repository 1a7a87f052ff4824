#pragma once
// sph-server's metrics in the Prometheus text format (docs/service.md, "Metrics"): what the
// gRPC calls did (counted by the interceptor in rpc_metrics_interceptor.h: calls and their
// durations per method and status code, the pools that claimed work) and what the store holds
// (read at each scrape: jobs by state, queue depth, attempts by outcome, requeues, lease
// expiries, bytes of results).
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "server/store/job_store.h"

namespace sph::server::metrics {

class Metrics {
 public:
  // Upper bounds of the call-duration histogram's buckets [s] (then +Inf).
  static constexpr std::array<double, 12> kBuckets = {0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025,
                                                      0.05,   0.1,   0.25,   1,     10,   60};

  // One finished call: "/sph.v1.JobService/Submit", its status code's name, seconds taken.
  void record_call(const std::string& method, const char* code, double seconds);
  // A pool that called Claim (WorkerService), with its ranks and host, at `unix_ms`.
  void record_pool(const std::string& pool, const std::string& hostname, int ranks,
                   std::int64_t unix_ms);

  // The text a scrape returns: the counters above and the store's counts.
  std::string render(const store::StoreCounts& store, std::int64_t now_unix_ms) const;

 private:
  struct Calls {
    std::uint64_t count = 0;
    double seconds = 0;
    std::array<std::uint64_t, kBuckets.size()> buckets{};  // cumulative on output only
  };
  struct Pool {
    std::string hostname;
    int ranks = 0;
    std::int64_t last_claim_unix_ms = 0;
    std::uint64_t claims = 0;
  };
  mutable std::mutex mu_;
  std::map<std::pair<std::string, std::string>, Calls> calls_;  // (method, code)
  std::map<std::string, Pool> pools_;
};

}  // namespace sph::server::metrics
