#pragma once
// Material parameters resolved from the case with defaults applied: one place that turns
// sound speed / reference pressure / viscosity options into the numbers the solver uses.
#include <string>
#include <vector>

#include "sph/v1/case.pb.h"

namespace sph {

struct MaterialParams {
  std::string name;
  bool fluid = true;
  double rho0 = 1;    // reference density
  bool tait = false;  // Tait (Adami 2012 eq. 3) or linear (Fuchs 2021 eq. 18)
  double gamma = 1;   // Tait exponent (1 for linear)
  double c = 0;       // artificial sound speed
  double p0 = 0;      // reference pressure, rho0 c^2 / gamma
  double chi = 0;     // background pressure of the EOS
  double eta = 0;     // dynamic viscosity
  double nu() const { return eta / rho0; }
  double pb = 0;  // transport-velocity background pressure
};

std::vector<MaterialParams> resolve_materials(const v1::Case& c);

// Index of the material with this name, or -1.
int material_index(const std::vector<MaterialParams>& m, const std::string& name);

}  // namespace sph
