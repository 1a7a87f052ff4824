// bench_service: how fast sph-server takes submissions, hands out work, and fans progress out
// to watchers. Starts a real sph-server (loopback, temporary directory) and acts as clients
// and as a worker pool; no solver runs.
//
//   bench_service [--jobs N] [--threads T] [--watchers W] [--events E]
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
  int jobs = 2000;
  int threads = 8;
  int watchers = 100;
  int events = 50;
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

void submit_throughput(const std::string& address, const Options& o) {
  const std::string text = bench_case();
  std::atomic<int> next{0}, failed{0};
  std::vector<std::vector<double>> latencies(static_cast<size_t>(o.threads));
  const auto t0 = Clock::now();
  std::vector<std::thread> threads;
  for (int t = 0; t < o.threads; ++t)
    threads.emplace_back([&, t] {
      auto stub = sph::v1::JobService::NewStub(
          grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
      for (int i = next++; i < o.jobs; i = next++) {
        sph::v1::SubmitRequest req;
        req.set_request_id("bench-" + std::to_string(i));
        req.set_case_text(text);
        sph::v1::SubmitResponse resp;
        const auto c0 = Clock::now();
        if (!stub->Submit(ctx().get(), req, &resp).ok()) ++failed;
        latencies[static_cast<size_t>(t)].push_back(ms_since(c0));
      }
    });
  for (auto& th : threads) th.join();
  const double seconds = ms_since(t0) / 1000;
  std::vector<double> all;
  for (auto& l : latencies) all.insert(all.end(), l.begin(), l.end());
  const Stats s = stats(all);
  std::printf(
      "submit: %d jobs from %d client threads in %.2f s: %.0f jobs/s "
      "(latency mean %.2f ms, p50 %.2f, p99 %.2f, max %.2f; %d failed)\n",
      o.jobs, o.threads, seconds, o.jobs / seconds, s.mean, s.p50, s.p99, s.max, failed.load());
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
  // Claims until it gets the fan-out job (the queue may hold earlier ones).
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

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::atoi(argv[i + 1]);
    if (a == "--jobs")
      o.jobs = v;
    else if (a == "--threads")
      o.threads = v;
    else if (a == "--watchers")
      o.watchers = v;
    else if (a == "--events")
      o.events = v;
    else {
      std::fprintf(stderr,
                   "usage: bench_service [--jobs N] [--threads T] [--watchers W] [--events E]\n");
      return 2;
    }
  }
  std::string tmpl = (fs::temp_directory_path() / "sphd-bench-XXXXXX").string();
  if (mkdtemp(tmpl.data()) == nullptr) return 1;
  const std::string dir = tmpl;
  std::printf("sph-server in %s (SQLite WAL, synchronous=FULL, on %s)\n", dir.c_str(),
              fs::temp_directory_path().c_str());
  Process server = Process::spawn(
      {SPHD_SERVER_BIN, "--address", "127.0.0.1:0", "--address-file", dir + "/address", "--db",
       dir + "/bench.db", "--results", dir + "/results", "--lease", "60"},
      dir + "/server.log");
  if (!sph::testing::eventually(20s, [&] { return fs::exists(dir + "/address"); })) {
    std::fprintf(stderr, "sph-server did not start:\n%s",
                 sph::testing::read_file(dir + "/server.log").c_str());
    return 1;
  }
  std::string address = sph::testing::read_file(dir + "/address");
  address.erase(address.find_last_not_of("\n") + 1);

  submit_throughput(address, o);
  claim_latency(address, std::min(o.jobs, 500));
  watch_fanout(address, server.pid(), o);
  server.kill_all();
  fs::remove_all(dir);
  return 0;
}
