#pragma once
// Where results live: RESULTS/<job>/<attempt>/result.h5 + result.xmf, checkpoints/. The server
// and every pool see RESULTS at the same path (a shared filesystem; see docs/service.md), so
// paths cross the API as absolute paths.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace sph::server {

class ResultLayout {
 public:
  // `root` is made absolute and normalised.
  explicit ResultLayout(const std::filesystem::path& root);

  const std::filesystem::path& root() const { return root_; }
  // `job_id` must be canonical ("job-42", store/job_ids.h); throws std::invalid_argument
  // otherwise.
  std::filesystem::path job_dir(const std::string& job_id) const;
  std::filesystem::path attempt_dir(const std::string& job_id, int attempt) const;

  // True when `path` (absolute) lies below the job's directory, after resolving "." and "..".
  bool inside_job(const std::string& job_id, const std::filesystem::path& path) const;

  // Checks a manifest file name: relative, no "..", and a regular file inside the attempt
  // directory. Returns the problem, or nullopt when the name is acceptable.
  std::optional<std::string> check_result_name(const std::string& job_id, int attempt,
                                               const std::string& name) const;

 private:
  std::filesystem::path root_;
};

}  // namespace sph::server
