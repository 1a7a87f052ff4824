// ParticleStore: columns keep their values through growth and reordering, and hold no more
// memory than the particles need (issue #40: memory per particle).
#include <gtest/gtest.h>

#include <cstdio>

#include "solver/core/particle_store.h"

namespace sph {
namespace {

std::size_t capacity_of_core(const ParticleStore<2>& s) {
  return s.memory_by_owner().at("core");
}

TEST(ParticleStore, GrowsByAnEighthNotByDoubling) {
  ParticleStore<2> s;
  const std::size_t per_particle = s.persistent_bytes_per_particle();
  s.resize(1000, 1000);
  s.release_unused();
  EXPECT_EQ(capacity_of_core(s), 1000 * per_particle);
  // Ghosts appended, as after each search: std::vector alone would reserve 2000.
  s.resize(1010, 1000);
  const double ratio = static_cast<double>(capacity_of_core(s)) / (1010.0 * per_particle);
  std::printf("capacity after growing 1000 -> 1010: %.4f of the size (limit 1.125)\n", ratio);
  EXPECT_LE(ratio, 1.125 + 1e-12);
  // Ghosts dropped and built again within that room: no new allocation, capacity unchanged.
  const std::size_t before = capacity_of_core(s);
  s.drop_ghosts();
  s.resize(1100, 1000);
  EXPECT_EQ(capacity_of_core(s), before);
}

TEST(ParticleStore, ReorderingPermutesEveryColumnAndKeepsItsRoom) {
  ParticleStore<2> s;
  s.resize(5, 5);
  for (std::size_t i = 0; i < 5; ++i) {
    s.x[i] = Vec<2>(static_cast<double>(i), -static_cast<double>(i));
    s.id[i] = static_cast<ParticleId>(100 + i);
    s.rho[i] = 1000.0 + static_cast<double>(i);
  }
  s.resize(7, 5);  // two ghosts
  const std::size_t room = capacity_of_core(s);
  s.reorder_owned({4, 0, 3});
  ASSERT_EQ(s.size(), 3u);
  ASSERT_EQ(s.owned(), 3u);
  const std::size_t order[3] = {4, 0, 3};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(s.id[k], static_cast<ParticleId>(100 + order[k]));
    EXPECT_EQ(s.x[k][0], static_cast<double>(order[k]));
    EXPECT_EQ(s.rho[k], 1000.0 + static_cast<double>(order[k]));
  }
  // The room ghosts were given stays for the next build (no reallocation at the next search).
  EXPECT_EQ(capacity_of_core(s), room);
  s.release_unused();
  EXPECT_EQ(capacity_of_core(s), 3 * s.persistent_bytes_per_particle());
}

}  // namespace
}  // namespace sph
