// Which pair kernel storage a case runs with (case/estimate.h pair_kernel_storage()): the
// compact table by default (each pass over pairs reads it as it is), the double table with
// Riemann dissipation (whose passes need r and dW/dr themselves), and whatever the case asks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "case/estimate.h"
#include "case/load.h"
#include "solver/core/kernel.h"
#include "solver/io/hdf5.h"
#include "solver/run/simulation.h"

namespace sph {
namespace {

v1::Case dam_break() {
  return load_case_file(SPHD_SOURCE_DIR "/cases/dambreak_2d.textproto");
}

TEST(PairKernelStorage, CompactByDefaultTableWithRiemannDissipation) {
  EXPECT_EQ(pair_kernel_storage(dam_break()), v1::PAIR_KERNEL_COMPACT);
  const auto with = [](auto add) {
    v1::Case c = dam_break();
    add(c);
    return pair_kernel_storage(c);
  };
  EXPECT_EQ(with([](v1::Case& c) { c.mutable_surface_tension(); }), v1::PAIR_KERNEL_COMPACT);
  EXPECT_EQ(with([](v1::Case& c) { c.mutable_fluid_model()->mutable_particle_shifting(); }),
            v1::PAIR_KERNEL_COMPACT);
  EXPECT_EQ(with([](v1::Case& c) { c.mutable_fluid_model()->mutable_riemann_dissipation(); }),
            v1::PAIR_KERNEL_TABLE);
  EXPECT_EQ(with([](v1::Case& c) { c.mutable_fluid_model()->mutable_density_diffusion(); }),
            v1::PAIR_KERNEL_COMPACT);
  for (const auto asked :
       {v1::PAIR_KERNEL_TABLE, v1::PAIR_KERNEL_STREAM, v1::PAIR_KERNEL_COMPACT}) {
    EXPECT_EQ(with([&](v1::Case& c) { c.set_pair_kernel_storage(asked); }), asked);
    EXPECT_EQ(with([&](v1::Case& c) {
                c.set_pair_kernel_storage(asked);
                c.mutable_fluid_model()->mutable_riemann_dissipation();
              }),
              asked);
  }
}

// The run keeps what the rule says: 8 bytes a pair (plus the 1/8 spare) by default, 24 with
// the table, none with the stream; and its result says which.
TEST(PairKernelStorage, TheRunKeepsEightBytesAPairByDefault) {
  const std::string out =
      (std::filesystem::temp_directory_path() / ("sphd-pk-" + std::to_string(::getpid()))).string();
  const auto bytes_a_pair = [&](v1::PairKernelStorage asked) {
    v1::Case c = dam_break();
    c.set_pair_kernel_storage(asked);
    RunOptions o;
    o.output_dir = out;
    o.quiet = true;
    Simulation<2, QuinticSpline<2>> sim(c, Comm(MPI_COMM_WORLD), o);
    sim.start();
    for (int k = 0; k < 3; ++k) sim.step();
    return static_cast<double>(sim.memory_by_owner()["pair_kernel"]) /
           static_cast<double>(sim.pairs());
  };
  // The result names the storage the run chose (/meta pair_kernel_storage).
  const auto recorded = [&] {
    const hid_t f = H5Fopen((out + "/result.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t meta = H5Gopen2(f, "/meta", H5P_DEFAULT);
    const std::string v = h5::read_string_attribute(meta, "pair_kernel_storage");
    H5Gclose(meta);
    H5Fclose(f);
    return v;
  };
  const double compact = bytes_a_pair(v1::PAIR_KERNEL_STORAGE_UNSPECIFIED);
  EXPECT_EQ(recorded(), "compact");
  const double table = bytes_a_pair(v1::PAIR_KERNEL_TABLE);
  EXPECT_EQ(recorded(), "table");
  const double stream = bytes_a_pair(v1::PAIR_KERNEL_STREAM);
  EXPECT_EQ(recorded(), "stream");
  std::printf("pair kernel bytes a pair: default %.2f, table %.2f, stream %.2f\n", compact, table,
              stream);
  EXPECT_GE(compact, 8.0);
  EXPECT_LE(compact, 8.0 * 1.25);
  EXPECT_GE(table, 24.0);
  EXPECT_LE(table, 24.0 * 1.25);
  // The stream keeps only its scratch of one particle's pairs.
  EXPECT_LT(stream, 0.1);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace sph
