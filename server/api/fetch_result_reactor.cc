#include "server/api/fetch_result_reactor.h"

#include <algorithm>

#include "common/job_state.h"
#include "common/time_text.h"
#include "server/api/errors.h"

namespace sph::server::api {
namespace {

constexpr std::size_t kChunkBytes = 1 << 20;

}  // namespace

FetchResultReactor::FetchResultReactor(store::JobStore& store, EventFeed& feed,
                                       const ResultLayout& layout, StreamLimiter::Slot slot,
                                       std::int64_t job, std::string file, std::int64_t offset)
    : store_(store),
      feed_(feed),
      layout_(layout),
      slot_(std::move(slot)),
      job_id_(job),
      file_(std::move(file)),
      start_offset_(offset) {
  std::optional<grpc::Status> refused;
  try {
    refused = check_job();
  } catch (...) {
    refused = status_from_current_exception();
  }
  if (refused)
    Finish(std::move(*refused));
  else
    send_next();
}

std::optional<grpc::Status> FetchResultReactor::check_job() {
  job_ = store_.get(job_id_, false);
  if (job_.files_deleted_unix_ms() > 0) return deleted();
  if (!job_.has_result() || job_.result().files_size() == 0)
    return grpc::Status(
        grpc::StatusCode::FAILED_PRECONDITION,
        job_.id() + " has no result yet (" + service::state_name(job_.state()) + ")");
  std::string names;
  for (const auto& f : job_.result().files()) {
    names += (names.empty() ? "" : ", ") + f.name();
    if (file_.empty() || file_ == f.name()) files_.push_back(&f);
  }
  // Only what the manifest lists is served: the name is compared, never used as a path.
  if (files_.empty())
    return grpc::Status(
        grpc::StatusCode::NOT_FOUND,
        "file: '" + file_ + "' is not in the result manifest of " + job_.id() + " (" + names + ")");
  return std::nullopt;
}

void FetchResultReactor::OnWriteDone(bool ok) {
  if (!ok) return Finish(grpc::Status(grpc::StatusCode::CANCELLED, "client went away"));
  offset_ += static_cast<std::int64_t>(chunk_.data().size());
  send_next();
}

void FetchResultReactor::send_next() {
  std::optional<grpc::Status> end;
  try {
    end = prepare_next();
  } catch (...) {
    end = status_from_current_exception();
  }
  if (end) return Finish(std::move(*end));
  StartWrite(&chunk_);
}

std::optional<grpc::Status> FetchResultReactor::prepare_next() {
  while (true) {
    if (!in_.is_open()) {
      if (file_index_ == files_.size()) return grpc::Status::OK;
      if (auto problem = open_next_file()) return problem;
    }
    const v1::ResultFile& f = *files_[file_index_ - 1];
    if (file_started_ && offset_ >= size_) {
      in_.close();
      continue;
    }
    if (cancelled_) return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled");
    if (feed_.shutting_down())
      return grpc::Status(
          grpc::StatusCode::UNAVAILABLE,
          "server shutting down; resume " + f.name() + " at offset " + std::to_string(offset_));
    std::string& data = *chunk_.mutable_data();
    // Never past the size the manifest gave: a file that grew since is served as listed.
    data.resize(static_cast<std::size_t>(
        std::min<std::int64_t>(static_cast<std::int64_t>(kChunkBytes), size_ - offset_)));
    in_.read(data.data(), static_cast<std::streamsize>(data.size()));
    data.resize(static_cast<std::size_t>(in_.gcount()));
    // Shorter than its size said when it was opened: removed or cut while it was sent.
    if (data.empty() && offset_ < size_) {
      if (store_.get(job_id_, false).files_deleted_unix_ms() > 0) return deleted();
      return grpc::Status(grpc::StatusCode::DATA_LOSS,
                          "result file " + f.name() + " ended at offset " +
                              std::to_string(offset_) + " while it was sent; the manifest says " +
                              std::to_string(f.size()) + " bytes");
    }
    chunk_.set_name(f.name());
    chunk_.set_offset(offset_);
    chunk_.set_size(f.size());
    chunk_.set_sha256(f.sha256());
    file_started_ = true;
    return std::nullopt;
  }
}

std::optional<grpc::Status> FetchResultReactor::open_next_file() {
  const v1::ResultFile& f = *files_[file_index_++];
  const auto& manifest = job_.result();
  if (auto problem = layout_.check_result_name(job_.id(), manifest.attempt(), f.name()))
    return grpc::Status(grpc::StatusCode::DATA_LOSS, "result file " + f.name() + " " + *problem);
  const auto path = layout_.attempt_dir(job_.id(), manifest.attempt()) / f.name();
  in_.open(path, std::ios::binary);
  // Deleted while this fetch went on: the delete is recorded before the files go.
  if (!in_ && store_.get(job_id_, false).files_deleted_unix_ms() > 0) return deleted();
  if (!in_) return grpc::Status(grpc::StatusCode::DATA_LOSS, "cannot read " + path.string());
  in_.seekg(0, std::ios::end);
  const std::int64_t size = in_.tellg();
  if (size != f.size())
    return grpc::Status(grpc::StatusCode::DATA_LOSS,
                        path.string() + " has " + std::to_string(size) +
                            " bytes but the manifest says " + std::to_string(f.size()));
  if (start_offset_ > size)
    return grpc::Status(grpc::StatusCode::OUT_OF_RANGE, "offset: beyond the end of the file");
  offset_ = start_offset_;
  size_ = size;
  file_started_ = false;
  in_.seekg(offset_);
  return std::nullopt;
}

grpc::Status FetchResultReactor::deleted() {
  return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                      job_.id() + "'s files were deleted at " +
                          service::format_unix_seconds(
                              store_.get(job_id_, false).files_deleted_unix_ms() / 1000, true) +
                          " (sphctl delete)");
}

void FetchResultReactor::OnDone() {
  delete this;
}

}  // namespace sph::server::api
