#include "server/api/submission.h"

#include <cctype>
#include <string>

#include "case/estimate.h"
#include "case/load.h"
#include "case/study_ladder.h"
#include "case/validate.h"
#include "common/log.h"
#include "common/message_limits.h"
#include "common/sha256.h"
#include "server/api/errors.h"
#include "server/api/stored_case_text.h"
#include "server/clock.h"

namespace sph::server::api {
namespace {

constexpr size_t kMaxRequestIdLength = 128;

grpc::Status check_request_id(const std::string& id) {
  if (id.empty())
    return invalid_argument("request_id",
                            "is required (a client-chosen key that makes retries "
                            "safe; sphctl generates one)");
  if (id.size() > kMaxRequestIdLength)
    return invalid_argument("request_id", "longer than 128 characters");
  for (unsigned char ch : id)
    if (!std::isalnum(ch) && ch != '.' && ch != '_' && ch != ':' && ch != '-')
      return invalid_argument("request_id", "may contain only letters, digits and . _ : -");
  return grpc::Status::OK;
}

}  // namespace

grpc::Status accept_submission(const Submission& s, grpc::ServerContextBase& context,
                               const v1::SubmitRequest& request, v1::SubmitResponse& response) {
  if (auto st = s.auth.check(context); !st.ok()) return st;
  if (auto st = check_request_id(request.request_id()); !st.ok()) return st;
  if (request.case_text().empty()) return invalid_argument("case_text", "is empty");
  return guarded([&] {
    // Everything is checked before anything is stored: a rejected case leaves no trace.
    v1::Case c;
    try {
      c = parse_case_text(request.case_text());
    } catch (const CaseLoadError& e) {
      context.AddTrailingMetadata("sph-invalid-field", "case_text");
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          std::string("invalid case: case_text: ") + e.what());
    }
    CaseEstimate estimate;
    const auto errors = validate_case(
        c, ValidationLimits{s.limits.max_particles, s.limits.max_memory_bytes}, &estimate);
    if (!errors.empty()) {
      for (const auto& e : errors)
        context.AddTrailingMetadata("sph-invalid-field", e.field.empty() ? "." : e.field);
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          "invalid case: " + join_errors(errors));
    }
    store::NewJob job;
    job.request_id = request.request_id();
    job.name = c.name();
    // Bounded by a small multiple of what was sent (server/api/stored_case_text.h): a compact
    // text of deeply nested shapes is stored on one line rather than quadratically indented.
    auto stored = stored_case_text(c, request.case_text().size());
    if (!stored) {
      context.AddTrailingMetadata("sph-invalid-field", "case_text");
      return invalid_argument(
          "case_text", "its stored form is more than " +
                           std::to_string(max_stored_case_bytes(request.case_text().size())) +
                           " bytes (4 times the " + std::to_string(request.case_text().size()) +
                           " bytes sent, plus 64 KiB)");
    }
    job.case_text = std::move(*stored);
    if (job.case_text.size() > service::kMaxCaseTextBytes) {
      context.AddTrailingMetadata("sph-invalid-field", "case_text");
      return invalid_argument(
          "case_text", "is " + std::to_string(job.case_text.size() >> 20) +
                           " MiB as stored; the limit is " +
                           std::to_string(service::kMaxCaseTextBytes >> 20) +
                           " MiB, so that a worker can receive it: make point sets coarser or "
                           "split the case");
    }
    job.estimated_particles = estimate.total();
    service::Sha256 h;
    h.update(job.case_text);
    if (request.has_study()) {
      // The ladder is checked as the case is: each level must pass (the particle limit
      // applies to the finest), and the case needs a reference.
      const auto study_errors = validate_study(
          c, request.study(), ValidationLimits{s.limits.max_particles, s.limits.max_memory_bytes});
      if (!study_errors.empty()) {
        for (const auto& e : study_errors)
          context.AddTrailingMetadata("sph-invalid-field", e.field.empty() ? "." : e.field);
        return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                            "invalid study: " + join_errors(study_errors));
      }
      job.study = request.study().SerializeAsString();
      // The same case as a study is a different job (a reused request id must conflict).
      h.update("\nstudy:" + job.study);
      const auto ladder = study_ladder(c, request.study());
      job.estimated_particles = estimate_case(level_case(c, ladder.back())).total();
    }
    job.case_sha256 = h.hex_digest();
    store::SubmitResult result;
    try {
      result = s.store.submit(
          job, now_unix_ms(),
          store::QueueLimits{s.limits.max_queued_jobs, s.limits.max_queued_particles});
    } catch (const store::QueueFull& e) {
      return grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED, e.what());
    }
    if (result.created)
      service::log_line("%s submitted (%s, about %.0f particles, request %s)",
                        result.job.id().c_str(), job.name.c_str(), job.estimated_particles,
                        job.request_id.c_str());
    *response.mutable_job() = std::move(result.job);
    response.set_created(result.created);
    return grpc::Status::OK;
  });
}

}  // namespace sph::server::api
