// Fuzz target: sequences of calls to both gRPC services of a real server hosted in this
// process (server/service_host.h: the same assembly as sph-server, with its SQLite database
// and results folder in a temporary directory), over a loopback channel, so every request
// goes through gRPC's parsing, the interceptors and the handlers. An input is text, a call a
// block:
//
//   @Submit
//   request_id: "a" case_text: "name: \"x\" ..."
//   @Claim
//   pool_id: "p" ranks: 1
//   @Raw /sph.v1.JobService/GetJob
//   (the rest of the block is sent as the request's bytes)
//
// Findings: a crash or sanitizer report in the server, or a status no request of a client
// should be able to cause: INTERNAL, UNKNOWN, DATA_LOSS, UNAVAILABLE (the server is not
// shutting down), UNIMPLEMENTED for a method the server has.
#include <google/protobuf/stubs/logging.h>
#include <google/protobuf/text_format.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/security/credentials.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "common/log.h"
#include "server/config.h"
#include "server/service_host.h"
#include "sph/v1/case.pb.h"
#include "sph/v1/service.grpc.pb.h"
#include "tests/fuzz/fuzz_target.h"
#include "tests/fuzz/proto_mutator.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using google::protobuf::Message;
using sph::fuzz::fail;

constexpr std::size_t kMaxCalls = 16;

struct Call {
  std::string method;  // "Submit", ..., or "Raw"
  std::string raw_method;
  std::string body;
};

std::vector<Call> split_calls(const std::string& input) {
  std::vector<Call> calls;
  std::size_t pos = 0;
  while (pos < input.size() && calls.size() < kMaxCalls) {
    const std::size_t line_end = input.find('\n', pos);
    const std::string line =
        input.substr(pos, line_end == std::string::npos ? std::string::npos : line_end - pos);
    pos = line_end == std::string::npos ? input.size() : line_end + 1;
    if (!line.empty() && line[0] == '@') {
      Call c;
      const std::size_t space = line.find(' ');
      c.method = line.substr(1, space == std::string::npos ? std::string::npos : space - 1);
      if (space != std::string::npos) c.raw_method = line.substr(space + 1);
      calls.push_back(std::move(c));
    } else if (!calls.empty()) {
      calls.back().body += line + "\n";
    }
  }
  return calls;
}

std::string join_calls(const std::vector<Call>& calls) {
  std::string out;
  for (const auto& c : calls) {
    out += "@" + c.method + (c.raw_method.empty() ? "" : " " + c.raw_method) + "\n" + c.body;
    if (!c.body.empty() && c.body.back() != '\n') out += "\n";
  }
  return out;
}

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names = {
      "Submit",         "GetJob",     "ListJobs", "WatchJob", "CancelJob", "FetchResult",
      "DeleteJobFiles", "GetJobLogs", "Claim",    "Report",   "Finish",    "Raw"};
  return names;
}

// A fresh request message of the method, nullptr for Raw and unknown names.
std::unique_ptr<Message> request_of(const std::string& method) {
  using namespace sph::v1;
  if (method == "Submit") return std::make_unique<SubmitRequest>();
  if (method == "GetJob") return std::make_unique<GetJobRequest>();
  if (method == "ListJobs") return std::make_unique<ListJobsRequest>();
  if (method == "WatchJob") return std::make_unique<WatchJobRequest>();
  if (method == "CancelJob") return std::make_unique<CancelJobRequest>();
  if (method == "FetchResult") return std::make_unique<FetchResultRequest>();
  if (method == "DeleteJobFiles") return std::make_unique<DeleteJobFilesRequest>();
  if (method == "GetJobLogs") return std::make_unique<GetJobLogsRequest>();
  if (method == "Claim") return std::make_unique<ClaimRequest>();
  if (method == "Report") return std::make_unique<ReportRequest>();
  if (method == "Finish") return std::make_unique<FinishRequest>();
  return nullptr;
}

bool parse_text(const std::string& text, Message& m) {
  google::protobuf::TextFormat::Parser parser;
  parser.SetRecursionLimit(100);
  return parser.ParseFromString(text, &m);
}

