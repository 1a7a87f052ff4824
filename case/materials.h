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
  // Elastic constants of a SOLID material for elastic bodies (thesis sec. 2.1; proto
  // Material.youngs_modulus ...); 0 where the case gives none.
  double youngs_modulus = 0;   // E [Pa]
  double poisson_ratio = 0;    // nu
  int elastic_law = 0;         // v1::ElasticLaw value (0 = SAINT_VENANT_KIRCHHOFF)
  double elastic_damping = 0;  // Kelvin-Voigt viscosity eta_d [Pa s]
  // J2 plasticity (Material.plasticity; solver/elastic/j2_plasticity.h): off unless `plastic`;
  // the hardening k(alpha) = sigma_0 + (sigma_inf - sigma_0)(1 - exp(-delta alpha)) + H alpha.
  bool plastic = false;
  double yield_stress = 0;         // sigma_0 [Pa]
  double saturation_stress = 0;    // sigma_inf [Pa] (yield_stress where the case gives 0)
  double saturation_exponent = 0;  // delta
  double linear_hardening = 0;     // H [Pa]
  // Porous solid (Material.porous; P-III eq. 2.21): the saturation diffuses through it
  // (solver/elastic/porous_diffusion.h) and presses with p = C (c - c0).
  bool porous = false;
  double swelling_modulus = 0;      // C [Pa]
  double diffusivity = 0;           // rho D [kg/(m s)] (Material.diffusivity)
  double reference_saturation = 0;  // c0
  // Lame parameters from E and nu (thesis eq. 2.6) and the bulk modulus K = E / (3 (1 - 2 nu)).
  double lame_lambda() const {
    return youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
  double shear_modulus() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3 * (1 - 2 * poisson_ratio)); }
};

std::vector<MaterialParams> resolve_materials(const v1::Case& c);

// Index of the material with this name, or -1.
int material_index(const std::vector<MaterialParams>& m, const std::string& name);

}  // namespace sph
