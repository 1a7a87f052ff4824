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

}  // namespace
}  // namespace sph
