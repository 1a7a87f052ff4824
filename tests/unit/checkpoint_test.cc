// Checkpoint files (solver/io/checkpoint.h): persistent columns round-trip bytewise, and a
// column that a later version added starts at zero from an older checkpoint, while any other
// missing column refuses the checkpoint, naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "solver/io/checkpoint.h"
#include "tests/support/test_cases.h"

namespace sph {
namespace {

// Five particles with a persistent column "tag", written to `path`.
void write_old_checkpoint(const std::string& path) {
  ParticleStore<2> s;
  auto& tag = s.add<double>("tag", "test", true);
  s.resize(5, 5);
  for (std::size_t i = 0; i < 5; ++i) {
    s.id[i] = static_cast<ParticleId>(i);
    s.x[i] = Vec<2>(0.1 * static_cast<double>(i), 0.0);
    tag[i] = 1.5 + static_cast<double>(i);
  }
  write_checkpoint<2>(Comm(MPI_COMM_WORLD), path, s, {{"time", 0.25}});
}

TEST(Checkpoint, AColumnAddedLaterStartsAtZeroAndAnyOtherMissingOneIsNamed) {
  const std::string dir = test::output_dir("checkpoint_added_column");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/old.h5";
  write_old_checkpoint(path);
  const Comm comm(MPI_COMM_WORLD);

  ParticleStore<2> s;
  auto& tag = s.add<double>("tag", "test", true);
  auto& later = s.add<std::int64_t>("added_later", "test", true);
  later.set_zero_if_absent(true);
  s.resize(3, 3);  // what the scene built before the checkpoint replaces it
  later.fill(7);
  const CheckpointState state = read_checkpoint<2>(comm, path, s);
  EXPECT_EQ(state.at("time"), 0.25);
  const std::size_t n = s.owned();
  const std::size_t total = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(n)));
  EXPECT_EQ(total, 5u);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(tag[i], 1.5 + static_cast<double>(s.id[i])) << "particle " << s.id[i];
    EXPECT_EQ(later[i], 0) << "particle " << s.id[i];
  }

  ParticleStore<2> strict;
  strict.add<double>("tag", "test", true);
  strict.add<double>("required", "test", true);
  try {
    read_checkpoint<2>(comm, path, strict);
    FAIL() << "a checkpoint without a required column was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no column 'required'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sph
