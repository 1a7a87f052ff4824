// sph-server against requests an outside client could send, not only what sphctl sends:
// malformed bytes, every spelling of a job id, paths that point elsewhere, texts that would
// come back in every listing, health by service name. A real server on loopback; the test
// plays client and pool.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/security/credentials.h>

#include "grpc/health/v1/health.grpc.pb.h"
#include "harness/service_harness.h"
#include "sph/v1/case.pb.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;

std::string small_case() {
  return read_test_case("channel_2d.textproto");
}

// Sends `bytes` as the request of `method` ("/sph.v1.JobService/Submit") and returns the
// status; for a server-streaming method the stream is read to its end.
grpc::Status call_raw(ServiceHarness& h, const std::string& method, const std::string& bytes) {
  auto channel = grpc::CreateChannel(h.address(), grpc::InsecureChannelCredentials());
  grpc::GenericStub stub(channel);
  grpc::Slice slice(bytes);
  grpc::ByteBuffer request(&slice, 1);
  grpc::ByteBuffer response;
  auto ctx = h.context();
  std::promise<grpc::Status> done;
  stub.UnaryCall(ctx.get(), method, grpc::StubOptions(), &request, &response,
                 [&](grpc::Status s) { done.set_value(std::move(s)); });
  return done.get_future().get();
}

TEST(ServiceHardening, MalformedRequestBytesAreInvalidArgumentNamingTheMessage) {
  ServiceHarness h;
  h.start_server();
  // A field header that announces 100 bytes of a length-delimited field and ends at once.
  const std::string truncated("\x12\x64xyz", 5);
  // Nested groups far past protobuf's recursion limit (field 1, start-group tag 0x0b).
  const std::string deep(5000, '\x0b');
  struct Probe {
    const char* method;
    const char* type;
  };
  for (const Probe& p : {Probe{"/sph.v1.JobService/Submit", "sph.v1.SubmitRequest"},
                         Probe{"/sph.v1.JobService/GetJob", "sph.v1.GetJobRequest"},
                         Probe{"/sph.v1.JobService/CancelJob", "sph.v1.CancelJobRequest"},
                         Probe{"/sph.v1.WorkerService/Finish", "sph.v1.FinishRequest"},
                         Probe{"/sph.v1.WorkerService/Report", "sph.v1.ReportRequest"}}) {
    for (const std::string& bytes : {truncated, deep}) {
      const auto status = call_raw(h, p.method, bytes);
      std::printf("%s with %zu malformed bytes: %d %s\n", p.method, bytes.size(),
                  static_cast<int>(status.error_code()), status.error_message().c_str());
      EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << p.method;
      EXPECT_NE(status.error_message().find(p.type), std::string::npos)
          << p.method << ": " << status.error_message();
    }
  }
  // The streaming methods answer the same way; their calls go through a stub that reads.
  for (const char* method : {"/sph.v1.JobService/WatchJob", "/sph.v1.JobService/FetchResult"}) {
    auto channel = grpc::CreateChannel(h.address(), grpc::InsecureChannelCredentials());
    grpc::GenericStub stub(channel);
    grpc::CompletionQueue cq;
    auto ctx = h.context();
    auto call = stub.PrepareCall(ctx.get(), method, &cq);
    void* tag = nullptr;
    bool ok = false;
    call->StartCall(reinterpret_cast<void*>(1));
    ASSERT_TRUE(cq.Next(&tag, &ok));
    grpc::Slice slice(truncated);
    grpc::ByteBuffer request(&slice, 1);
    call->WriteLast(request, grpc::WriteOptions(), reinterpret_cast<void*>(2));
    ASSERT_TRUE(cq.Next(&tag, &ok));
    grpc::ByteBuffer response;
    call->Read(&response, reinterpret_cast<void*>(3));
    ASSERT_TRUE(cq.Next(&tag, &ok));
    EXPECT_FALSE(ok) << method << " sent a message for malformed bytes";
    grpc::Status status;
    call->Finish(&status, reinterpret_cast<void*>(4));
    ASSERT_TRUE(cq.Next(&tag, &ok));
    std::printf("%s with malformed bytes: %d %s\n", method, static_cast<int>(status.error_code()),
                status.error_message().c_str());
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << method;
    EXPECT_NE(status.error_message().find("Request"), std::string::npos) << method;
    cq.Shutdown();
    while (cq.Next(&tag, &ok)) {
    }
  }
  EXPECT_TRUE(h.server().running());
  // Well-formed requests still work.
  EXPECT_EQ(h.submit_text(small_case()).id(), "job-1");
}

