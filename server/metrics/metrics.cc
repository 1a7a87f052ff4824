#include "server/metrics/metrics.h"

#include <cstdio>

namespace sph::server::metrics {
namespace {

// Label values are quoted; a backslash, quote or newline in one is escaped (Prometheus text
// format 0.0.4). Pool ids and host names come from clients.
std::string label(const std::string& v) {
  std::string out;
  for (char c : v) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

void header(std::string& out, const char* name, const char* type, const char* help) {
  out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
}

// "/sph.v1.JobService/Submit" -> service "sph.v1.JobService", method "Submit".
std::pair<std::string, std::string> split_method(const std::string& full) {
  const auto slash = full.rfind('/');
  if (slash == std::string::npos || slash == 0) return {"", full};
  return {full.substr(full.front() == '/' ? 1 : 0, slash - (full.front() == '/' ? 1 : 0)),
          full.substr(slash + 1)};
}

}  // namespace

void Metrics::record_call(const std::string& method, const char* code, double seconds) {
  std::lock_guard lock(mu_);
  Calls& c = calls_[{method, code}];
  ++c.count;
  c.seconds += seconds;
  for (std::size_t b = 0; b < kBuckets.size(); ++b)
    if (seconds <= kBuckets[b]) {
      ++c.buckets[b];
      break;
    }
}

void Metrics::record_pool(const std::string& pool, const std::string& hostname, int ranks,
                          std::int64_t unix_ms) {
  std::lock_guard lock(mu_);
  // A pool id is the client's choice: keep the table bounded whatever clients send.
  if (!pools_.count(pool) && pools_.size() >= 10000) return;
  Pool& p = pools_[pool];
  p.hostname = hostname;
  p.ranks = ranks;
  p.last_claim_unix_ms = unix_ms;
  ++p.claims;
}

std::string Metrics::render(const store::StoreCounts& s, std::int64_t now_unix_ms) const {
  std::string out;
  header(out, "sphd_jobs", "gauge", "Jobs in the database by state.");
  for (const auto& [state, n] : s.jobs_by_state)
    out += "sphd_jobs{state=\"" + state + "\"} " + std::to_string(n) + "\n";
  header(out, "sphd_queue_depth", "gauge", "Jobs waiting for a pool (state QUEUED).");
  const auto queued = s.jobs_by_state.find("QUEUED");
  out += "sphd_queue_depth " +
         std::to_string(queued == s.jobs_by_state.end() ? 0 : queued->second) + "\n";
  header(out, "sphd_queued_particles", "gauge", "Estimated particles of the queued jobs.");
  out += "sphd_queued_particles " + number(s.queued_particles) + "\n";

  std::int64_t started = 0, finished = 0;
  for (const auto& [outcome, n] : s.attempts_by_outcome) {
    started += n;
    if (outcome != "RUNNING") finished += n;
  }
  header(out, "sphd_attempts_started_total", "counter", "Attempts pools have claimed.");
  out += "sphd_attempts_started_total " + std::to_string(started) + "\n";
  header(out, "sphd_attempts_finished_total", "counter", "Attempts that ended, by outcome.");
  for (const auto& [outcome, n] : s.attempts_by_outcome)
    if (outcome != "RUNNING")
      out +=
          "sphd_attempts_finished_total{outcome=\"" + outcome + "\"} " + std::to_string(n) + "\n";
  header(out, "sphd_attempts_running", "gauge", "Attempts running now.");
  const auto running = s.attempts_by_outcome.find("RUNNING");
  out += "sphd_attempts_running " +
         std::to_string(running == s.attempts_by_outcome.end() ? 0 : running->second) + "\n";
  header(out, "sphd_attempts_requeued_total", "counter",
         "Attempts that followed an earlier one of their job (after a lost lease or an "
         "interrupted pool).");
  out += "sphd_attempts_requeued_total " + std::to_string(s.attempts_requeued) + "\n";
  header(out, "sphd_lease_expiries_total", "counter",
         "Attempts whose pool stopped reporting (outcome LEASE_EXPIRED).");
  const auto expired = s.attempts_by_outcome.find("LEASE_EXPIRED");
  out += "sphd_lease_expiries_total " +
         std::to_string(expired == s.attempts_by_outcome.end() ? 0 : expired->second) + "\n";
  header(out, "sphd_result_bytes", "gauge",
         "Bytes of result files in the manifests of jobs whose files are kept.");
  out += "sphd_result_bytes " + std::to_string(s.result_bytes) + "\n";
  header(out, "sphd_result_deleted_bytes_total", "counter", "Bytes DeleteJobFiles freed.");
  out += "sphd_result_deleted_bytes_total " + std::to_string(s.results_deleted_bytes) + "\n";

  std::lock_guard lock(mu_);
  header(out, "sphd_submits_total", "counter",
         "Submit calls since the server started, by status code (OK also for a repeated "
         "request id).");
  for (const auto& [key, c] : calls_)
    if (key.first == "/sph.v1.JobService/Submit")
      out += "sphd_submits_total{code=\"" + key.second + "\"} " + std::to_string(c.count) + "\n";
  header(out, "sphd_rpc_duration_seconds", "histogram",
         "gRPC calls since the server started, by method and status code: time from the call's "
         "start to its status (for streams, the stream's life).");
  for (const auto& [key, c] : calls_) {
    const auto [service, method] = split_method(key.first);
    const std::string labels = "service=\"" + label(service) + "\",method=\"" + label(method) +
                               "\",code=\"" + key.second + "\"";
    std::uint64_t cumulative = 0;
    for (std::size_t b = 0; b < kBuckets.size(); ++b) {
      cumulative += c.buckets[b];
      out += "sphd_rpc_duration_seconds_bucket{" + labels + ",le=\"" + number(kBuckets[b]) +
             "\"} " + std::to_string(cumulative) + "\n";
    }
    out += "sphd_rpc_duration_seconds_bucket{" + labels + ",le=\"+Inf\"} " +
           std::to_string(c.count) + "\n";
    out += "sphd_rpc_duration_seconds_sum{" + labels + "} " + number(c.seconds) + "\n";
    out += "sphd_rpc_duration_seconds_count{" + labels + "} " + std::to_string(c.count) + "\n";
  }
  header(out, "sphd_pools_seen", "gauge",
         "Worker pools that called Claim since the server started.");
  out += "sphd_pools_seen " + std::to_string(pools_.size()) + "\n";
  header(out, "sphd_pool_ranks", "gauge", "MPI ranks of each pool seen.");
  for (const auto& [id, p] : pools_)
    out += "sphd_pool_ranks{pool=\"" + label(id) + "\",host=\"" + label(p.hostname) + "\"} " +
           std::to_string(p.ranks) + "\n";
  header(out, "sphd_pool_last_claim_age_seconds", "gauge",
         "Seconds since each pool's last Claim call (a pool long polls while idle).");
  for (const auto& [id, p] : pools_)
    out += "sphd_pool_last_claim_age_seconds{pool=\"" + label(id) + "\"} " +
           number(static_cast<double>(now_unix_ms - p.last_claim_unix_ms) / 1000.0) + "\n";
  return out;
}

}  // namespace sph::server::metrics
