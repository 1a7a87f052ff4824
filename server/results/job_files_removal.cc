#include "server/results/job_files_removal.h"

#include <filesystem>

namespace sph::server {
namespace fs = std::filesystem;

RemovedFiles remove_job_files(const ResultLayout& layout, const std::string& job_id) {
  RemovedFiles out;
  const fs::path dir = layout.job_dir(job_id);
  if (!fs::exists(fs::symlink_status(dir))) return out;
  // Counted before removal: remove_all reports entries, not bytes. The iterator does not
  // follow directory links, so nothing outside the job's directory is counted or touched.
  if (fs::is_directory(fs::symlink_status(dir)))
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
      std::error_code ec;
      if (e.is_regular_file(ec) && !e.is_symlink(ec)) {
        const auto size = e.file_size(ec);
        if (!ec) {
          out.bytes += static_cast<std::int64_t>(size);
          ++out.files;
        }
      }
    }
  fs::remove_all(dir);
  return out;
}

}  // namespace sph::server