struct Server {
  fs::path dir;
  std::unique_ptr<sph::server::ServiceHost> host;
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<sph::v1::JobService::Stub> jobs;
  std::unique_ptr<sph::v1::WorkerService::Stub> workers;
};

Server* g_server = nullptr;

void check_status(const std::string& method, const grpc::Status& s) {
  switch (s.error_code()) {
    case grpc::StatusCode::INTERNAL:
    case grpc::StatusCode::UNKNOWN:
    case grpc::StatusCode::DATA_LOSS:
    case grpc::StatusCode::UNAVAILABLE:
      fail(("a client's request made " + method + " answer " +
            std::to_string(static_cast<int>(s.error_code())))
               .c_str(),
           s.error_message());
    case grpc::StatusCode::UNIMPLEMENTED:
      if (method != "Raw") fail("UNIMPLEMENTED", method + ": " + s.error_message());
      break;
    default:
      break;
  }
}

std::unique_ptr<grpc::ClientContext> context(std::chrono::milliseconds timeout) {
  auto c = std::make_unique<grpc::ClientContext>();
  c->set_deadline(std::chrono::system_clock::now() + timeout);
  return c;
}

// Reads a stream to its end (or a bounded number of messages) and returns its status.
template <typename Reader, typename Item>
grpc::Status drain(grpc::ClientContext& ctx, Reader& reader, Item& item) {
  for (int n = 0; n < 64 && reader->Read(&item); ++n) {
  }
  ctx.TryCancel();
  while (reader->Read(&item)) {
  }
  return reader->Finish();
}

