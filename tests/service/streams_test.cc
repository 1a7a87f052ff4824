// WatchJob and FetchResult streams on a real sph-server: thousands of open watches cost no
// thread each, one event reaches all of its job's watchers, SIGTERM ends every stream with
// UNAVAILABLE within the grace, the per-client cap on open streams, and many fetches at once.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <thread>

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/support/client_callback.h>

#include "common/sha256.h"
#include "harness/service_harness.h"
#include "server/api/stream_limiter.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// An sph-server with flags of this test's choosing in the harness's directory.
struct StreamServer {
  Process process;
  std::string address;
  std::vector<std::shared_ptr<grpc::Channel>> channels;
  std::unique_ptr<v1::JobService::Stub> jobs;
  std::unique_ptr<v1::WorkerService::Stub> workers;

  // One HTTP/2 connection for each channel (different arguments keep gRPC from sharing one).
  std::shared_ptr<grpc::Channel> channel(std::size_t i) {
    while (channels.size() <= i) {
      grpc::ChannelArguments args;
      args.SetInt("sphd.test.connection", static_cast<int>(channels.size()));
      channels.push_back(
          grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
    }
    return channels[i];
  }
};

StreamServer start_server(ServiceHarness& h, const std::vector<std::string>& flags) {
  const std::string address_file = h.dir() + "/server.address";
  std::vector<std::string> argv = {SPHD_SERVER_BIN,      "--address",  "127.0.0.1:0",
                                   "--address-file",     address_file, "--db",
                                   h.dir() + "/sphd.db", "--results",  h.dir() + "/results"};
  argv.insert(argv.end(), flags.begin(), flags.end());
  StreamServer s;
  s.process = Process::spawn(argv, h.dir() + "/server.log");
  const bool up = eventually(20s, [&] { return fs::exists(address_file) || !s.process.running(); });
  if (!up || !fs::exists(address_file))
    throw std::runtime_error("sph-server did not start:\n" + read_file(h.dir() + "/server.log"));
  s.address = read_file(address_file);
  s.address.erase(s.address.find_last_not_of("\n") + 1);
  s.jobs = v1::JobService::NewStub(s.channel(0));
  s.workers = v1::WorkerService::NewStub(s.channel(0));
  return s;
}

std::unique_ptr<grpc::ClientContext> context(std::chrono::milliseconds timeout = 30s) {
  auto ctx = std::make_unique<grpc::ClientContext>();
  ctx->set_deadline(std::chrono::system_clock::now() + scaled(timeout));
  return ctx;
}

std::string submit(StreamServer& s, const std::string& request_id) {
  v1::SubmitRequest req;
  req.set_request_id(request_id);
  req.set_case_text(read_test_case("channel_2d.textproto"));
  v1::SubmitResponse resp;
  const auto status = s.jobs->Submit(context().get(), req, &resp);
  if (!status.ok()) throw std::runtime_error("Submit: " + status.error_message());
  return resp.job().id();
}

// Threads: of /proc/<pid>/status.
int thread_count(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
  return -1;
}

long rss_kib(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// Counts that the test waits on, shared by many client reactors.
struct Tally {
  std::mutex mu;
  std::condition_variable cv;
  int live = 0;  // streams that received their first message
  int done = 0;  // streams that ended

  void add(int Tally::*field) {
    {
      std::lock_guard lock(mu);
      ++(this->*field);
    }
    cv.notify_all();
  }
  // Waits until `field` reaches `n` (scaled timeout); returns the count reached.
  int wait_for(int Tally::*field, int n, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mu);
    cv.wait_for(lock, scaled(timeout), [&] { return this->*field >= n; });
    return this->*field;
  }
};

// One WatchJob stream on the client's callback API (no thread of the test per stream).
class Watcher final : public grpc::ClientReadReactor<v1::JobEvent> {
 public:
  Watcher(v1::JobService::Stub& stub, const std::string& job, Tally& tally,
          const std::string& authorization = "")
      : tally_(tally) {
    request_.set_job_id(job);
    if (!authorization.empty()) context_.AddMetadata("authorization", authorization);
    stub.async()->WatchJob(&context_, &request_, this);
    StartRead(&event_);
    StartCall();
  }
  // Ends the stream from the client's side and waits for it to end.
  void cancel() {
    context_.TryCancel();
    std::unique_lock lock(mu_);
    done_cv_.wait(lock, [&] { return done_; });
  }
  void OnReadDone(bool ok) override {
    if (!ok) return;  // OnDone follows with the status
    bool first = false;
    {
      std::lock_guard lock(mu_);
      sequences_.push_back(event_.sequence());
      first = sequences_.size() == 1;
      if (event_.has_state_change()) last_state_ = event_.state_change().state();
    }
    if (first) tally_.add(&Tally::live);
    StartRead(&event_);
  }
  void OnDone(const grpc::Status& status) override {
    {
      std::lock_guard lock(mu_);
      status_ = status;
      done_ = true;
    }
    done_cv_.notify_all();
    tally_.add(&Tally::done);
  }

