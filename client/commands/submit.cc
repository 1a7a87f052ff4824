// sphctl submit CASE [--watch] [--dry-run] [--request-id ID]
#include <google/protobuf/struct.pb.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "case/estimate.h"
#include "case/load.h"
#include "case/validate.h"
#include "cli/exit_codes.h"
#include "commands/commands.h"
#include "common/job_state.h"
#include "common/message_limits.h"
#include "render/job_text.h"
#include "render/json.h"

namespace sph::ctl {
namespace {

constexpr const char* kUsageText =
    "usage: sphctl submit CASE.textproto [--watch] [--dry-run] [--request-id ID]";
// How long submit keeps retrying while the server is unreachable. Retrying is safe: the
// request id makes a repeated Submit return the job created the first time.
constexpr auto kRetryFor = std::chrono::seconds(30);

std::string random_request_id() {
  std::random_device rd;
  std::uniform_int_distribution<unsigned> hex(0, 15);
  std::string id = "sphctl-";
  for (int i = 0; i < 24; ++i) id += "0123456789abcdef"[hex(rd)];
  return id;
}

int print_dry_run(const GlobalOptions& g, const v1::Case& c, const std::string& path) {
  const CaseEstimate e = estimate_case(c);
  if (g.json) {
    google::protobuf::Struct s;
    auto& f = *s.mutable_fields();
    f["case"].set_string_value(path);
    f["name"].set_string_value(c.name());
    f["dimension"].set_number_value(c.dimension());
    f["dx"].set_number_value(c.dx());
    f["fluid_particles"].set_number_value(e.fluid_particles);
    f["wall_particles"].set_number_value(e.wall_particles);
    f["rigid_particles"].set_number_value(e.rigid_particles);
    f["elastic_particles"].set_number_value(e.elastic_particles);
    f["elastic_isotropic_particles"].set_number_value(e.elastic_isotropic_particles);
    f["total_particles"].set_number_value(e.total());
    f["initial_dt"].set_number_value(e.initial_dt);
    f["dt_limited_by"].set_string_value(e.dt_limited_by);
    f["estimated_steps"].set_number_value(e.steps);
    if (c.time().has_quasi_static()) f["estimated_inner_steps"].set_number_value(e.inner_steps);
    f["estimated_bytes"].set_number_value(e.bytes);
    std::printf("%s\n", to_json(s).c_str());
    return kOk;
  }
  std::printf("case %s (%dD, dx = %g): valid, not submitted (--dry-run)\n", c.name().c_str(),
              c.dimension(), c.dx());
  std::printf("  particles:  %.0f fluid, %.0f wall, %.0f rigid, %.0f elastic, %.0f total\n",
              e.fluid_particles, e.wall_particles, e.rigid_particles, e.elastic_particles,
              e.total());
  if (e.elastic_isotropic_particles != e.elastic_particles)
    std::printf(
        "  anisotropic elastic bodies: %.0f particles, %.0f if resolved isotropically "
        "(%.1f%% fewer)\n",
        e.elastic_particles, e.elastic_isotropic_particles,
        100.0 * (1.0 - e.elastic_particles / e.elastic_isotropic_particles));
  std::printf("  time step:  %.4g s at rest (%s)\n", e.initial_dt, e.dt_limited_by.c_str());
  std::printf("  steps:      about %.0f to t = %g s\n", e.steps, c.time().end_time());
  if (c.time().has_quasi_static())
    std::printf(
        "  quasi-static: %.0f load steps, each of at most %.0f inner steps (%.0f in all, what "
        "plain steps would take); the relaxation ends most sooner\n",
        e.steps, e.steps > 0 ? std::ceil(e.inner_steps / e.steps) : 0.0, e.inner_steps);
  std::printf("  memory:     about %s over all ranks\n", format_bytes(e.bytes).c_str());
  return kOk;
}

}  // namespace

int submit_job(const GlobalOptions& g, const v1::Case& c, const std::string& path,
               const v1::StudySpec* study, bool watch, const std::string& request_id) {
  auto conn = Connection::open(g);
  if (!conn) return kUsage;
  v1::SubmitRequest req;
  req.set_request_id(request_id.empty() ? random_request_id() : request_id);
  req.set_case_text(case_to_text(c));
  // The server would refuse it too, but only after sending it (service/message_limits.h).
  if (req.case_text().size() > service::kMaxCaseTextBytes) {
    std::fprintf(stderr,
                 "sphctl: %s: case_text: the case is %zu MiB with its point and reference data "
                 "inlined; the service takes at most %zu MiB: make point sets coarser or split "
                 "the case\n",
                 path.c_str(), req.case_text().size() >> 20, service::kMaxCaseTextBytes >> 20);
    return kInvalidCase;
  }
  if (study != nullptr) *req.mutable_study() = *study;
  v1::SubmitResponse resp;
  grpc::Status status;
  const auto give_up = std::chrono::steady_clock::now() + kRetryFor;
  auto pause = std::chrono::milliseconds(200);
  while (true) {
    status = conn->jobs().Submit(conn->unary_context().get(), req, &resp);
    if (status.ok() || !is_transient(status) || std::chrono::steady_clock::now() >= give_up) break;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(3000));
  }
  if (!status.ok())
    return report_error(status, (study ? "study " : "submit ") + path, conn->address());

  if (g.json && !watch) {
    std::printf("%s\n", to_json(resp).c_str());
  } else if (!g.json) {
    if (resp.created())
      std::printf("submitted %s (%s%s, about %s particles%s)\n", resp.job().id().c_str(),
                  resp.job().name().c_str(), study ? ", convergence study" : "",
                  format_count(resp.job().estimated_particles()).c_str(),
                  study ? " at the finest level" : "");
    else
      std::printf("%s was already submitted with request id %s (%s)\n", resp.job().id().c_str(),
                  req.request_id().c_str(), service::state_name(resp.job().state()));
    std::fflush(stdout);
  }
  if (!watch) return kOk;
  return watch_job(*conn, g, resp.job().id(), 0);
}

int load_and_validate(const std::string& path, v1::Case& c) {
  // Load (inlining point and reference data files, which the server cannot read) and
  // validate here first, so mistakes are reported without a round trip and the server gets a
  // self-contained case.
  try {
    c = load_case_file(path);
  } catch (const CaseLoadError& e) {
    std::fprintf(stderr, "sphctl: %s: %s\n", path.c_str(), e.what());
    return kInvalidCase;
  }
  if (const auto errors = validate_case(c); !errors.empty()) {
    std::fprintf(stderr, "sphctl: %s is not a valid case:\n", path.c_str());
    for (const auto& e : errors) std::fprintf(stderr, "  %s\n", e.to_string().c_str());
    return kInvalidCase;
  }
  return kOk;
}

int cmd_submit(const GlobalOptions& g, ArgScanner args) {
  const bool watch = args.take_flag("--watch");
  const bool dry_run = args.take_flag("--dry-run");
  std::string request_id;
  args.take_value("--request-id", request_id);
  std::vector<std::string> pos;
  if (!expect_positionals(args, 1, kUsageText, pos)) return kUsage;
  const std::string& path = pos[0];
  v1::Case c;
  if (const int rc = load_and_validate(path, c); rc != kOk) return rc;
  if (dry_run) return print_dry_run(g, c, path);
  return submit_job(g, c, path, nullptr, watch, request_id);
}

}  // namespace sph::ctl
