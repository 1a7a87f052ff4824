#pragma once
// Per-material constants in the form the hot loops want, indexed by the particle's material.
#include <cmath>
#include <vector>

#include "case/materials.h"

namespace sph {

struct FluidConstants {
  bool fluid = false;
  double rho0 = 1, inv_rho0 = 1, p0 = 0, inv_p0 = 0, gamma = 1, inv_gamma = 1, chi = 0, c = 0;
  double eta = 0, pb = 0;
  int int_gamma = 1;  // gamma when it is a small integer (fast power), else 0

  // p(rho): Adami 2012 eq. 3 (Tait) or Fuchs 2021 eq. 18 (gamma = 1).
  double pressure(double rho) const {
    const double r = rho * inv_rho0;
    return p0 * (power(r) - 1.0) + chi;
  }
  // rho(p), the inverse: Adami 2012 eq. 28. The base is kept positive: a wall particle
  // under strong suction gets a small positive density rather than NaN.
  double density(double p) const {
    const double base = std::max((p - chi) * inv_p0 + 1.0, 1e-3);
    return gamma == 1.0 ? rho0 * base : rho0 * std::pow(base, inv_gamma);
  }
  // The elastic energy a unit of mass stores at density rho, zero at rho0: the work of the
  // pressure compressing it, e = int_{rho0}^{rho} p / rho'^2 drho' (the internal energy whose
  // exchange with the kinetic energy makes an SPH fluid conserve its total energy). For
  // delta = rho / rho0 - 1 it is c^2 delta^2 / 2 + chi delta / rho0 to leading order; the
  // chi term sums to chi (V0 - V), the work of the background pressure on the fluid's volume.
  double elastic_energy(double rho) const {
    const double delta = rho * inv_rho0 - 1.0, shrink = delta / (1.0 + delta);  // 1 - rho0/rho
    const double stiff =
        gamma == 1.0 ? std::log1p(delta) - shrink
                     : std::expm1((gamma - 1.0) * std::log1p(delta)) / (gamma - 1.0) - shrink;
    return inv_rho0 * (p0 * stiff + chi * shrink);
  }

 private:
  double power(double r) const {
    switch (int_gamma) {
      case 1:
        return r;
      case 7: {
        const double r2 = r * r, r4 = r2 * r2;
        return r4 * r2 * r;
      }
      default:
        return std::pow(r, gamma);
    }
  }
};

inline std::vector<FluidConstants> make_fluid_table(const std::vector<MaterialParams>& mats) {
  std::vector<FluidConstants> t;
  for (const auto& m : mats) {
    FluidConstants f;
    f.fluid = m.fluid;
    f.rho0 = m.rho0;
    f.inv_rho0 = 1.0 / m.rho0;
    if (m.fluid) {
      f.p0 = m.p0;
      f.inv_p0 = 1.0 / m.p0;
      f.gamma = m.gamma;
      f.inv_gamma = 1.0 / m.gamma;
      f.chi = m.chi;
      f.c = m.c;
      f.eta = m.eta;
      f.pb = m.pb;
      f.int_gamma = m.gamma == 1.0 ? 1 : m.gamma == 7.0 ? 7 : 0;
    }
    t.push_back(f);
  }
  return t;
}

}  // namespace sph
