// bench_service: how fast sph-server takes submissions, hands out work, and fans progress out
// to watchers. Starts a real sph-server (loopback, temporary directory) and acts as clients
// and as a worker pool; no solver runs.
//
//   bench_service [--submits N] [--clients C[,C...]] [--watchers W] [--events E]
//                 [--server PATH] [--server-args "ARGS"]
//
// Each submit phase keeps C clients (one connection each) with one Submit in flight apiece and
// reports submits/s, latency percentiles and whether every job was stored exactly once.
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/support/channel_arguments.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "harness/process.h"
#include "sph/v1/service.grpc.pb.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using sph::testing::Process;

struct Options {
  int submits = 5000;             // per submit phase
  std::vector<int> clients{100};  // one submit phase per entry
  int watchers = 100;
  int events = 50;
  std::string server = SPHD_SERVER_BIN;
  // Queue limits high enough for every phase, but enforced (their cost is part of a submit).
  std::string server_args = "--max-queued-jobs 10000000 --max-queued-particles 1e15";
};

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Stats {
  double mean = 0, p50 = 0, p99 = 0, max = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  s.p50 = v[v.size() / 2];
  s.p99 = v[std::min(v.size() - 1, v.size() * 99 / 100)];
  s.max = v.back();
  return s;
}

// CPU seconds (user + system) the server process has used so far.
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  std::getline(in, stat);
  std::istringstream rest(stat.substr(stat.rfind(')') + 2));
  std::string field;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15; ++i) {
    rest >> field;
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::unique_ptr<grpc::ClientContext> ctx(std::chrono::seconds timeout = 30s) {
  auto c = std::make_unique<grpc::ClientContext>();
  c->set_deadline(std::chrono::system_clock::now() + timeout);
  return c;
}

std::string bench_case() {
  return sph::testing::read_file(std::string(SPHD_TEST_CASES_DIR) + "/channel_2d.textproto");
}

// What one submit phase measured.
struct SubmitPhase {
  int clients = 0;
  int submits = 0;
  double seconds = 0;
  Stats latency;
  int failed = 0;
  int not_created = 0;
  double server_cpu_seconds = 0;
};

// One Submit in flight per client, each client on its own connection, all driven by one
// completion-queue thread, so that the clients take as little as possible of the cores they
// share with the server.
class SubmitClients {
 public:
  SubmitClients(const std::string& address, int clients) {
    for (int c = 0; c < clients; ++c) {
      grpc::ChannelArguments args;
      // A connection of its own (channels with equal arguments would share one).
      args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
      auto channel = grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
      channel->WaitForConnected(std::chrono::system_clock::now() + 10s);
      stubs_.push_back(sph::v1::JobService::NewStub(channel));
    }
  }

  // Submits `submits` jobs with request ids prefix + index, each client starting its next
  // Submit when its last one is answered.
  SubmitPhase run(const std::string& prefix, const std::string& case_text, int submits,
                  pid_t server_pid) {
    struct Call {
      int client = 0;
      grpc::ClientContext ctx;
      sph::v1::SubmitResponse response;
      grpc::Status status;
      std::unique_ptr<grpc::ClientAsyncResponseReader<sph::v1::SubmitResponse>> rpc;
      Clock::time_point started;
    };
    grpc::CompletionQueue cq;
    int next = 0;
    const auto start = [&](int client) {
      if (next >= submits) return;
      auto* call = new Call;
      call->client = client;
      call->ctx.set_deadline(std::chrono::system_clock::now() + 60s);
      sph::v1::SubmitRequest req;
      req.set_request_id(prefix + std::to_string(next++));
      req.set_case_text(case_text);
      call->started = Clock::now();
      call->rpc = stubs_[static_cast<size_t>(client)]->AsyncSubmit(&call->ctx, req, &cq);
      call->rpc->Finish(&call->response, &call->status, call);
    };
    SubmitPhase phase;
    phase.clients = static_cast<int>(stubs_.size());
    phase.submits = submits;
    std::vector<double> latencies;
    latencies.reserve(static_cast<size_t>(submits));
    const double cpu0 = cpu_seconds(server_pid);
    const auto t0 = Clock::now();
    for (int c = 0; c < phase.clients; ++c) start(c);
    for (int done = 0; done < submits; ++done) {
      void* tag = nullptr;
      bool ok = false;
      if (!cq.Next(&tag, &ok)) break;
      std::unique_ptr<Call> call(static_cast<Call*>(tag));
      latencies.push_back(ms_since(call->started));
      if (!ok || !call->status.ok()) {
        if (++phase.failed <= 5)
          std::printf("  submit failed: %d %s\n", call->status.error_code(),
                      call->status.error_message().c_str());
      } else if (!call->response.created()) {
        ++phase.not_created;
      }
      start(call->client);
    }
    phase.seconds = ms_since(t0) / 1000;
    phase.server_cpu_seconds = cpu_seconds(server_pid) - cpu0;
    phase.latency = stats(std::move(latencies));
    cq.Shutdown();
    void* tag = nullptr;
    bool ok = false;
    while (cq.Next(&tag, &ok)) delete static_cast<Call*>(tag);
    return phase;
  }

 private:
  std::vector<std::unique_ptr<sph::v1::JobService::Stub>> stubs_;
};

// How many stored jobs carry each request id that starts with `prefix`.
std::map<std::string, int> stored_request_ids(const std::string& address,
                                              const std::string& prefix) {
  auto stub = sph::v1::JobService::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  std::map<std::string, int> seen;
  std::string token;
  do {
    sph::v1::ListJobsRequest req;
    req.set_page_size(1000);
    req.set_page_token(token);
    sph::v1::ListJobsResponse resp;
    const auto status = stub->ListJobs(ctx().get(), req, &resp);
    if (!status.ok()) {
      std::printf("  ListJobs failed: %s\n", status.error_message().c_str());
      break;
    }
    for (const auto& j : resp.jobs())
      if (j.request_id().rfind(prefix, 0) == 0) ++seen[j.request_id()];
    token = resp.next_page_token();
  } while (!token.empty());
  return seen;
}

// False when a submit failed or a job was lost or stored twice.
bool submit_throughput(const std::string& address, pid_t server_pid, const Options& o) {
  const std::string text = bench_case();
  bool all_stored_once = true;
  for (const int clients : o.clients) {
    SubmitClients pool(address, clients);
    const std::string prefix = "bench-c" + std::to_string(clients) + "-";
    // A short warm-up (connections, server threads) that is not measured.
    pool.run("warm-c" + std::to_string(clients) + "-", text, std::min(o.submits, 2 * clients),
             server_pid);
    const SubmitPhase p = pool.run(prefix, text, o.submits, server_pid);
    const auto stored = stored_request_ids(address, prefix);
    int doubled = 0, lost = 0;
    for (int i = 0; i < o.submits; ++i) {
      const auto it = stored.find(prefix + std::to_string(i));
      if (it == stored.end())
        ++lost;
      else if (it->second > 1)
        ++doubled;
    }
    std::printf(
        "submit: %d submits from %d concurrent clients in %.2f s: %.0f submits/s (latency mean "
        "%.2f ms, p50 %.2f, p99 %.2f, max %.2f); server CPU %.0f us per submit; %d failed, %d "
        "not created, %d of %d stored (%d lost, %d stored twice)\n",
        p.submits, p.clients, p.seconds, p.submits / p.seconds, p.latency.mean, p.latency.p50,
        p.latency.p99, p.latency.max, 1e6 * p.server_cpu_seconds / p.submits, p.failed,
        p.not_created, static_cast<int>(stored.size()), o.submits, lost, doubled);
    std::fflush(stdout);
    all_stored_once = all_stored_once && p.failed == 0 && p.not_created == 0 && lost == 0 &&
                      doubled == 0 && static_cast<int>(stored.size()) == o.submits;
  }
  return all_stored_once;
}

void claim_latency(const std::string& address, int claims) {
  auto stub = sph::v1::WorkerService::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  std::vector<double> claim_ms, cycle_ms;
  for (int i = 0; i < claims; ++i) {
    sph::v1::ClaimRequest req;
    req.set_pool_id("bench-pool");
    req.set_ranks(2);
    sph::v1::ClaimResponse claim;
    const auto c0 = Clock::now();
    if (!stub->Claim(ctx().get(), req, &claim).ok() || claim.job_id().empty()) break;
    claim_ms.push_back(ms_since(c0));
    sph::v1::FinishRequest fin;
    fin.set_job_id(claim.job_id());
    fin.set_attempt(claim.attempt());
    fin.set_outcome(sph::v1::ATTEMPT_FAILED);
    fin.set_message("benchmark");
    sph::v1::FinishResponse fr;
    stub->Finish(ctx().get(), fin, &fr);
    cycle_ms.push_back(ms_since(c0));
  }
  const Stats c = stats(claim_ms), y = stats(cycle_ms);
  std::printf(
      "claim: %zu claims from a queue of queued jobs: latency mean %.2f ms, p50 %.2f, "
      "p99 %.2f, max %.2f; claim+finish cycle mean %.2f ms\n",
      claim_ms.size(), c.mean, c.p50, c.p99, c.max, y.mean);
}

void watch_fanout(const std::string& address, pid_t server_pid, const Options& o) {
  auto jobs = sph::v1::JobService::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  auto workers = sph::v1::WorkerService::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  sph::v1::SubmitRequest sub;
  sub.set_request_id("fanout");
  sub.set_case_text(bench_case());
  sph::v1::SubmitResponse job;
  jobs->Submit(ctx().get(), sub, &job);
  // Claims until it gets the fan-out job (a queue left by an earlier run may hold others).
  sph::v1::ClaimResponse claim;
  do {
    sph::v1::ClaimRequest req;
    req.set_pool_id("bench-fanout");
    req.set_ranks(1);
    claim.Clear();
    if (!workers->Claim(ctx().get(), req, &claim).ok() || claim.job_id().empty()) {
      std::printf("watch: could not claim the fan-out job\n");
      return;
    }
  } while (claim.job_id() != job.job().id());

  // Each watcher records when it saw each progress event (by step).
  std::vector<std::vector<Clock::time_point>> seen(
      static_cast<size_t>(o.watchers),
      std::vector<Clock::time_point>(static_cast<size_t>(o.events)));
  std::atomic<int> ready{0};
  std::vector<std::thread> watchers;
  for (int w = 0; w < o.watchers; ++w)
    watchers.emplace_back([&, w] {
      // One channel per watcher, as separate clients would have.
      auto stub = sph::v1::JobService::NewStub(
          grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
      sph::v1::WatchJobRequest req;
      req.set_job_id(job.job().id());
      auto c = ctx(120s);
      auto reader = stub->WatchJob(c.get(), req);
      sph::v1::JobEvent e;
      bool counted = false;
      while (reader->Read(&e)) {
        if (!counted) {
          ++ready;  // the history replay arrived: the stream is live
          counted = true;
        }
        if (e.has_progress() && e.progress().step() < o.events)
          seen[static_cast<size_t>(w)][static_cast<size_t>(e.progress().step())] = Clock::now();
      }
      reader->Finish();
    });
  while (ready.load() < o.watchers) std::this_thread::sleep_for(10ms);

  std::vector<Clock::time_point> sent(static_cast<size_t>(o.events));
  const double cpu0 = cpu_seconds(server_pid);
  for (int i = 0; i < o.events; ++i) {
    sph::v1::ReportRequest r;
    r.set_job_id(claim.job_id());
    r.set_attempt(claim.attempt());
    r.mutable_progress()->set_step(i);
    sph::v1::ReportResponse rr;
    sent[static_cast<size_t>(i)] = Clock::now();
    workers->Report(ctx().get(), r, &rr);
    std::this_thread::sleep_for(20ms);
  }
  std::this_thread::sleep_for(500ms);
  const double cpu = cpu_seconds(server_pid) - cpu0;
  sph::v1::FinishRequest fin;
  fin.set_job_id(claim.job_id());
  fin.set_attempt(claim.attempt());
  fin.set_outcome(sph::v1::ATTEMPT_COMPLETED);
  sph::v1::FinishResponse fr;
  workers->Finish(ctx().get(), fin, &fr);
  for (auto& t : watchers) t.join();

  std::vector<double> all_delivered, each;
  int missing = 0;
  for (int i = 0; i < o.events; ++i) {
    double last = 0;
    for (int w = 0; w < o.watchers; ++w) {
      const auto at = seen[static_cast<size_t>(w)][static_cast<size_t>(i)];
      if (at == Clock::time_point{}) {
        ++missing;
        continue;
      }
      const double d =
          std::chrono::duration<double, std::milli>(at - sent[static_cast<size_t>(i)]).count();
      each.push_back(d);
      last = std::max(last, d);
    }
    all_delivered.push_back(last);
  }
  const Stats e = stats(each), a = stats(all_delivered);
  std::printf(
      "watch: %d events to %d watchers: report-to-watcher latency mean %.2f ms, p50 %.2f, "
      "p99 %.2f; until all %d have it: mean %.2f ms, max %.2f; server CPU %.2f ms per "
      "event (%.1f us per delivery); %d deliveries missing\n",
      o.events, o.watchers, e.mean, e.p50, e.p99, o.watchers, a.mean, a.max, 1000 * cpu / o.events,
      1e6 * cpu / (o.events * o.watchers), missing);
}

// argv followed by the words of `extra`.
std::vector<std::string> with_words(std::vector<std::string> argv, const std::string& extra) {
  std::istringstream words(extra);
  for (std::string w; words >> w;) argv.push_back(w);
  return argv;
}

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  bool ok = true;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const std::string v = argv[i + 1];
    if (a == "--submits")
      o.submits = std::atoi(v.c_str());
    else if (a == "--clients")
      o.clients = parse_list(v);
    else if (a == "--watchers")
      o.watchers = std::atoi(v.c_str());
    else if (a == "--events")
      o.events = std::atoi(v.c_str());
    else if (a == "--server")
      o.server = v;
    else if (a == "--server-args")
      o.server_args = v;
    else
      ok = false;
  }
  ok = ok && argc % 2 == 1 && o.submits > 0 && !o.clients.empty() &&
       std::all_of(o.clients.begin(), o.clients.end(), [](int c) { return c > 0; });
  if (!ok) {
    std::fprintf(stderr,
                 "usage: bench_service [--submits N] [--clients C[,C...]] [--watchers W] "
                 "[--events E] [--server PATH] [--server-args \"ARGS\"]\n");
    return 2;
  }
  std::string tmpl = (fs::temp_directory_path() / "sphd-bench-XXXXXX").string();
  if (mkdtemp(tmpl.data()) == nullptr) return 1;
  const std::string dir = tmpl;
  std::printf("sph-server in %s (SQLite WAL, synchronous=FULL, on %s)\n", dir.c_str(),
              fs::temp_directory_path().c_str());
  Process server = Process::spawn(
      with_words({o.server, "--address", "127.0.0.1:0", "--address-file", dir + "/address", "--db",
                  dir + "/bench.db", "--results", dir + "/results", "--lease", "60",
                  // Every watcher is this one process: the per-client cap must hold them all.
                  "--max-streams-per-client", std::to_string(std::max(256, o.watchers + 16))},
                 o.server_args),
      dir + "/server.log");
  if (!sph::testing::eventually(20s, [&] { return fs::exists(dir + "/address"); })) {
    std::fprintf(stderr, "sph-server did not start:\n%s",
                 sph::testing::read_file(dir + "/server.log").c_str());
    return 1;
  }
  std::string address = sph::testing::read_file(dir + "/address");
  address.erase(address.find_last_not_of("\n") + 1);

  // The fan-out job is claimed first, from an empty queue.
  watch_fanout(address, server.pid(), o);
  const bool submits_ok = submit_throughput(address, server.pid(), o);
  claim_latency(address, std::min(o.submits, 500));
  server.kill_all();
  fs::remove_all(dir);
  return submits_ok ? 0 : 1;
}
