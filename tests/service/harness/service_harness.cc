#include "harness/service_harness.h"

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/auth_token.h"
#include "common/channel.h"

namespace sph::testing {
namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : s) {
    if (ch == sep) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += ch;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

ServiceHarness::ServiceHarness() {
  std::string tmpl = (fs::temp_directory_path() / "sphd-service-XXXXXX").string();
  if (mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  dir_ = tmpl;
}

ServiceHarness::~ServiceHarness() {
  server_.kill_all();
  const bool keep = ::testing::Test::HasFailure() || std::getenv("SPHD_KEEP_TEST_DIRS") != nullptr;
  if (keep) {
    std::fprintf(stderr, "test files kept in %s\n", dir_.c_str());
  } else {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
}

void ServiceHarness::start_server(const ServerSettings& settings) {
  if (server_starts_ == 0) {
    settings_ = settings;
    if (!settings.token.empty()) {
      token_ = settings.token;
      token_file_ = dir_ + "/token";
      std::ofstream(token_file_) << token_ << "\n";
    }
  }
  const std::string address_file = dir_ + "/server.address";
  fs::remove(address_file);
  std::vector<std::string> argv = {SPHD_SERVER_BIN,
                                   "--address",
                                   address_.empty() ? "127.0.0.1:0" : address_,
                                   "--address-file",
                                   address_file,
                                   "--db",
                                   dir_ + "/sphd.db",
                                   "--results",
                                   dir_ + "/results",
                                   "--lease",
                                   std::to_string(settings_.lease_seconds),
                                   "--shutdown-grace",
                                   "3"};
  if (!token_file_.empty()) argv.insert(argv.end(), {"--token-file", token_file_});
  if (settings_.max_particles >= 0)
    argv.insert(argv.end(), {"--max-particles", std::to_string(settings_.max_particles)});
  if (settings_.shutdown_grace >= 0)
    argv.insert(argv.end(), {"--shutdown-grace", std::to_string(settings_.shutdown_grace)});
  argv.insert(argv.end(), settings_.extra_args.begin(), settings_.extra_args.end());
  const std::string log = dir_ + "/server" + std::to_string(++server_starts_) + ".log";
  log_files_.push_back(log);
  server_ = Process::spawn(argv, log);
  const bool up = eventually(20s, [&] { return fs::exists(address_file) || !server_.running(); });
  if (!up || !fs::exists(address_file))
    throw std::runtime_error("sph-server did not start:\n" + read_file(log));
  address_ = trim(read_file(address_file));
  connect();
}

void ServiceHarness::connect() {
  auto channel = service::make_channel(address_);  // the clients' limits and reconnects
  jobs_ = v1::JobService::NewStub(channel);
  workers_ = v1::WorkerService::NewStub(channel);
}

std::unique_ptr<grpc::ClientContext> ServiceHarness::context(
    std::chrono::milliseconds timeout) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  service::add_token(*ctx, token_);
  ctx->set_deadline(std::chrono::system_clock::now() + timeout);
  return ctx;
}

Process ServiceHarness::start_pool(int ranks, const std::vector<std::string>& extra_args,
                                   const std::string& log_name) {
  std::vector<std::string> argv = split(SPHD_MPIRUN_ARGS, '|');
  argv.insert(argv.end(), {"-np", std::to_string(ranks), SPHD_WORKER_BIN, "--server", address_});
  if (!token_file_.empty()) argv.insert(argv.end(), {"--token-file", token_file_});
  argv.insert(argv.end(), extra_args.begin(), extra_args.end());
  const std::string log = dir_ + "/" + log_name + ".log";
  log_files_.push_back(log);
  return Process::spawn(argv, log);
}

int ServiceHarness::run_local(int ranks, const std::string& case_path, const std::string& out_dir) {
  std::vector<std::string> argv = split(SPHD_MPIRUN_ARGS, '|');
  argv.insert(argv.end(), {"-np", std::to_string(ranks), SPHD_WORKER_BIN, "--case", case_path,
                           "--out", out_dir, "--quiet"});
  const auto r = run_command(argv, dir_, 120s);
  if (r.exit_code != 0)
    std::fprintf(stderr, "local run failed:\n%s%s", r.out.c_str(), r.err.c_str());
  return r.exit_code;
}

CommandResult ServiceHarness::sphctl(const std::vector<std::string>& args,
                                     std::chrono::milliseconds timeout) {
  std::vector<std::string> argv = {SPHCTL_BIN, "--server", address_};
  if (!token_file_.empty()) argv.insert(argv.end(), {"--token-file", token_file_});
  argv.insert(argv.end(), args.begin(), args.end());
  return run_command(argv, dir_, timeout);
}

v1::ClaimResponse ServiceHarness::claim(const std::string& pool, int ranks) {
  return claim_next_job(*workers_, *context(20s), pool, ranks);
}

v1::ClaimResponse claim_next_job(v1::WorkerService::Stub& workers, grpc::ClientContext& context,
                                 const std::string& pool, int ranks) {
  v1::ClaimRequest req;
  req.set_pool_id(pool);
  req.set_ranks(ranks);
  req.set_wait_seconds(5);
  v1::ClaimResponse resp;
  const auto status = workers.Claim(&context, req, &resp);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return resp;
}

v1::Job ServiceHarness::get_job(const std::string& id) {
  v1::GetJobRequest req;
  req.set_job_id(id);
  v1::Job job;
  const auto status = jobs_->GetJob(context().get(), req, &job);
  if (!status.ok()) throw std::runtime_error("GetJob " + id + ": " + status.error_message());
  return job;
}

bool ServiceHarness::wait_for_state(const std::string& id, v1::JobState state,
                                    std::chrono::milliseconds timeout) {
  return wait_for_job(id, timeout, [&](const v1::Job& j) { return j.state() == state; });
}

std::vector<v1::JobEvent> ServiceHarness::history(const std::string& id) {
  v1::WatchJobRequest req;
  req.set_job_id(id);
  auto ctx = context(30s);
  auto reader = jobs_->WatchJob(ctx.get(), req);
  std::vector<v1::JobEvent> out;
  v1::JobEvent e;
  while (reader->Read(&e)) out.push_back(e);
  const auto status = reader->Finish();
  if (!status.ok()) throw std::runtime_error("WatchJob " + id + ": " + status.error_message());
  return out;
}

v1::Job ServiceHarness::submit_text(const std::string& case_text, const std::string& request_id) {
  static std::atomic<int> counter{0};
  v1::SubmitRequest req;
  req.set_request_id(request_id.empty()
                         ? "test-" + std::to_string(getpid()) + "-" + std::to_string(++counter)
                         : request_id);
  req.set_case_text(case_text);
  v1::SubmitResponse resp;
  const auto status = jobs_->Submit(context().get(), req, &resp);
  if (!status.ok()) throw std::runtime_error("Submit: " + status.error_message());
  return resp.job();
}

std::string ServiceHarness::logs() const {
  std::string out;
  for (const auto& f : log_files_) out += "---- " + f + "\n" + read_file(f);
  return out;
}

std::string test_case_path(const std::string& name) {
  return std::string(SPHD_TEST_CASES_DIR) + "/" + name;
}

std::string read_test_case(const std::string& name) {
  return read_file(test_case_path(name));
}

std::string with_end_time(const std::string& case_text, double end_time) {
  std::ostringstream v;
  v << end_time;
  return std::regex_replace(case_text, std::regex(R"(end_time: [0-9.eE+-]+)"),
                            "end_time: " + v.str());
}

int h5check(const std::vector<std::string>& args, const std::string& work_dir, std::string& out) {
  std::vector<std::string> argv = {SPHD_PYTHON, SPHD_H5CHECK};
  argv.insert(argv.end(), args.begin(), args.end());
  const auto r = run_command(argv, work_dir, 60s);
  out = r.out + r.err;
  return r.exit_code;
}

}  // namespace sph::testing
