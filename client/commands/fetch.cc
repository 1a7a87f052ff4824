// sphctl fetch JOB [-o DIR] [--file NAME]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/sha256.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {
namespace {

namespace fs = std::filesystem;
constexpr const char* kUsageText = "usage: sphctl fetch JOB [-o DIR] [--file NAME]";
constexpr int kMaxRetries = 20;

// A manifest name must stay inside the output directory, whatever the server says.
bool safe_name(const std::string& name) {
  const fs::path p(name);
  if (name.empty() || p.is_absolute()) return false;
  for (const auto& part : p)
    if (part == "..") return false;
  return true;
}

// Downloads one file into `dest` (via dest.part), resuming after transient errors, and checks
// its size and sha256 against the manifest. Returns an exit code.
int fetch_file(Connection& conn, const std::string& job_id, const v1::ResultFile& f,
               const fs::path& dest) {
  const fs::path part = dest.string() + ".part";
  fs::create_directories(dest.parent_path());
  std::ofstream out(part, std::ios::binary | std::ios::trunc);
  if (!out) {
    std::fprintf(stderr, "sphctl: cannot write %s\n", part.c_str());
    return kVerifyFailed;
  }
  service::Sha256 hash;
  std::int64_t offset = 0;
  for (int attempt = 0;; ++attempt) {
    auto ctx = conn.context(0);
    v1::FetchResultRequest req;
    req.set_job_id(job_id);
    req.set_file(f.name());
    req.set_offset(offset);
    auto reader = conn.jobs().FetchResult(ctx.get(), req);
    v1::FileChunk chunk;
    while (reader->Read(&chunk)) {
      if (chunk.offset() != offset) {
        std::fprintf(stderr, "sphctl: %s: chunk at offset %lld, expected %lld\n", f.name().c_str(),
                     static_cast<long long>(chunk.offset()), static_cast<long long>(offset));
        return kVerifyFailed;
      }
      out.write(chunk.data().data(), static_cast<std::streamsize>(chunk.data().size()));
      hash.update(chunk.data());
      offset += static_cast<std::int64_t>(chunk.data().size());
    }
    const auto status = reader->Finish();
    if (status.ok()) break;
    if (!is_transient(status) || attempt >= kMaxRetries) {
      out.close();
      fs::remove(part);
      return report_error(status, "fetch " + job_id + " " + f.name(), conn.address());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  out.close();
  if (!out) {
    std::fprintf(stderr, "sphctl: error writing %s\n", part.c_str());
    return kVerifyFailed;
  }
  const std::string digest = hash.hex_digest();
  if (offset != f.size() || digest != f.sha256()) {
    std::fprintf(stderr,
                 "sphctl: %s failed verification: %lld bytes, sha256 %s; the manifest says %lld "
                 "bytes, sha256 %s\n",
                 f.name().c_str(), static_cast<long long>(offset), digest.c_str(),
                 static_cast<long long>(f.size()), f.sha256().c_str());
    fs::remove(part);
    return kVerifyFailed;
  }
  fs::rename(part, dest);
  return kOk;
}

}  // namespace

int cmd_fetch(const GlobalOptions& g, ArgScanner args) {
  std::string out_dir, only;
  args.take_value("--output", out_dir, "-o");
  args.take_value("--file", only);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, kUsageText, pos)) return kUsage;
  auto conn = Connection::open(g);
  if (!conn) return kUsage;

  v1::GetJobRequest get;
  get.set_job_id(pos[0]);
  v1::Job job;
  if (auto s = conn->jobs().GetJob(conn->unary_context().get(), get, &job); !s.ok())
    return report_error(s, "fetch " + pos[0], conn->address());
  if (!job.has_result() || job.result().files_size() == 0) {
    std::fprintf(stderr, "sphctl: fetch %s: no result yet (%s)\n", job.id().c_str(),
                 job.reason().c_str());
    return kConflict;
  }
  if (out_dir.empty()) out_dir = job.id();
  v1::ResultManifest fetched = job.result();
  fetched.clear_files();
  fetched.set_output_dir(fs::absolute(out_dir).string());
  for (const auto& f : job.result().files()) {
    if (!only.empty() && f.name() != only) continue;
    if (!safe_name(f.name())) {
      std::fprintf(stderr, "sphctl: refusing manifest entry '%s' (outside %s)\n", f.name().c_str(),
                   out_dir.c_str());
      return kVerifyFailed;
    }
    const fs::path dest = fs::path(out_dir) / f.name();
    if (const int rc = fetch_file(*conn, job.id(), f, dest); rc != kOk) return rc;
    *fetched.add_files() = f;
    if (!g.json)
      std::printf("fetched %s (%s, sha256 verified)\n", dest.c_str(),
                  format_bytes(static_cast<double>(f.size())).c_str());
  }
  if (fetched.files_size() == 0) {
    // Ask the server, so the message is the same as for any name outside the manifest.
    auto ctx = conn->context(g.timeout_seconds);
    v1::FetchResultRequest req;
    req.set_job_id(job.id());
    req.set_file(only);
    auto reader = conn->jobs().FetchResult(ctx.get(), req);
    v1::FileChunk chunk;
    while (reader->Read(&chunk)) {
    }
    const auto status = reader->Finish();
    return report_error(
        status.ok() ? grpc::Status(grpc::StatusCode::NOT_FOUND, "no such file") : status,
        "fetch " + job.id() + " " + only, conn->address());
  }
  if (g.json) std::printf("%s\n", to_json(fetched).c_str());
  return kOk;
}

}  // namespace sph::ctl
