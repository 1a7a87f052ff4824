#include "server/results/job_files_removal.h"

#include <filesystem>

namespace sph::server {
namespace fs = std::filesystem;

JobFiles measure_job_files(const ResultLayout& layout, const std::string& job_id) {
  JobFiles out;
  const fs::path dir = layout.job_dir(job_id);
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return out;
  // The iterator does not follow directory links; file links are skipped.
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    std::error_code fe;
    if (it->is_symlink(fe) || !it->is_regular_file(fe)) continue;
    const auto size = it->file_size(fe);
    if (fe) continue;
    out.bytes += static_cast<std::int64_t>(size);
    ++out.files;
  }
  return out;
}

void remove_job_files(const ResultLayout& layout, const std::string& job_id) {
  fs::remove_all(layout.job_dir(job_id));
}

}  // namespace sph::server
