#include "server/api/job_service.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <vector>

#include "case/estimate.h"
#include "case/load.h"
#include "case/study_ladder.h"
#include "case/validate.h"
#include "server/api/errors.h"
#include "server/clock.h"
#include "server/common/job_state.h"
#include "server/common/log.h"
#include "server/common/message_limits.h"
#include "server/common/sha256.h"
#include "server/common/time_text.h"
#include "server/results/job_files_removal.h"
#include "server/store/job_ids.h"

namespace sph::server::api {
namespace {

constexpr size_t kMaxRequestIdLength = 128;
constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
constexpr int kEventBatch = 500;
constexpr size_t kChunkBytes = 1 << 20;
// How often a waiting stream looks at client cancellation and server shutdown.
constexpr std::chrono::milliseconds kWatchPoll{250};

grpc::Status parse_id(const std::string& text, std::int64_t& id) {
  const auto parsed = store::parse_job_id(text);
  if (!parsed)
    return invalid_argument("job_id", "'" + text + "' is not a job id (expected job-<n>)");
  id = *parsed;
  return grpc::Status::OK;
}

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

bool is_terminal_event(const v1::JobEvent& e) {
  return e.has_state_change() && service::is_terminal(e.state_change().state());
}

}  // namespace

grpc::Status JobServiceImpl::Submit(grpc::ServerContext* context, const v1::SubmitRequest* request,
                                    v1::SubmitResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  if (auto s = check_request_id(request->request_id()); !s.ok()) return s;
  if (request->case_text().empty()) return invalid_argument("case_text", "is empty");
  return guarded([&] {
    // Everything is checked before anything is stored: a rejected case leaves no trace.
    v1::Case c;
    try {
      c = parse_case_text(request->case_text());
    } catch (const CaseLoadError& e) {
      context->AddTrailingMetadata("sph-invalid-field", "case_text");
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          std::string("invalid case: case_text: ") + e.what());
    }
    const auto errors = validate_case(c, ValidationLimits{limits_.max_particles});
    if (!errors.empty()) {
      for (const auto& e : errors)
        context->AddTrailingMetadata("sph-invalid-field", e.field.empty() ? "." : e.field);
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                          "invalid case: " + join_errors(errors));
    }
    store::NewJob job;
    job.request_id = request->request_id();
    job.name = c.name();
    job.case_text = case_to_text(c);
    if (job.case_text.size() > service::kMaxCaseTextBytes) {
      context->AddTrailingMetadata("sph-invalid-field", "case_text");
      return invalid_argument(
          "case_text", "is " + std::to_string(job.case_text.size() >> 20) +
                           " MiB as stored; the limit is " +
                           std::to_string(service::kMaxCaseTextBytes >> 20) +
                           " MiB, so that a worker can receive it: make point sets coarser or "
                           "split the case");
    }
    job.estimated_particles = estimate_case(c).total();
    service::Sha256 h;
    h.update(job.case_text);
    if (request->has_study()) {
      // The ladder is checked as the case is: each level must pass (the particle limit
      // applies to the finest), and the case needs a reference.
      const auto study_errors =
          validate_study(c, request->study(), ValidationLimits{limits_.max_particles});
      if (!study_errors.empty()) {
        for (const auto& e : study_errors)
          context->AddTrailingMetadata("sph-invalid-field", e.field.empty() ? "." : e.field);
        return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                            "invalid study: " + join_errors(study_errors));
      }
      job.study = request->study().SerializeAsString();
      // The same case as a study is a different job (a reused request id must conflict).
      h.update("\nstudy:" + job.study);
      const auto ladder = study_ladder(c, request->study());
      job.estimated_particles = estimate_case(level_case(c, ladder.back())).total();
    }
    job.case_sha256 = h.hex_digest();
    auto result = store_.submit(job, now_unix_ms());
    if (result.created)
      service::log_line("%s submitted (%s, about %.0f particles, request %s)",
                        result.job.id().c_str(), job.name.c_str(), job.estimated_particles,
                        job.request_id.c_str());
    *response->mutable_job() = std::move(result.job);
    response->set_created(result.created);
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::GetJob(grpc::ServerContext* context, const v1::GetJobRequest* request,
                                    v1::Job* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  return guarded([&] {
    *response = store_.get(id, request->include_case());
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::ListJobs(grpc::ServerContext* context,
                                      const v1::ListJobsRequest* request,
                                      v1::ListJobsResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  if (request->page_size() < 0) return invalid_argument("page_size", "must be >= 0");
  const int page_size =
      request->page_size() == 0 ? kDefaultPageSize : std::min(request->page_size(), kMaxPageSize);
  std::int64_t before = 0;
  if (!request->page_token().empty()) {
    const auto parsed = store::parse_job_id(request->page_token());
    if (!parsed) return invalid_argument("page_token", "is not a token from ListJobs");
    before = *parsed;
  }
  std::vector<v1::JobState> states;
  for (int i = 0; i < request->states_size(); ++i) {
    const auto s = request->states(i);
    if (s == v1::JOB_STATE_UNSPECIFIED || !v1::JobState_IsValid(s))
      return invalid_argument("states[" + std::to_string(i) + "]", "is not a job state");
    states.push_back(s);
  }
  return guarded([&] {
    auto page = store_.list(states, page_size, before);
    for (auto& j : page.jobs) *response->add_jobs() = std::move(j);
    if (page.next_before > 0) response->set_next_page_token(std::to_string(page.next_before));
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::WatchJob(grpc::ServerContext* context,
                                      const v1::WatchJobRequest* request,
                                      grpc::ServerWriter<v1::JobEvent>* writer) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  if (request->after_sequence() < 0) return invalid_argument("after_sequence", "must be >= 0");
  return guarded([&] {
    store_.state(id);  // NOT_FOUND before the stream starts
    EventFeed::Subscription sub(feed_, id);
    std::int64_t last = request->after_sequence();
    while (true) {
      // The state is read before the events: a job that finishes between the two reads has
      // its last events read here, and is found finished only on the next round, after they
      // were sent.
      const bool finished = service::is_terminal(store_.state(id));
      const auto events = store_.events_after(id, last, kEventBatch);
      for (const auto& e : events) {
        if (!writer->Write(e)) return grpc::Status(grpc::StatusCode::CANCELLED, "client went away");
        last = e.sequence();
        if (is_terminal_event(e)) return grpc::Status::OK;
      }
      if (!events.empty()) continue;
      // Nothing newer: a finished job has nothing more to say (the terminal event is last).
      if (finished) return grpc::Status::OK;
      if (context->IsCancelled()) return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled");
      if (feed_.shutting_down())
        return grpc::Status(
            grpc::StatusCode::UNAVAILABLE,
            "server shutting down; resume with after_sequence=" + std::to_string(last));
      sub.wait(last, kWatchPoll);
    }
  });
}

grpc::Status JobServiceImpl::CancelJob(grpc::ServerContext* context,
                                       const v1::CancelJobRequest* request, v1::Job* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  return guarded([&] {
    *response = store_.cancel(id, request->reason(), now_unix_ms());
    service::log_line("%s: cancel requested, now %s", response->id().c_str(),
                      service::state_name(response->state()));
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::FetchResult(grpc::ServerContext* context,
                                         const v1::FetchResultRequest* request,
                                         grpc::ServerWriter<v1::FileChunk>* writer) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  if (request->offset() < 0) return invalid_argument("offset", "must be >= 0");
  if (request->offset() > 0 && request->file().empty())
    return invalid_argument("offset", "needs a single file");
  return guarded([&] {
    const v1::Job job = store_.get(id, false);
    const auto deleted = [&] {
      return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                          job.id() + "'s files were deleted at " +
                              service::format_unix_seconds(
                                  store_.get(id, false).files_deleted_unix_ms() / 1000, true) +
                              " (sphctl delete)");
    };
    if (job.files_deleted_unix_ms() > 0) return deleted();
    if (!job.has_result() || job.result().files_size() == 0)
      return grpc::Status(
          grpc::StatusCode::FAILED_PRECONDITION,
          job.id() + " has no result yet (" + service::state_name(job.state()) + ")");
    const auto& manifest = job.result();
    std::vector<const v1::ResultFile*> files;
    std::string names;
    for (const auto& f : manifest.files()) {
      names += (names.empty() ? "" : ", ") + f.name();
      if (request->file().empty() || request->file() == f.name()) files.push_back(&f);
    }
    // Only what the manifest lists is served: the name is compared, never used as a path.
    if (files.empty())
      return grpc::Status(grpc::StatusCode::NOT_FOUND, "file: '" + request->file() +
                                                           "' is not in the result manifest of " +
                                                           job.id() + " (" + names + ")");
    std::vector<char> buf(kChunkBytes);
    for (const v1::ResultFile* f : files) {
      if (auto problem = layout_.check_result_name(job.id(), manifest.attempt(), f->name()))
        return grpc::Status(grpc::StatusCode::DATA_LOSS,
                            "result file " + f->name() + " " + *problem);
      const auto path = layout_.attempt_dir(job.id(), manifest.attempt()) / f->name();
      std::ifstream in(path, std::ios::binary);
      // Deleted while this fetch went on: the delete is recorded before the files go.
      if (!in && store_.get(id, false).files_deleted_unix_ms() > 0) return deleted();
      if (!in) return grpc::Status(grpc::StatusCode::DATA_LOSS, "cannot read " + path.string());
      in.seekg(0, std::ios::end);
      const std::int64_t size = in.tellg();
      if (size != f->size())
        return grpc::Status(grpc::StatusCode::DATA_LOSS,
                            path.string() + " has " + std::to_string(size) +
                                " bytes but the manifest says " + std::to_string(f->size()));
      if (request->offset() > size)
        return grpc::Status(grpc::StatusCode::OUT_OF_RANGE, "offset: beyond the end of the file");
      std::int64_t offset = request->offset();
      in.seekg(offset);
      do {
        if (context->IsCancelled()) return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled");
        if (feed_.shutting_down())
          return grpc::Status(
              grpc::StatusCode::UNAVAILABLE,
              "server shutting down; resume " + f->name() + " at offset " + std::to_string(offset));
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        const auto n = in.gcount();
        v1::FileChunk chunk;
        chunk.set_name(f->name());
        chunk.set_offset(offset);
        chunk.set_data(buf.data(), static_cast<size_t>(n));
        chunk.set_size(f->size());
        chunk.set_sha256(f->sha256());
        if (!writer->Write(chunk))
          return grpc::Status(grpc::StatusCode::CANCELLED, "client went away");
        offset += n;
      } while (offset < size);
    }
    return grpc::Status::OK;
  });
}

grpc::Status JobServiceImpl::DeleteJobFiles(grpc::ServerContext* context,
                                            const v1::DeleteJobFilesRequest* request,
                                            v1::DeleteJobFilesResponse* response) {
  if (auto s = auth_.check(*context); !s.ok()) return s;
  std::int64_t id = 0;
  if (auto s = parse_id(request->job_id(), id); !s.ok()) return s;
  return guarded([&] {
    std::lock_guard lock(delete_mu_);
    // A finished job never runs again, so nothing of ours writes into its directory while it
    // is removed. The deletion is recorded before the files go, so that a fetch starting
    // after this point is refused as "deleted" rather than finding files missing; a removal
    // that fails half way (permissions) is reported, and calling again finishes it. Every
    // call removes the directory, also after the first: a pool cut off from the server may
    // still write there until it learns that its attempt ended.
    const v1::Job job = store_.get_finished(id);
    const JobFiles files = measure_job_files(layout_, job.id());
    auto [updated, now] = store_.record_files_deleted(id, files.bytes, now_unix_ms());
    try {
      remove_job_files(layout_, job.id());
    } catch (const std::filesystem::filesystem_error& e) {
      service::log_line("%s: deleting its files failed: %s", job.id().c_str(), e.what());
      return grpc::Status(grpc::StatusCode::INTERNAL,
                          "deleting " + layout_.job_dir(job.id()).string() +
                              " failed (what was removed stays removed; call again to "
                              "retry): " +
                              e.what());
    }
    if (now || files.files > 0)
      service::log_line("%s: deleted %lld files (%lld bytes) in %s", job.id().c_str(),
                        static_cast<long long>(files.files), static_cast<long long>(files.bytes),
                        layout_.job_dir(job.id()).string().c_str());
    *response->mutable_job() = std::move(updated);
    response->set_deleted_now(now);
    return grpc::Status::OK;
  });
}

}  // namespace sph::server::api