TEST(ServiceHardening, HealthAnswersForTheServerAndEachService) {
  ServiceHarness h;
  h.start_server();
  auto stub = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(h.address(), grpc::InsecureChannelCredentials()));
  for (const char* service : {"", "sph.v1.JobService", "sph.v1.WorkerService"}) {
    grpc::health::v1::HealthCheckRequest req;
    req.set_service(service);
    grpc::health::v1::HealthCheckResponse resp;
    const auto status = stub->Check(h.context().get(), req, &resp);
    ASSERT_TRUE(status.ok()) << "'" << service << "': " << status.error_message();
    EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING) << service;
  }
  grpc::health::v1::HealthCheckRequest req;
  req.set_service("sph.v1.NoSuchService");
  grpc::health::v1::HealthCheckResponse resp;
  EXPECT_EQ(stub->Check(h.context().get(), req, &resp).error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST(ServiceHardening, AJobHasOneSpellingOfItsId) {
  ServiceHarness h;
  h.start_server();
  for (int i = 0; i < 8; ++i) h.submit_text(small_case());
  EXPECT_EQ(h.get_job("job-8").id(), "job-8");
  for (const char* other : {"8", "job-08", "job-+8", "job- 8", "JOB-8", "job-8 ", "job-8x", "job-0",
                            "job--8", "job-99999999999999999999", "/etc", "../job-8"}) {
    v1::GetJobRequest req;
    req.set_job_id(other);
    v1::Job job;
    const auto status = h.jobs().GetJob(h.context().get(), req, &job);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << "'" << other << "'";
    EXPECT_NE(status.error_message().find("job_id"), std::string::npos) << status.error_message();
  }
}

TEST(ServiceHardening, WorkerCallsResolveTheJobBeforeAnyPath) {
  ServiceHarness h;
  h.start_server();
  h.submit_text(small_case());
  const auto c = h.claim("hardening-pool", 1);
  ASSERT_EQ(c.job_id(), "job-1");
  // A file outside the results directory, of a size a probe would look for.
  const fs::path outside = fs::path(h.dir()) / "outside";
  fs::create_directories(outside / "1");
  std::ofstream(outside / "1" / "secret.txt") << "12345";
  const auto finish_with = [&](const std::string& job_id, const std::string& name,
                               std::int64_t size) {
    v1::FinishRequest req;
    req.set_job_id(job_id);
    req.set_attempt(1);
    req.set_outcome(v1::ATTEMPT_COMPLETED);
    auto* f = req.add_files();
    f->set_name(name);
    f->set_size(size);
    f->set_sha256(std::string(64, 'a'));
    v1::FinishResponse resp;
    return h.workers().Finish(h.context().get(), req, &resp);
  };
  // The request's id is not a path: an absolute one, or another spelling of job-1.
  for (const std::string& id : {outside.string(), std::string("1"), std::string("job-01")}) {
    const auto status = finish_with(id, "secret.txt", 5);
    std::printf("Finish as '%s': %d %s\n", id.c_str(), static_cast<int>(status.error_code()),
                status.error_message().c_str());
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << id;
    EXPECT_EQ(status.error_message().find("bytes"), std::string::npos)
        << "an answer about a file outside the job: " << status.error_message();
  }
  // A job that does not exist is NOT_FOUND before its folder is looked at.
  EXPECT_EQ(finish_with("job-2", "secret.txt", 5).error_code(), grpc::StatusCode::NOT_FOUND);
  // A symbolic link inside the attempt folder that leads outside is refused by name only.
  fs::create_symlink(outside / "1" / "secret.txt", fs::path(c.output_dir()) / "link.txt");
  const auto linked = finish_with("job-1", "link.txt", 5);
  EXPECT_EQ(linked.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(linked.error_message().find("outside"), std::string::npos) << linked.error_message();
  EXPECT_EQ(linked.error_message().find(outside.string()), std::string::npos)
      << linked.error_message();

  // Checkpoints: only below RESULTS/job-1/, after resolving links, and not under another
  // spelling of the id.
  const fs::path results = fs::path(c.output_dir()).parent_path().parent_path();
  fs::create_directories(results / "1" / "checkpoints");
  fs::create_symlink(outside, fs::path(c.output_dir()) / "escape");
  for (const fs::path& p : {results / "1" / "checkpoints" / "ckpt_1.h5",
                            fs::path(c.output_dir()) / "escape" / "ckpt_1.h5",
                            fs::path(c.output_dir()) / ".." / ".." / "job-2" / "ckpt_1.h5"}) {
    v1::ReportRequest req;
    req.set_job_id("job-1");
    req.set_attempt(1);
    auto* cp = req.add_checkpoints();
    cp->set_path(p.string());
    cp->set_step(1);
    v1::ReportResponse resp;
    const auto status = h.workers().Report(h.context().get(), req, &resp);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << p;
  }
  v1::ReportRequest good;
  good.set_job_id("job-1");
  good.set_attempt(1);
  good.add_checkpoints()->set_path((fs::path(c.output_dir()) / "checkpoints" / "c.h5").string());
  v1::ReportResponse resp;
  EXPECT_TRUE(h.workers().Report(h.context().get(), good, &resp).ok());
}

TEST(ServiceHardening, CancelReasonsAreBounded) {
  ServiceHarness h;
  h.start_server();
  h.submit_text(small_case());
  v1::CancelJobRequest req;
  req.set_job_id("job-1");
  req.set_reason(std::string(10 << 20, 'r'));
  v1::Job job;
  const auto status = h.jobs().CancelJob(h.context().get(), req, &job);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("reason"), std::string::npos) << status.error_message();
  EXPECT_NE(status.error_message().find("1024"), std::string::npos) << status.error_message();
  EXPECT_EQ(h.get_job("job-1").state(), v1::JOB_STATE_QUEUED);
  req.set_reason(std::string(1024, 'r'));
  EXPECT_TRUE(h.jobs().CancelJob(h.context().get(), req, &job).ok());
}

TEST(ServiceHardening, StoredCaseTextIsBoundedByWhatWasSent) {
  // 31 chains of unions 31 deep under one union (depth 32, 962 shapes: inside the limits),
  // written compactly: indented one field a line, its canonical text is about 20 times the
  // request.
  const std::string box = "box{lo{x:0 y:0}hi{x:0.4 y:1}}";
  std::string chain;
  for (int i = 0; i < 30; ++i) chain += "union{shapes{";
  chain += box;
  for (int i = 0; i < 30; ++i) chain += "}}";
  std::string shape = "union{";
  for (int i = 0; i < 31; ++i) shape += "shapes{" + chain + "}";
  shape += "}";
  std::string text = small_case();
  const std::string original = "shape { box { lo { x: 0 y: 0 } hi { x: 0.4 y: 1 } } }";
  text.replace(text.find(original), original.size(), "shape{" + shape + "}");

  ServiceHarness h;
  h.start_server();
  const v1::Job job = h.submit_text(text);
  v1::GetJobRequest req;
  req.set_job_id(job.id());
  req.set_include_case(true);
  v1::Job stored;
  ASSERT_TRUE(h.jobs().GetJob(h.context().get(), req, &stored).ok());
  const std::size_t bound = 4 * text.size() + (64 << 10);
  std::printf("sent %zu bytes, stored %zu (bound %zu)\n", text.size(), stored.case_text().size(),
              bound);
  EXPECT_LE(stored.case_text().size(), bound);
  v1::Case sent_case, stored_case;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &sent_case));
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(stored.case_text(), &stored_case));
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(sent_case, stored_case));
  // A resubmit of the same text is the same job.
  EXPECT_EQ(h.submit_text(text, job.request_id()).id(), job.id());
}

