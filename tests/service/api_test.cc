// sph-server as a process on loopback, driven through its gRPC API. The test plays the client
// and, where no solver is needed, the worker pool (claim, report, finish), which lets it
// check fencing, validation and the manifest rules precisely.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>

#include "common/sha256.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "harness/service_harness.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;

std::string small_case() {
  return read_test_case("channel_2d.textproto");
}

// Submits and expects INVALID_ARGUMENT whose message names `field`.
void expect_rejected(ServiceHarness& h, const std::string& text, const std::string& field) {
  static int counter = 0;
  v1::SubmitRequest req;
  req.set_request_id("bad-" + std::to_string(++counter));
  req.set_case_text(text);
  v1::SubmitResponse resp;
  const auto status = h.jobs().Submit(h.context().get(), req, &resp);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_NE(status.error_message().find(field), std::string::npos)
      << "the message does not name " << field << ": " << status.error_message();
}

std::vector<v1::Job> all_jobs(ServiceHarness& h) {
  std::vector<v1::Job> out;
  v1::ListJobsRequest req;
  req.set_page_size(1000);
  while (true) {
    v1::ListJobsResponse resp;
    const auto status = h.jobs().ListJobs(h.context().get(), req, &resp);
    EXPECT_TRUE(status.ok()) << status.error_message();
    for (const auto& j : resp.jobs()) out.push_back(j);
    if (!status.ok() || resp.next_page_token().empty()) break;
    req.set_page_token(resp.next_page_token());
  }
  return out;
}

// Writes a result file into the attempt directory and returns its manifest entry.
v1::ResultFile write_result(const v1::ClaimResponse& c, const std::string& name,
                            const std::string& content) {
  fs::create_directories(fs::path(c.output_dir()) / fs::path(name).parent_path());
  std::ofstream(fs::path(c.output_dir()) / name, std::ios::binary) << content;
  v1::ResultFile f;
  f.set_name(name);
  f.set_size(static_cast<std::int64_t>(content.size()));
  service::Sha256 h;
  h.update(content);
  f.set_sha256(h.hex_digest());
  return f;
}

grpc::Status fetch(ServiceHarness& h, const std::string& job, const std::string& file,
                   std::string* data = nullptr) {
  v1::FetchResultRequest req;
  req.set_job_id(job);
  req.set_file(file);
  auto ctx = h.context();
  auto reader = h.jobs().FetchResult(ctx.get(), req);
  v1::FileChunk chunk;
  while (reader->Read(&chunk))
    if (data != nullptr) *data += chunk.data();
  return reader->Finish();
}

