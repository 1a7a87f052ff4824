#include "server/results/results_owner.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace sph::server {
namespace fs = std::filesystem;

namespace {

bool holds_job_folders(const fs::path& root) {
  for (const auto& e : fs::directory_iterator(root))
    if (e.path().filename().string().rfind("job-", 0) == 0) return true;
  return false;
}

}  // namespace

void claim_results_directory(const ResultLayout& layout, const std::string& database_id,
                             bool database_has_jobs) {
  const fs::path root = layout.root();
  const fs::path marker = root / kDatabaseIdFile;
  if (fs::exists(marker)) {
    std::ifstream in(marker);
    std::string owner;
    std::getline(in, owner);
    if (owner == database_id) return;
    throw std::runtime_error(
        "the results directory " + root.string() + " belongs to another database (" +
        marker.string() + " says " + owner + ", this database is " + database_id +
        "): job ids would collide with its jobs. Start sph-server with the database that "
        "wrote it, or give this database a results directory of its own (--results)");
  }
  if (!database_has_jobs && holds_job_folders(root))
    throw std::runtime_error(
        "the results directory " + root.string() +
        " holds job folders but this database is new: its job-1 would overwrite theirs. Give "
        "the new database an empty results directory (--results), or start sph-server with the "
        "database that wrote them");
  // Written whole under another name and renamed, so a crash leaves no half-written identity.
  const fs::path tmp = root / (std::string(kDatabaseIdFile) + ".tmp");
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << database_id << "\n";
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, marker);
}

}  // namespace sph::server
