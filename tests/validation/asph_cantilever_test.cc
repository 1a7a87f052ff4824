// The oscillating cantilever plate of P-II (thesis digest sec. 8.4) with anisotropic kernels
// (ASPH, docs/asph.md) at a CI size: H / dx = 10 through the thickness, resolved isotropically
// and with r = 2 and 4 (particles spaced r dx along the plate), small amplitude (tip velocity
// 0.05 m/s), to t = 0.3 s. The first period against Euler-Bernoulli (0.2541 s) and against the
// isotropic run; the thesis' Table 1 at H / dx = 20 and the large amplitude is
// tests/validation/reports/asph_cantilever.md (tests/validation/asph/run_cantilever.sh).
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/validation/asph/cantilever.h"

namespace sph {
namespace {

TEST(ASPH, CantileverPeriodAgainstIsotropic) {
  const double dx = 0.002, exact = asph_test::euler_bernoulli_period();
  const asph_test::CantileverRun iso =
      asph_test::run_cantilever(dx, 1, 0.05, 0.3, "asph_cantilever_iso");
  ASSERT_EQ(iso.status, "completed");
  for (double r : {2.0, 4.0}) {
    const asph_test::CantileverRun a = asph_test::run_cantilever(
        dx, r, 0.05, 0.3, "asph_cantilever_r" + std::to_string(static_cast<int>(r)));
    ASSERT_EQ(a.status, "completed") << "r = " << r;
    const double vs_beam = a.period / exact - 1, vs_iso = a.period / iso.period - 1;
    std::printf(
        "ASPH cantilever, H/dx = 10, r = %g: %.0f particles (isotropic %.0f), %lld steps, %.2f s "
        "(isotropic %.2f s): first period %.4f s vs Euler-Bernoulli %.4f s (%+.2f%%), vs the "
        "isotropic run %.4f s (%+.2f%%); energy drift %.2g%%\n",
        r, a.particles, iso.particles, a.steps, a.wall_seconds, iso.wall_seconds, a.period, exact,
        100 * vs_beam, iso.period, 100 * vs_iso, 100 * a.energy_drift);
    // Fewer particles by r (up to the rounding of the plate's length to r dx).
    EXPECT_NEAR(a.particles * r / iso.particles, 1.0, 0.1);
    EXPECT_NEAR(a.iso_particles, iso.particles, 0.5);
    // The thesis (its Table 1 at H / dx = 20): r = 2 and 4 within 0.3% of its SPH; here at
    // H / dx = 10 the tolerance is what the isotropic run itself errs by against the beam.
    EXPECT_LT(std::abs(vs_iso), 0.03);
    EXPECT_GT(vs_beam, -0.02);
    EXPECT_LT(vs_beam, 0.10);
    EXPECT_LT(a.energy_drift, 0.01);
  }
}

}  // namespace
}  // namespace sph