TEST(ServiceApi, HealthServiceReportsServing) {
  ServiceHarness h;
  h.start_server();
  auto stub = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(h.address(), grpc::InsecureChannelCredentials()));
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  ASSERT_TRUE(stub->Check(h.context().get(), req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

TEST(ServiceApi, ASecondServerOnTheSameDatabaseIsRefused) {
  ServiceHarness h;
  h.start_server();
  auto second = Process::spawn({SPHD_SERVER_BIN, "--address", "127.0.0.1:0", "--db",
                                h.dir() + "/sphd.db", "--results", h.dir() + "/results"},
                               h.dir() + "/second.log");
  EXPECT_EQ(second.wait(10s).value_or(-1), 1);
  EXPECT_NE(read_file(h.dir() + "/second.log").find("another sph-server"), std::string::npos)
      << read_file(h.dir() + "/second.log");
  EXPECT_TRUE(h.server().running());
}

TEST(ServiceApi, ANewDatabaseIsNotGivenAnotherDatabasesResults) {
  // Job ids restart at job-1 in a new database: pointed at the old results directory it
  // would write over the old job-1's files.
  ServiceHarness h;
  h.start_server();
  h.submit_text(small_case());
  h.claim();  // the attempt folder results/job-1/1
  auto fresh = Process::spawn({SPHD_SERVER_BIN, "--address", "127.0.0.1:0", "--db",
                               h.dir() + "/fresh.db", "--results", h.dir() + "/results"},
                              h.dir() + "/fresh.log");
  EXPECT_EQ(fresh.wait(10s).value_or(-1), 1);
  EXPECT_NE(read_file(h.dir() + "/fresh.log").find("belongs to another database"),
            std::string::npos)
      << read_file(h.dir() + "/fresh.log");
  EXPECT_TRUE(fs::exists(h.dir() + "/results/job-1/1"));
  // The database that wrote them starts again on them (a restart).
  h.server().kill_all();
  h.start_server();
  EXPECT_EQ(h.get_job("job-1").state(), v1::JOB_STATE_RUNNING);
}

TEST(ServiceApi, BadCasesAreRejectedNamingTheFieldAndNothingIsStored) {
  ServiceHarness h;
  h.start_server(ServerSettings().particle_limit(1000));
  const std::string ok = small_case();  // 432 particles
  expect_rejected(h, "name: \"x\"\ndimension: 2\ndx: [", "line 3");
  expect_rejected(h, ok + "\nvelocity_scale: 2\n", "velocity_scale");
  expect_rejected(h, std::regex_replace(ok, std::regex("dx: [0-9.]+"), "dx: -0.01"), "dx");
  expect_rejected(h, std::regex_replace(ok, std::regex("material: \"fluid\""), "material: \"oil\""),
                  "fluids[0].material");
  // dx / 10 in 2D: 100 times the particles of a case the server accepts.
  expect_rejected(h, std::regex_replace(ok, std::regex("dx: [0-9.]+"), "dx: 0.00333333333333333"),
                  "dx: case too large");
  v1::SubmitRequest no_id;
  no_id.set_case_text(ok);
  v1::SubmitResponse resp;
  const auto s = h.jobs().Submit(h.context().get(), no_id, &resp);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(s.error_message().find("request_id"), std::string::npos);
  EXPECT_TRUE(all_jobs(h).empty()) << "a rejected submission was stored";
  // The good case itself is accepted.
  EXPECT_EQ(h.submit_text(ok).state(), v1::JOB_STATE_QUEUED);
}

TEST(ServiceApi, ALargeCaseReachesItsPoolAndATooLargeOneIsRejectedNamingCaseText) {
  // One message limit on the server and on the clients' channels (common/message_limits.h):
  // a case the server accepts must also fit the Claim that hands it to a pool, or it would be
  // accepted and then never claimed. Large cases are inlined point sets: a fluid given as
  // `count` points.
  ServiceHarness h;
  h.start_server();
  auto with_points = [](int count) {
    std::string points;
    points.reserve(static_cast<std::size_t>(count) * 40);
    char buf[96];
    for (int i = 0; i < count; ++i) {
      std::snprintf(buf, sizeof buf, "points{x:%.9f y:%.9f}", 0.01 + 0.38 * (i % 1000) / 1000.0,
                    0.01 + 0.98 * (i / 1000) / (count / 1000 + 1.0));
      points += buf;
    }
    const std::string box = "shape { box { lo { x: 0 y: 0 } hi { x: 0.4 y: 1 } } }";
    std::string text = small_case();
    text.replace(text.find(box), box.size(), "shape { points { " + points + " } }");
    return text;
  };
  const v1::Job big = h.submit_text(with_points(350000));
  EXPECT_EQ(big.state(), v1::JOB_STATE_QUEUED);
  const v1::ClaimResponse c = h.claim();
  EXPECT_EQ(c.job_id(), big.id());
  std::printf("a case of 350000 points is %zu bytes as claimed\n", c.case_text().size());
  EXPECT_GT(c.case_text().size(), 20u << 20);
  expect_rejected(h, with_points(900000), "case_text: is 5");
  EXPECT_EQ(all_jobs(h).size(), 1u) << "the rejected case was stored";
}

TEST(ServiceApi, WrongOrMissingTokenIsUnauthenticatedOnEveryService) {
  ServiceHarness h;
  h.start_server(ServerSettings().with_token("s3cret-token"));
  EXPECT_EQ(h.submit_text(small_case()).id(), "job-1");  // the right token works

  for (const std::string token : {"", "wrong-token"}) {
    auto ctx = [&] {
      auto c = std::make_unique<grpc::ClientContext>();
      if (!token.empty()) c->AddMetadata("authorization", "Bearer " + token);
      return c;
    };
    v1::GetJobRequest get;
    get.set_job_id("job-1");
    v1::Job job;
    EXPECT_EQ(h.jobs().GetJob(ctx().get(), get, &job).error_code(),
              grpc::StatusCode::UNAUTHENTICATED);
    v1::SubmitRequest sub;
    sub.set_request_id("x");
    sub.set_case_text(small_case());
    v1::SubmitResponse sresp;
    EXPECT_EQ(h.jobs().Submit(ctx().get(), sub, &sresp).error_code(),
              grpc::StatusCode::UNAUTHENTICATED);
    v1::WatchJobRequest watch;
    watch.set_job_id("job-1");
    auto c = ctx();
    auto reader = h.jobs().WatchJob(c.get(), watch);
    v1::JobEvent e;
    EXPECT_FALSE(reader->Read(&e));
    EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::UNAUTHENTICATED);
    v1::ClaimRequest cl;
    cl.set_pool_id("p");
    cl.set_ranks(1);
    v1::ClaimResponse cresp;
    EXPECT_EQ(h.workers().Claim(ctx().get(), cl, &cresp).error_code(),
              grpc::StatusCode::UNAUTHENTICATED);
  }
  // sphctl maps it to its documented exit code.
  std::ofstream(h.dir() + "/wrong") << "wrong-token\n";
  const auto r = run_command(
      {SPHCTL_BIN, "--server", h.address(), "--token-file", h.dir() + "/wrong", "status", "job-1"},
      h.dir(), 30s);
  EXPECT_EQ(r.exit_code, 6) << r.err;
  EXPECT_EQ(all_jobs(h).size(), 1u);
}

TEST(ServiceApi, DuplicateSubmitWithOneRequestIdMakesOneJob) {
  ServiceHarness h;
  h.start_server();
  const auto a = h.submit_text(small_case(), "same-id");
  const auto b = h.submit_text(small_case(), "same-id");
  EXPECT_EQ(a.id(), b.id());
  EXPECT_EQ(all_jobs(h).size(), 1u);
  // Reusing the id for a different case is refused, not silently merged.
  v1::SubmitRequest req;
  req.set_request_id("same-id");
  req.set_case_text(with_end_time(small_case(), 0.25));
  v1::SubmitResponse resp;
  EXPECT_EQ(h.jobs().Submit(h.context().get(), req, &resp).error_code(),
            grpc::StatusCode::ALREADY_EXISTS);
  EXPECT_EQ(all_jobs(h).size(), 1u);
}

TEST(ServiceApi, FiveHundredConcurrentSubmitsStoreFiveHundredJobs) {
  ServiceHarness h;
  h.start_server();
  const std::string text = small_case();
  constexpr int kThreads = 8;
  constexpr int kJobs = 500;
  std::atomic<int> next{0}, failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&] {
      auto channel = grpc::CreateChannel(h.address(), grpc::InsecureChannelCredentials());
      auto stub = v1::JobService::NewStub(channel);
      for (int i = next++; i < kJobs; i = next++) {
        v1::SubmitRequest req;
        req.set_request_id("load-" + std::to_string(i));
        req.set_case_text(text);
        // Every request is sent twice, as a client retrying after a lost reply would.
        for (int copy = 0; copy < 2; ++copy) {
          v1::SubmitResponse resp;
          if (!stub->Submit(h.context(30s).get(), req, &resp).ok()) ++failures;
        }
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0);
  const auto jobs = all_jobs(h);
  std::set<std::string> ids, request_ids;
  for (const auto& j : jobs) {
    ids.insert(j.id());
    request_ids.insert(j.request_id());
  }
  EXPECT_EQ(jobs.size(), static_cast<size_t>(kJobs));
  EXPECT_EQ(ids.size(), static_cast<size_t>(kJobs));
  EXPECT_EQ(request_ids.size(), static_cast<size_t>(kJobs));
}

TEST(ServiceApi, StaleWorkerIsRefusedAndTheNextAttemptResumesFromItsCheckpoint) {
  ServiceHarness h;
  h.start_server(ServerSettings().lease(1));
  const auto job = h.submit_text(small_case());
  const auto c1 = h.claim("pool-1");
  ASSERT_EQ(c1.job_id(), job.id());
  fs::create_directories(c1.output_dir() + "/checkpoints");
  const std::string cp = c1.output_dir() + "/checkpoints/ckpt_000000000042.h5";
  std::ofstream(cp) << "checkpoint";

  v1::ReportRequest report;
  report.set_job_id(c1.job_id());
  report.set_attempt(c1.attempt());
  report.add_checkpoints()->set_path(cp);
  report.mutable_checkpoints(0)->set_step(42);
  v1::ReportResponse rr;
  ASSERT_TRUE(h.workers().Report(h.context().get(), report, &rr).ok());

  // A checkpoint outside the job's directory is refused.
  v1::ReportRequest outside = report;
  outside.mutable_checkpoints(0)->set_path("/etc/passwd");
  const auto so = h.workers().Report(h.context().get(), outside, &rr);
  EXPECT_EQ(so.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(so.error_message().find("checkpoints[0].path"), std::string::npos);

  // pool-1 goes silent; the lease (1 s) runs out and the job is queued again.
  ASSERT_TRUE(h.wait_for_state(job.id(), v1::JOB_STATE_QUEUED, 10s)) << h.logs();
  const auto c2 = h.claim("pool-2");
  EXPECT_EQ(c2.attempt(), 2);
  EXPECT_EQ(c2.resume_from(), cp);

  report.clear_checkpoints();
  const auto stale = h.workers().Report(h.context().get(), report, &rr);
  EXPECT_EQ(stale.error_code(), grpc::StatusCode::ABORTED) << stale.error_message();
  v1::FinishRequest fin;
  fin.set_job_id(c1.job_id());
  fin.set_attempt(c1.attempt());
  fin.set_outcome(v1::ATTEMPT_COMPLETED);
  v1::FinishResponse fr;
  EXPECT_EQ(h.workers().Finish(h.context().get(), fin, &fr).error_code(),
            grpc::StatusCode::ABORTED);
  EXPECT_EQ(h.get_job(job.id()).state(), v1::JOB_STATE_RUNNING);
}

TEST(ServiceApi, FetchServesOnlyTheResultManifest) {
  ServiceHarness h;
  h.start_server();
  const auto job = h.submit_text(small_case());
  const auto c = h.claim();
  const auto h5 = write_result(c, "result.h5", std::string(3 << 20, 'x') + "end");  // > 1 chunk
  const auto xmf = write_result(c, "result.xmf", "<Xdmf/>");
  write_result(c, "checkpoints/ckpt_1.h5", "not part of the result");
  std::ofstream(h.dir() + "/secret.txt") << "secret";

  v1::FinishRequest fin;
  fin.set_job_id(c.job_id());
  fin.set_attempt(c.attempt());
  fin.set_outcome(v1::ATTEMPT_COMPLETED);
  v1::FinishResponse fr;
  // A manifest naming a file outside the attempt directory is refused.
  *fin.add_files() = h5;
  fin.add_files()->set_name("../../../secret.txt");
  auto bad = h.workers().Finish(h.context().get(), fin, &fr);
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(bad.error_message().find("files[1].name"), std::string::npos) << bad.error_message();
  // So is a size that does not match the file.
  fin.clear_files();
  *fin.add_files() = xmf;
  fin.mutable_files(0)->set_size(99);
  EXPECT_EQ(h.workers().Finish(h.context().get(), fin, &fr).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  fin.clear_files();
  *fin.add_files() = h5;
  *fin.add_files() = xmf;
  ASSERT_TRUE(h.workers().Finish(h.context().get(), fin, &fr).ok());
  EXPECT_EQ(fr.state(), v1::JOB_STATE_SUCCEEDED);

  std::string data;
  ASSERT_TRUE(fetch(h, job.id(), "result.h5", &data).ok());
  EXPECT_EQ(data.size(), static_cast<size_t>(h5.size()));
  for (const std::string name : {"checkpoints/ckpt_1.h5", "../../secret.txt", "/etc/passwd",
                                 "result.h5/..", "./result.h5"}) {
    const auto s = fetch(h, job.id(), name);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND) << name << ": " << s.error_message();
  }
  EXPECT_EQ(fetch(h, "job-99", "result.h5").error_code(), grpc::StatusCode::NOT_FOUND);

  // sphctl fetch verifies what it downloads.
  const auto r = h.sphctl({"fetch", job.id(), "-o", h.dir() + "/fetched"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(fs::file_size(h.dir() + "/fetched/result.h5"), static_cast<uintmax_t>(h5.size()));
  const auto outside = h.sphctl({"fetch", job.id(), "--file", "checkpoints/ckpt_1.h5"});
  EXPECT_EQ(outside.exit_code, 4) << outside.err;
}

TEST(ServiceApi, DeletingAFinishedJobsFilesFreesItsDiskAndKeepsItsRecord) {
  ServiceHarness h;
  h.start_server();
  const auto job = h.submit_text(small_case());
  const auto c = h.claim();
  const auto h5 = write_result(c, "result.h5", std::string(100000, 'x'));
  const auto xmf = write_result(c, "result.xmf", "<Xdmf/>");
  write_result(c, "checkpoints/ckpt_1.h5", std::string(5000, 'c'));
  const fs::path job_dir = fs::path(c.output_dir()).parent_path();

  // Not while it runs: its pool is writing there.
  const auto running = h.sphctl({"delete", job.id()});
  EXPECT_EQ(running.exit_code, 8) << running.err;
  EXPECT_NE(running.err.find("cancel it first"), std::string::npos) << running.err;
  EXPECT_TRUE(fs::exists(fs::path(c.output_dir()) / "result.h5"));

  v1::FinishRequest fin;
  fin.set_job_id(c.job_id());
  fin.set_attempt(c.attempt());
  fin.set_outcome(v1::ATTEMPT_COMPLETED);
  *fin.add_files() = h5;
  *fin.add_files() = xmf;
  v1::FinishResponse fr;
  ASSERT_TRUE(h.workers().Finish(h.context().get(), fin, &fr).ok());
  ASSERT_TRUE(fetch(h, job.id(), "result.h5").ok());

  const auto deleted = h.sphctl({"delete", job.id()});
  EXPECT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_NE(deleted.out.find("deleted its files (102.5 KiB, 1 attempt)"), std::string::npos)
      << deleted.out;
  EXPECT_FALSE(fs::exists(job_dir));
  const v1::Job after = h.get_job(job.id());
  EXPECT_EQ(after.state(), v1::JOB_STATE_SUCCEEDED);
  EXPECT_GT(after.files_deleted_unix_ms(), 0);
  EXPECT_EQ(after.files_deleted_bytes(), h5.size() + xmf.size() + 5000);
  EXPECT_EQ(after.attempts_size(), 1);
  EXPECT_EQ(after.result().files_size(), 2);  // what there was, for the record

  const auto gone = fetch(h, job.id(), "result.h5");
  EXPECT_EQ(gone.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(gone.error_message().find("deleted"), std::string::npos) << gone.error_message();
  EXPECT_EQ(h.sphctl({"fetch", job.id(), "-o", h.dir() + "/fetched"}).exit_code, 8);
  const auto status = h.sphctl({"status", job.id()});
  EXPECT_NE(status.out.find("files:      deleted"), std::string::npos) << status.out;

  // Idempotent, and the first call's record stays.
  const auto again = h.sphctl({"delete", job.id(), "--json"});
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("\"deleted_now\":false"), std::string::npos) << again.out;
  EXPECT_EQ(h.get_job(job.id()).files_deleted_unix_ms(), after.files_deleted_unix_ms());
  EXPECT_NE(h.sphctl({"delete", job.id()}).out.find("nothing of them is left"), std::string::npos);

  EXPECT_EQ(h.sphctl({"delete", "job-99"}).exit_code, 4);
  EXPECT_EQ(h.sphctl({"delete", "nonsense"}).exit_code, 3);  // INVALID_ARGUMENT
  // A queued job keeps what a resubmission would need, so it is refused too.
  const auto queued = h.submit_text(small_case());
  v1::DeleteJobFilesRequest req;
  req.set_job_id(queued.id());
  v1::DeleteJobFilesResponse resp;
  EXPECT_EQ(h.jobs().DeleteJobFiles(h.context().get(), req, &resp).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
}

TEST(ServiceApi, WatchResumesFromASequenceAndEndsWithTheJob) {
  ServiceHarness h;
  h.start_server();
  const auto job = h.submit_text(small_case());
  const auto c = h.claim();
  // A watcher that joins now sees QUEUED and RUNNING, then what follows live.
  v1::WatchJobRequest req;
  req.set_job_id(job.id());
  auto ctx = h.context(30s);
  auto reader = h.jobs().WatchJob(ctx.get(), req);
  v1::JobEvent e;
  ASSERT_TRUE(reader->Read(&e));
  EXPECT_EQ(e.sequence(), 1);
  ASSERT_TRUE(reader->Read(&e));
  EXPECT_EQ(e.state_change().state(), v1::JOB_STATE_RUNNING);

  v1::ReportRequest report;
  report.set_job_id(c.job_id());
  report.set_attempt(c.attempt());
  report.mutable_progress()->set_step(7);
  v1::ReportResponse rr;
  ASSERT_TRUE(h.workers().Report(h.context().get(), report, &rr).ok());
  ASSERT_TRUE(reader->Read(&e));
  EXPECT_EQ(e.sequence(), 3);
  EXPECT_EQ(e.progress().step(), 7);

  v1::FinishRequest fin;
  fin.set_job_id(c.job_id());
  fin.set_attempt(c.attempt());
  fin.set_outcome(v1::ATTEMPT_FAILED);
  fin.set_message("density deviation at particle 12");
  v1::FinishResponse fr;
  ASSERT_TRUE(h.workers().Finish(h.context().get(), fin, &fr).ok());
  ASSERT_TRUE(reader->Read(&e));
  EXPECT_EQ(e.state_change().state(), v1::JOB_STATE_FAILED);
  EXPECT_EQ(e.state_change().reason(), "density deviation at particle 12");
  EXPECT_FALSE(reader->Read(&e)) << "the stream did not end with the job";
  EXPECT_TRUE(reader->Finish().ok());

  // Resuming after event 2 replays exactly the rest.
  req.set_after_sequence(2);
  auto ctx2 = h.context();
  auto resumed = h.jobs().WatchJob(ctx2.get(), req);
  std::vector<std::int64_t> seqs;
  while (resumed->Read(&e)) seqs.push_back(e.sequence());
  EXPECT_TRUE(resumed->Finish().ok());
  EXPECT_EQ(seqs, (std::vector<std::int64_t>{3, 4}));
  EXPECT_EQ(h.sphctl({"watch", job.id()}).exit_code, 10);  // FAILED
}

TEST(ServiceApi, SigtermEndsOpenStreamsAndLongPollsPromptly) {
  ServiceHarness h;
  // A long grace period: ending well before it shows the streams were ended, not cut off.
  h.start_server(ServerSettings().grace(30));
  const auto job = h.submit_text(small_case());
  h.claim();  // the job runs: a watcher waits for more
  std::atomic<int> watch_code{-1}, claim_code{-1};
  std::thread watcher([&] {
    v1::WatchJobRequest req;
    req.set_job_id(job.id());
    auto ctx = h.context(60s);
    auto reader = h.jobs().WatchJob(ctx.get(), req);
    v1::JobEvent e;
    while (reader->Read(&e)) {
    }
    watch_code = static_cast<int>(reader->Finish().error_code());
  });
  std::thread poller([&] {
    v1::ClaimRequest req;
    req.set_pool_id("idle-pool");
    req.set_ranks(1);
    req.set_wait_seconds(20);
    v1::ClaimResponse resp;
    claim_code = static_cast<int>(h.workers().Claim(h.context(60s).get(), req, &resp).error_code());
  });
  std::this_thread::sleep_for(500ms);
  const auto t0 = std::chrono::steady_clock::now();
  h.server().signal(SIGTERM);
  const auto code = h.server().wait(40s);
  const auto took = std::chrono::steady_clock::now() - t0;
  watcher.join();
  poller.join();
  ASSERT_TRUE(code.has_value()) << "sph-server did not exit after SIGTERM\n" << h.logs();
  EXPECT_EQ(*code, 0) << h.logs();
  EXPECT_LT(took, 15s) << "shutdown waited for its grace period instead of ending streams";
  EXPECT_EQ(watch_code.load(), static_cast<int>(grpc::StatusCode::UNAVAILABLE));
  EXPECT_EQ(claim_code.load(), static_cast<int>(grpc::StatusCode::OK));
}

TEST(ServiceApi, ClaimWakesUpWhenAJobIsSubmitted) {
  ServiceHarness h;
  h.start_server();
  std::string claimed;
  std::thread poller([&] { claimed = h.claim().job_id(); });
  std::this_thread::sleep_for(300ms);
  const auto t0 = std::chrono::steady_clock::now();
  const auto job = h.submit_text(small_case());
  poller.join();
  EXPECT_EQ(claimed, job.id());
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
}

}  // namespace
}  // namespace sph::testing
