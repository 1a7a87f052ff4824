// The pool's checkpoint pruning on its own (worker/pool/checkpoint_pruner.h): files go only
// once two newer ones in the same folder are acknowledged; unacknowledged ones stay.
#include "worker/pool/checkpoint_pruner.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace sph::worker::pool {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "sphd_pruner_XXXXXX").string();
    path = mkdtemp(t.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

fs::path touch(const fs::path& p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "x";
  return p;
}

TEST(CheckpointPruner, DeletesOnlyWhatTwoNewerAcknowledgedOnesReplace) {
  TempDir d;
  const fs::path a = d.path / "checkpoints";
  std::vector<fs::path> ck;
  for (int k = 1; k <= 5; ++k)
    ck.push_back(touch(a / ("ckpt_00000000000" + std::to_string(k) + ".h5")));
  const fs::path wall = touch(a / "ckpt_000000000001.h5.wall");  // a study level's companion
  CheckpointPruner p;
  p.acknowledged(ck[0].string());
  p.acknowledged(ck[1].string());
  EXPECT_TRUE(fs::exists(ck[0]));
  // ck[2] and ck[3] were written but never acknowledged (the server was away); ck[4] was.
  p.acknowledged(ck[4].string());
  EXPECT_FALSE(fs::exists(ck[0]));
  EXPECT_FALSE(fs::exists(wall));
  EXPECT_TRUE(fs::exists(ck[1]));
  EXPECT_TRUE(fs::exists(ck[2]));
  EXPECT_TRUE(fs::exists(ck[3]));
  EXPECT_TRUE(fs::exists(ck[4]));
  p.acknowledged(ck[4].string());  // acknowledged again (Report, then Finish): no effect
  EXPECT_TRUE(fs::exists(ck[1]));
}

TEST(CheckpointPruner, KeepsEachFolderSeparately) {
  TempDir d;
  // A study runs its levels in folders of their own.
  const fs::path l0 = touch(d.path / "level_0/checkpoints/ckpt_000000000010.h5");
  const fs::path l1a = touch(d.path / "level_1/checkpoints/ckpt_000000000001.h5");
  const fs::path l1b = touch(d.path / "level_1/checkpoints/ckpt_000000000002.h5");
  const fs::path l1c = touch(d.path / "level_1/checkpoints/ckpt_000000000003.h5");
  CheckpointPruner p;
  for (const auto& f : {l0, l1a, l1b, l1c}) p.acknowledged(f.string());
  EXPECT_TRUE(fs::exists(l0));
  EXPECT_FALSE(fs::exists(l1a));
  EXPECT_TRUE(fs::exists(l1b));
  EXPECT_TRUE(fs::exists(l1c));
}

}  // namespace
}  // namespace sph::worker::pool