TEST(ServiceHardening, QueueLimitsRefuseWithTheNumbersAndStoreNothing) {
  ServiceHarness h;
  h.start_server(ServerSettings().flag("--max-queued-jobs", "2"));
  const v1::Job first = h.submit_text(small_case(), "q-1");
  h.submit_text(small_case(), "q-2");
  v1::SubmitRequest req;
  req.set_request_id("q-3");
  req.set_case_text(small_case());
  v1::SubmitResponse resp;
  const auto full = h.jobs().Submit(h.context().get(), req, &resp);
  std::printf("third submit: %d %s\n", static_cast<int>(full.error_code()),
              full.error_message().c_str());
  EXPECT_EQ(full.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(full.error_message().find("2 jobs are queued or running; the limit is 2 "
                                      "(--max-queued-jobs)"),
            std::string::npos)
      << full.error_message();
  // A retry of a stored submit is still answered, and nothing of the refused one is stored.
  EXPECT_EQ(h.submit_text(small_case(), "q-1").id(), first.id());
  v1::GetJobRequest get;
  get.set_job_id("job-3");
  v1::Job job;
  EXPECT_EQ(h.jobs().GetJob(h.context().get(), get, &job).error_code(),
            grpc::StatusCode::NOT_FOUND);
  // A finished job leaves the queue: the next submit is taken.
  v1::CancelJobRequest cancel;
  cancel.set_job_id(first.id());
  ASSERT_TRUE(h.jobs().CancelJob(h.context().get(), cancel, &job).ok());
  EXPECT_EQ(h.submit_text(small_case(), "q-3").id(), "job-3");
}

TEST(ServiceHardening, ListingWorksWhateverTheStoredJobsHold) {
  // Jobs stored before names were bounded: ten with a 10 MiB name each, written into the
  // database beside the running server (as an older server would have stored them).
  ServiceHarness h;
  h.start_server();
  for (int i = 0; i < 10; ++i) h.submit_text(small_case());
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((h.dir() + "/sphd.db").c_str(), &db), SQLITE_OK);
  sqlite3_busy_timeout(db, 5000);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "UPDATE jobs SET name = ?1", -1, &st, nullptr), SQLITE_OK);
  // A multi-byte character straddles the listing's cut.
  std::string huge = std::string(1023, 'n') + "\xc3\xa9" + std::string(10 << 20, 'n');
  sqlite3_bind_text(st, 1, huge.data(), static_cast<int>(huge.size()), SQLITE_TRANSIENT);
  ASSERT_EQ(sqlite3_step(st), SQLITE_DONE);
  sqlite3_finalize(st);
  sqlite3_close(db);

  v1::ListJobsRequest req;
  req.set_page_size(1000);
  int listed = 0;
  std::size_t largest_page = 0;
  while (true) {
    v1::ListJobsResponse resp;
    const auto status = h.jobs().ListJobs(h.context().get(), req, &resp);
    ASSERT_TRUE(status.ok()) << status.error_message();
    largest_page = std::max(largest_page, resp.ByteSizeLong());
    for (const auto& j : resp.jobs()) {
      EXPECT_LE(j.name().size(), 1024u + 3u);
      ++listed;
    }
    if (resp.next_page_token().empty()) break;
    req.set_page_token(resp.next_page_token());
  }
  std::printf("listed %d jobs with 10 MiB names, largest page %zu bytes\n", listed, largest_page);
  EXPECT_EQ(listed, 10);
  EXPECT_LE(largest_page, std::size_t{4} << 20);
  const auto list = h.sphctl({"list"});
  EXPECT_EQ(list.exit_code, 0) << list.err;
}

}  // namespace
}  // namespace sph::testing
