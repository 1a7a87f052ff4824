// Each particle guard trips on the state it is meant to catch and names the particle.
#include <gtest/gtest.h>

#include <limits>

#include "solver/diagnostics/stability_guards.h"

namespace sph {
namespace {

struct Fixture {
  ParticleStore<2> s;
  std::vector<MaterialParams> mats;
  std::vector<FluidConstants> fluids;
  Fixture() {
    MaterialParams m;
    m.name = "water";
    m.rho0 = 1;
    m.c = 10;
    m.p0 = 100;
    mats = {m};
    fluids = make_fluid_table(mats);
    s.resize(3, 3);
    for (std::size_t i = 0; i < 3; ++i) {
      s.x[i] = Vec<2>(0.1 * static_cast<double>(i + 1), 0.5);
      s.v[i] = Vec<2>::Zero();
      s.rho[i] = 1;
      s.p[i] = 0;
      s.kind[i] = Kind::kFluid;
      s.material[i] = 0;
      s.id[i] = static_cast<ParticleId>(100 + i);
    }
  }
  std::string scan(bool periodic_x = false) {
    return scan_particles<2>(s, fluids, mats, GuardSettings{}, Vec<2>(0, 0), Vec<2>(1, 1),
                             {periodic_x, false}, 42, 1.5)
        .violation;
  }
};

TEST(StabilityGuards, CleanStatePasses) {
  Fixture f;
  EXPECT_EQ(f.scan(), "");
}

TEST(StabilityGuards, NonFinite) {
  Fixture f;
  f.s.v[1].x() = std::numeric_limits<double>::quiet_NaN();
  const std::string v = f.scan();
  EXPECT_NE(v.find("non-finite"), std::string::npos) << v;
  EXPECT_NE(v.find("id 101"), std::string::npos) << v;
  EXPECT_NE(v.find("step 42"), std::string::npos) << v;
}

TEST(StabilityGuards, DensityDeviation) {
  Fixture f;
  f.s.rho[2] = 1.6;
  const std::string v = f.scan();
  EXPECT_NE(v.find("guards.max_density_deviation"), std::string::npos) << v;
  EXPECT_NE(v.find("id 102"), std::string::npos) << v;
}

TEST(StabilityGuards, SpeedBeyondSoundSpeed) {
  Fixture f;
  f.s.v[0] = Vec<2>(0, -12);
  const std::string v = f.scan();
  EXPECT_NE(v.find("guards.max_mach"), std::string::npos) << v;
}

TEST(StabilityGuards, LeavingTheDomain) {
  Fixture f;
  f.s.x[0] = Vec<2>(1.2, 0.5);
  EXPECT_NE(f.scan().find("left the domain along x"), std::string::npos);
  EXPECT_EQ(f.scan(/*periodic_x=*/true), "");  // a periodic axis wraps instead
}

}  // namespace
}  // namespace sph
