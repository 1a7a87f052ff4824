// Equation of state: p(rho) and its inverse rho(p) (Adami 2012 eqs. 3, 28; Fuchs 2021 eq. 18).
#include <gtest/gtest.h>

#include "case/materials.h"
#include "solver/physics/fluid_table.h"

namespace sph {
namespace {

FluidConstants make(bool tait, double c, double chi, double gamma = 7) {
  MaterialParams m;
  m.rho0 = 1000;
  m.tait = tait;
  m.gamma = tait ? gamma : 1;
  m.c = c;
  m.p0 = m.rho0 * c * c / m.gamma;
  m.chi = chi;
  return make_fluid_table({m}).front();
}

TEST(EquationOfState, LinearMatchesFuchsEq18) {
  const FluidConstants f = make(false, 10, 0);
  EXPECT_DOUBLE_EQ(f.pressure(1000), 0.0);
  EXPECT_NEAR(f.pressure(1010), 100.0 * 10.0, 1e-9);  // c^2 (rho - rho0)
}

TEST(EquationOfState, TaitMatchesAdamiEq3) {
  const FluidConstants f = make(true, 20, 5);
  const double p0 = 1000.0 * 400.0 / 7.0;
  EXPECT_NEAR(f.pressure(1000), 5.0, 1e-9);
  EXPECT_NEAR(f.pressure(1020), p0 * (std::pow(1.02, 7) - 1) + 5.0, 1e-6);
}

TEST(EquationOfState, RoundTrip) {
  for (bool tait : {false, true}) {
    for (double gamma : {7.0, 3.0}) {  // 3: the general pow() path
      const FluidConstants f = make(tait, 15, -3.0, gamma);
      for (double rho = 950; rho < 1060; rho += 7.3) {
        EXPECT_NEAR(f.density(f.pressure(rho)), rho, 1e-9 * rho)
            << "tait " << tait << " gamma " << gamma;
      }
    }
  }
}

TEST(EquationOfState, InverseStaysFiniteUnderSuction) {
  const FluidConstants f = make(true, 10, 0);
  EXPECT_GT(f.density(-1e9), 0.0);
  EXPECT_TRUE(std::isfinite(f.density(-1e9)));
}

// The elastic energy per unit mass is the work int_{rho0}^{rho} p / rho'^2 drho': checked
// against Simpson's rule on 2000 intervals (error ~1e-13 of the value here), for both EOS, with a
// background pressure, compressed and expanded.
TEST(EquationOfState, ElasticEnergyIsThePressureWork) {
  for (bool tait : {false, true}) {
    const FluidConstants f = make(tait, 15, 40.0);
    EXPECT_EQ(f.elastic_energy(1000), 0.0);
    for (double rho : {930.0, 990.0, 1001.0, 1080.0}) {
      const int n = 2000;
      const double h = (rho - 1000) / n;
      double sum = 0;
      for (int k = 0; k <= n; ++k) {
        const double r = 1000 + k * h, g = f.pressure(r) / (r * r);
        sum += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * g;
      }
      const double expect = sum * h / 3;
      EXPECT_NEAR(f.elastic_energy(rho), expect, 1e-10 * std::abs(expect))
          << "tait " << tait << " rho " << rho;
    }
  }
  // c^2 delta^2 / 2 (1 - 4 delta / 3 + ...) without background pressure.
  const FluidConstants lin = make(false, 15, 0);
  EXPECT_NEAR(lin.elastic_energy(1001), 225 * 1e-6 / 2 * (1 - 4e-3 / 3), 1e-5 * 225 * 1e-6 / 2);
}

}  // namespace
}  // namespace sph