  bool done() {
    std::lock_guard lock(mu_);
    return done_;
  }
  grpc::Status status() {
    std::lock_guard lock(mu_);
    return status_;
  }
  std::vector<std::int64_t> sequences() {
    std::lock_guard lock(mu_);
    return sequences_;
  }
  v1::JobState last_state() {
    std::lock_guard lock(mu_);
    return last_state_;
  }

 private:
  Tally& tally_;
  grpc::ClientContext context_;
  v1::WatchJobRequest request_;
  v1::JobEvent event_;
  std::mutex mu_;
  std::condition_variable done_cv_;
  bool done_ = false;
  grpc::Status status_;
  std::vector<std::int64_t> sequences_;
  v1::JobState last_state_ = v1::JOB_STATE_UNSPECIFIED;
};

// Client reactors must outlive their calls: whatever a failed assertion leaves open is
// cancelled and waited for before the reactors go.
struct Watchers {
  std::vector<std::unique_ptr<Watcher>> all;
  ~Watchers() {
    for (auto& w : all)
      if (!w->done()) w->cancel();
  }
};

// A blocking WatchJob that returns the stream's status once it ends, or OK once the first
// event arrived (the stream was accepted; it is then cancelled).
grpc::Status watch_accepted(v1::JobService::Stub& stub, const std::string& job) {
  v1::WatchJobRequest req;
  req.set_job_id(job);
  auto ctx = context(10s);
  auto reader = stub.WatchJob(ctx.get(), req);
  v1::JobEvent e;
  if (reader->Read(&e)) {
    ctx->TryCancel();
    reader->Finish();
    return grpc::Status::OK;
  }
  return reader->Finish();
}

TEST(ServiceStreams, AClientIsItsPeersHostAndItsToken) {
  using server::api::stream_client;
  EXPECT_EQ(stream_client("ipv4:127.0.0.1:5555").host, "127.0.0.1");
  EXPECT_EQ(stream_client("ipv4:127.0.0.1:5555").key, stream_client("ipv4:127.0.0.1:6666").key);
  EXPECT_EQ(stream_client("ipv6:[::1]:5555").host, "::1");
  EXPECT_EQ(stream_client("ipv6:%5B2001:db8::7%5D:443").host, "2001:db8::7");
  EXPECT_EQ(stream_client("unix:/run/sphd.sock").host, "unix:/run/sphd.sock");
  EXPECT_NE(stream_client("ipv4:10.0.0.1:1").key, stream_client("ipv4:10.0.0.2:1").key);
  EXPECT_EQ(stream_client("ipv4:10.0.0.1:1").key, stream_client("ipv4:10.0.0.1:2").key);
}

TEST(ServiceStreams, TwoThousandOpenWatchesTakeNoThreadEachAndEndOnSigterm) {
  ServiceHarness h;
  constexpr double kGraceSeconds = 20;
  StreamServer s = start_server(
      h, {"--max-streams-per-client", "5000", "--shutdown-grace", std::to_string(kGraceSeconds)});
  // Four queued jobs with 500 watchers each, over 8 connections.
  constexpr int kJobs = 4, kWatchersPerJob = 500, kWatchers = kJobs * kWatchersPerJob;
  std::vector<std::string> jobs;
  for (int j = 0; j < kJobs; ++j) jobs.push_back(submit(s, "watched-" + std::to_string(j)));
  std::vector<std::unique_ptr<v1::JobService::Stub>> stubs;
  for (std::size_t c = 0; c < 8; ++c) stubs.push_back(v1::JobService::NewStub(s.channel(c)));
  const int threads_before = thread_count(s.process.pid());

  Tally tally;
  Watchers watchers;
  const auto t0 = Clock::now();
  for (int w = 0; w < kWatchers; ++w)
    watchers.all.push_back(std::make_unique<Watcher>(
        *stubs[static_cast<std::size_t>(w) % 8], jobs[static_cast<std::size_t>(w % kJobs)], tally));
  // Each watch first replays the job's history (its QUEUED event), then waits.
  ASSERT_EQ(tally.wait_for(&Tally::live, kWatchers, 60s), kWatchers)
      << tally.done << " ended early; first status: " << [&] {
           for (auto& w : watchers.all)
             if (w->done()) return w->status().error_message();
           return std::string();
         }();
  const double open_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const int threads = thread_count(s.process.pid());
  std::printf(
      "%d watches open in %.2f s; sph-server threads: %d before, %d with them open; "
      "RSS %ld KiB\n",
      kWatchers, open_s, threads_before, threads, rss_kib(s.process.pid()));
  // A thread per watch would be over 2000.
  EXPECT_LT(threads, 100);
  EXPECT_EQ(tally.done, 0);

  // One cancel of a queued job (two events: cancel requested, CANCELLED) reaches each of its
  // 500 watchers, which end with it; the other jobs' watchers get nothing.
  v1::CancelJobRequest cancel;
  cancel.set_job_id(jobs[0]);
  cancel.set_reason("streams test");
  v1::Job cancelled;
  const auto t1 = Clock::now();
  ASSERT_TRUE(s.jobs->CancelJob(context().get(), cancel, &cancelled).ok());
  ASSERT_EQ(tally.wait_for(&Tally::done, kWatchersPerJob, 30s), kWatchersPerJob);
  std::printf("the cancel reached all %d watchers of %s in %.1f ms\n", kWatchersPerJob,
              jobs[0].c_str(),
              std::chrono::duration<double, std::milli>(Clock::now() - t1).count());
  std::this_thread::sleep_for(200ms);  // a stray delivery to another job's watcher would show
  int ended_with_cancel = 0;
  for (int w = 0; w < kWatchers; ++w) {
    Watcher& watcher = *watchers.all[static_cast<std::size_t>(w)];
    if (w % kJobs == 0) {
      ended_with_cancel += watcher.done() && watcher.status().ok() &&
                           watcher.last_state() == v1::JOB_STATE_CANCELLED &&
                           watcher.sequences() == std::vector<std::int64_t>{1, 2, 3};
    } else {
      EXPECT_FALSE(watcher.done()) << "watcher " << w << ": " << watcher.status().error_message();
      EXPECT_EQ(watcher.sequences(), std::vector<std::int64_t>{1}) << "watcher " << w;
    }
  }
  EXPECT_EQ(ended_with_cancel, kWatchersPerJob);

  // SIGTERM: every open watch ends with UNAVAILABLE, saying where to resume, and the server
  // exits well within its grace (a cut would take the whole grace).
  const auto t2 = Clock::now();
  s.process.signal(SIGTERM);
  const auto code = s.process.wait(
      std::chrono::milliseconds(static_cast<std::int64_t>(kGraceSeconds * 1000) + 10'000));
  const double stop_s = std::chrono::duration<double>(Clock::now() - t2).count();
  ASSERT_TRUE(code.has_value()) << "sph-server did not exit after SIGTERM\n"
                                << read_file(h.dir() + "/server.log");
  EXPECT_EQ(*code, 0) << read_file(h.dir() + "/server.log");
  ASSERT_EQ(tally.wait_for(&Tally::done, kWatchers, 30s), kWatchers);
  int unavailable = 0;
  std::string other;
  for (int w = 0; w < kWatchers; ++w) {
    if (w % kJobs == 0) continue;
    const auto st = watchers.all[static_cast<std::size_t>(w)]->status();
    if (st.error_code() == grpc::StatusCode::UNAVAILABLE &&
        st.error_message() == "server shutting down; resume with after_sequence=1")
      ++unavailable;
    else if (other.empty())
      other = std::to_string(st.error_code()) + " " + st.error_message();
  }
  std::printf(
      "SIGTERM: sph-server exited after %.2f s (grace %.0f s); %d of %d open watches "
      "ended UNAVAILABLE with where to resume\n",
      stop_s, kGraceSeconds, unavailable, kWatchers - kWatchersPerJob);
  EXPECT_EQ(unavailable, kWatchers - kWatchersPerJob) << "another ending: " << other;
  EXPECT_LT(stop_s, kGraceSeconds / 2);
}

TEST(ServiceStreams, AClientsOpenStreamsAreCappedAndAnEndedOneFreesItsPlace) {
  ServiceHarness h;
  StreamServer s = start_server(h, {"--max-streams-per-client", "3"});
  const std::string job = submit(s, "capped");
  Tally tally;
  Watchers watchers;
  for (int i = 0; i < 3; ++i)
    watchers.all.push_back(std::make_unique<Watcher>(*s.jobs, job, tally));
  ASSERT_EQ(tally.wait_for(&Tally::live, 3, 20s), 3);

  // The fourth stream from 127.0.0.1, a watch or a fetch, is refused at once, naming the
  // limit and the flag.
  const auto fourth = watch_accepted(*s.jobs, job);
  std::printf("4th stream: %d %s\n", fourth.error_code(), fourth.error_message().c_str());
  EXPECT_EQ(fourth.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(fourth.error_message(),
            "WatchJob: 3 streams already open from 127.0.0.1; the limit is 3 "
            "(--max-streams-per-client; WatchJob and FetchResult count together)");
  v1::FetchResultRequest fetch;
  fetch.set_job_id(job);
  auto ctx = context();
  auto reader = s.jobs->FetchResult(ctx.get(), fetch);
  v1::FileChunk chunk;
  EXPECT_FALSE(reader->Read(&chunk));
  const auto fetched = reader->Finish();
  EXPECT_EQ(fetched.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(fetched.error_message().find("FetchResult: 3 streams already open from 127.0.0.1"),
            std::string::npos)
      << fetched.error_message();
  EXPECT_FALSE(watchers.all[0]->done()) << "a refusal must not end the open streams";

  // A made-up token does not make the same host another client (the server has no token, so
  // any is accepted), or each new token would open three more streams.
  Watcher other(*s.jobs, job, tally, "Bearer someone-else");
  ASSERT_TRUE(eventually(10s, [&] { return other.done(); }));
  EXPECT_EQ(other.status().error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED)
      << other.status().error_message();

  // One of the three ends: its place is free again once the server has seen it end.
  watchers.all[0]->cancel();
  int tries = 0;
  grpc::Status again;
  const bool accepted = eventually(10s, [&] {
    ++tries;
    again = watch_accepted(*s.jobs, job);
    return again.ok();
  });
  EXPECT_TRUE(accepted) << again.error_code() << " " << again.error_message();
  std::printf("a new stream was accepted on try %d after one of the three ended\n", tries);
}

// Collects one FetchResult stream's bytes by file, reading a first chunk and then waiting
// until the test lets it go on (so that all fetches are open at once).
class Fetcher final : public grpc::ClientReadReactor<v1::FileChunk> {
 public:
  Fetcher(v1::JobService::Stub& stub, const std::string& job, Tally& tally) : tally_(tally) {
    request_.set_job_id(job);
    stub.async()->FetchResult(&context_, &request_, this);
    StartRead(&chunk_);
    StartCall();
  }
  void go_on() { StartRead(&chunk_); }
  void cancel() { context_.TryCancel(); }
  void OnReadDone(bool ok) override {
    if (!ok) return;
    std::string& data = files_[chunk_.name()];
    if (chunk_.offset() != static_cast<std::int64_t>(data.size())) bad_offsets_ = true;
    data += chunk_.data();
    sha256_[chunk_.name()] = chunk_.sha256();
    if (++chunks_ == 1)
      tally_.add(&Tally::live);
    else
      StartRead(&chunk_);
  }
  void OnDone(const grpc::Status& status) override {
    status_ = status;
    done_ = true;
    tally_.add(&Tally::done);
  }

  // Read after OnDone (the tally's lock orders it).
  grpc::Status status_;
  std::atomic<bool> done_{false};
  bool bad_offsets_ = false;
  std::map<std::string, std::string> files_;
  std::map<std::string, std::string> sha256_;

 private:
  Tally& tally_;
  grpc::ClientContext context_;
  v1::FetchResultRequest request_;
  v1::FileChunk chunk_;
  int chunks_ = 0;
};

TEST(ServiceStreams, ManyFetchesAtOnceStreamTheResultByteForByte) {
  ServiceHarness h;
  StreamServer s = start_server(h, {});
  const std::string job = submit(s, "fetched");
  // Finished as a fake pool would: a result in the attempt directory and its manifest.
  const v1::ClaimResponse claim = claim_next_job(*s.workers, *context(), "test-pool", 1);
  ASSERT_EQ(claim.job_id(), job);
  std::string h5((3 << 20) + 12345, '\0');  // four chunks, the last one short
  std::mt19937 random(41);
  for (char& c : h5) c = static_cast<char>(random());
  const std::map<std::string, std::string> content = {{"result.h5", h5}, {"result.xmf", "<Xdmf/>"}};
  std::map<std::string, std::string> sha256;
  v1::FinishRequest fin;
  fin.set_job_id(job);
  fin.set_attempt(claim.attempt());
  fin.set_outcome(v1::ATTEMPT_COMPLETED);
  for (const auto& [name, bytes] : content) {
    std::ofstream(fs::path(claim.output_dir()) / name, std::ios::binary) << bytes;
    auto* f = fin.add_files();
    f->set_name(name);
    f->set_size(static_cast<std::int64_t>(bytes.size()));
    service::Sha256 sha;
    sha.update(bytes);
    f->set_sha256(sha.hex_digest());
    sha256[name] = f->sha256();
  }
  v1::FinishResponse finished;
  ASSERT_TRUE(s.workers->Finish(context().get(), fin, &finished).ok());

  constexpr int kFetches = 64;
  Tally tally;
  std::vector<std::unique_ptr<Fetcher>> fetchers;
  std::vector<std::unique_ptr<v1::JobService::Stub>> stubs;
  for (std::size_t c = 0; c < 4; ++c) stubs.push_back(v1::JobService::NewStub(s.channel(c)));
  for (int i = 0; i < kFetches; ++i)
    fetchers.push_back(
        std::make_unique<Fetcher>(*stubs[static_cast<std::size_t>(i) % 4], job, tally));
  const int open = tally.wait_for(&Tally::live, kFetches, 30s);
  std::printf(
      "%d fetches open at once, each with its first chunk; sph-server threads: %d, "
      "RSS %ld KiB\n",
      open, thread_count(s.process.pid()), rss_kib(s.process.pid()));
  EXPECT_EQ(open, kFetches);
  for (auto& f : fetchers) f->go_on();
  const int done = tally.wait_for(&Tally::done, kFetches, 60s);
  if (done < kFetches)
    for (auto& f : fetchers) f->cancel();
  ASSERT_EQ(tally.wait_for(&Tally::done, kFetches, 30s), kFetches);
  int identical = 0;
  for (auto& f : fetchers) {
    std::lock_guard lock(tally.mu);
    EXPECT_TRUE(f->status_.ok()) << f->status_.error_message();
    EXPECT_FALSE(f->bad_offsets_);
    bool same = f->files_.size() == content.size();
    for (const auto& [name, bytes] : content)
      same = same && f->files_[name] == bytes && f->sha256_[name] == sha256[name];
    identical += same;
  }
  std::printf("%d of %d fetches got both files byte for byte (%zu + %zu bytes)\n", identical,
              kFetches, h5.size(), content.at("result.xmf").size());
  EXPECT_EQ(identical, kFetches);

  // A fetch resumed at an offset gets the rest of the file.
  v1::FetchResultRequest resume;
  resume.set_job_id(job);
  resume.set_file("result.h5");
  resume.set_offset((2 << 20) + 7);
  auto ctx = context();
  auto reader = s.jobs->FetchResult(ctx.get(), resume);
  v1::FileChunk chunk;
  std::string tail;
  while (reader->Read(&chunk)) tail += chunk.data();
  EXPECT_TRUE(reader->Finish().ok());
  EXPECT_TRUE(tail == h5.substr((2 << 20) + 7)) << tail.size() << " bytes";
}

}  // namespace
}  // namespace sph::testing