grpc::Status run_call(Server& s, const Call& call) {
  using namespace sph::v1;
  if (call.method == "Raw") {
    grpc::GenericStub stub(s.channel);
    grpc::Slice slice(call.body);
    grpc::ByteBuffer request(&slice, 1);
    grpc::ByteBuffer response;
    auto ctx = context(2s);
    std::promise<grpc::Status> done;
    stub.UnaryCall(ctx.get(), call.raw_method, grpc::StubOptions(), &request, &response,
                   [&](grpc::Status st) { done.set_value(std::move(st)); });
    return done.get_future().get();
  }
  auto request = request_of(call.method);
  if (request == nullptr || !parse_text(call.body, *request)) return grpc::Status::OK;
  auto ctx = context(5s);
  if (call.method == "Submit") {
    SubmitResponse r;
    return s.jobs->Submit(ctx.get(), static_cast<SubmitRequest&>(*request), &r);
  }
  if (call.method == "GetJob") {
    Job r;
    return s.jobs->GetJob(ctx.get(), static_cast<GetJobRequest&>(*request), &r);
  }
  if (call.method == "ListJobs") {
    ListJobsResponse r;
    return s.jobs->ListJobs(ctx.get(), static_cast<ListJobsRequest&>(*request), &r);
  }
  if (call.method == "CancelJob") {
    Job r;
    return s.jobs->CancelJob(ctx.get(), static_cast<CancelJobRequest&>(*request), &r);
  }
  if (call.method == "DeleteJobFiles") {
    DeleteJobFilesResponse r;
    return s.jobs->DeleteJobFiles(ctx.get(), static_cast<DeleteJobFilesRequest&>(*request), &r);
  }
  if (call.method == "GetJobLogs") {
    GetJobLogsResponse r;
    return s.jobs->GetJobLogs(ctx.get(), static_cast<GetJobLogsRequest&>(*request), &r);
  }
  if (call.method == "WatchJob") {
    auto c = context(200ms);
    auto reader = s.jobs->WatchJob(c.get(), static_cast<WatchJobRequest&>(*request));
    JobEvent e;
    return drain(*c, reader, e);
  }
  if (call.method == "FetchResult") {
    auto c = context(200ms);
    auto reader = s.jobs->FetchResult(c.get(), static_cast<FetchResultRequest&>(*request));
    FileChunk chunk;
    return drain(*c, reader, chunk);
  }
  if (call.method == "Claim") {
    // A long poll on an empty queue would only make the fuzzer slow.
    auto& claim = static_cast<ClaimRequest&>(*request);
    if (claim.wait_seconds() > 0.05) claim.set_wait_seconds(0.05);
    ClaimResponse r;
    return s.workers->Claim(ctx.get(), claim, &r);
  }
  if (call.method == "Report") {
    ReportResponse r;
    return s.workers->Report(ctx.get(), static_cast<ReportRequest&>(*request), &r);
  }
  FinishResponse r;
  return s.workers->Finish(ctx.get(), static_cast<FinishRequest&>(*request), &r);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  sph::service::set_log_enabled(false);
  google::protobuf::SetLogHandler(nullptr);  // parse errors of mutated text are expected
  // tmpfs when there is one: the store commits durably, and fsync there costs nothing.
  const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
  std::string templ = (base / "sphd-rpc-fuzz-XXXXXX").string();
  if (mkdtemp(templ.data()) == nullptr) fail("mkdtemp", templ);
  static Server server;
  server.dir = templ;
  sph::server::ServerConfig config;
  config.address = "127.0.0.1:0";
  config.db_path = (server.dir / "sphd.db").string();
  config.results_dir = (server.dir / "results").string();
  config.lease_seconds = 30;
  server.host = std::make_unique<sph::server::ServiceHost>(config);
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  server.channel = grpc::CreateCustomChannel(server.host->bound_address(),
                                             grpc::InsecureChannelCredentials(), args);
  server.jobs = sph::v1::JobService::NewStub(server.channel);
  server.workers = sph::v1::WorkerService::NewStub(server.channel);
  g_server = &server;
  // The server goes before the process does: its threads joined (and their per-thread state
  // freed) before LeakSanitizer looks at what is left.
  std::atexit([] {
    std::error_code ec;
    g_server->jobs.reset();
    g_server->workers.reset();
    g_server->channel.reset();
    g_server->host.reset();
    fs::remove_all(g_server->dir, ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  for (const Call& call : split_calls(input)) check_status(call.method, run_call(*g_server, call));
  return 0;
}

// One structural change: a call's request mutated (for Submit, often the case inside its
// text), a call copied or dropped, or a call sent to another method; bytes otherwise.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t max_size, unsigned int seed) {
  std::mt19937_64 rng(seed);
  auto calls = split_calls(std::string(reinterpret_cast<const char*>(data), size));
  if (calls.empty() || rng() % 5 == 0) return LLVMFuzzerMutate(data, size, max_size);
  const std::size_t i = rng() % calls.size();
  switch (rng() % 6) {
    case 0:
      if (calls.size() < kMaxCalls) calls.insert(calls.begin() + static_cast<long>(i), calls[i]);
      break;
    case 1:
      if (calls.size() > 1) calls.erase(calls.begin() + static_cast<long>(i));
      break;
    case 2:
      calls[i].method = method_names()[rng() % (method_names().size() - 1)];
      break;
    default: {
      auto request = request_of(calls[i].method);
      if (request == nullptr || !parse_text(calls[i].body, *request))
        return LLVMFuzzerMutate(data, size, max_size);
      auto* submit = dynamic_cast<sph::v1::SubmitRequest*>(request.get());
      sph::v1::Case c;
      if (submit != nullptr && rng() % 2 == 0 && parse_text(submit->case_text(), c)) {
        sph::fuzz::mutate_message(c, rng);
        std::string text;
        google::protobuf::TextFormat::PrintToString(c, &text);
        submit->set_case_text(text);
      } else {
        sph::fuzz::mutate_message(*request, rng);
      }
      google::protobuf::TextFormat::Printer printer;
      printer.SetSingleLineMode(true);
      calls[i].body.clear();
      printer.PrintToString(*request, &calls[i].body);
    }
  }
  const std::string out = join_calls(calls);
  if (out.size() > max_size) return LLVMFuzzerMutate(data, size, max_size);
  std::memcpy(data, out.data(), out.size());
  return out.size();
}
