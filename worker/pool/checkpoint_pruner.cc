#include "worker/pool/checkpoint_pruner.h"

#include <algorithm>
#include <filesystem>

namespace sph::worker::pool {

namespace fs = std::filesystem;

void CheckpointPruner::acknowledged(const std::string& path) {
  const std::string dir = fs::path(path).parent_path().string();
  auto& list = kept_[dir];
  if (std::find(list.begin(), list.end(), path) != list.end()) return;  // reported twice
  list.push_back(path);
  while (list.size() > kKeep) {
    const fs::path old(list.front());
    list.erase(list.begin());
    std::error_code ec;
    fs::remove(old, ec);
    // Files that belong to it (a study level's "<checkpoint>.wall").
    const std::string prefix = old.filename().string() + ".";
    for (const auto& e : fs::directory_iterator(old.parent_path(), ec))
      if (e.path().filename().string().starts_with(prefix)) fs::remove(e.path(), ec);
  }
}

}  // namespace sph::worker::pool
