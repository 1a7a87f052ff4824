#include "case/materials.h"

#include <cmath>

namespace sph {

std::vector<MaterialParams> resolve_materials(const v1::Case& c) {
  std::vector<MaterialParams> out;
  for (const auto& m : c.materials()) {
    MaterialParams p;
    p.name = m.name();
    p.fluid = m.phase() != v1::SOLID;
    p.rho0 = m.density();
    if (p.fluid) {
      const auto& e = m.eos();
      p.tait = e.kind() == v1::TAIT;
      p.gamma = p.tait ? (e.has_gamma() ? e.gamma() : 7.0) : 1.0;
      if (e.has_sound_speed()) {
        p.c = e.sound_speed();
        p.p0 = p.rho0 * p.c * p.c / p.gamma;  // Adami 2012 eq. 4; Fuchs 2021 eq. 18 for gamma = 1
      } else {
        p.p0 = e.reference_pressure();
        p.c = std::sqrt(p.gamma * p.p0 / p.rho0);
      }
      p.chi = e.background_pressure();
      if (m.has_dynamic_viscosity()) p.eta = m.dynamic_viscosity();
      if (m.has_kinematic_viscosity()) p.eta = m.kinematic_viscosity() * p.rho0;
      p.pb = m.has_transport_background_pressure() ? m.transport_background_pressure() : p.p0;
    }
    p.youngs_modulus = m.youngs_modulus();
    p.poisson_ratio = m.poisson_ratio();
    p.elastic_law = static_cast<int>(m.elastic_law());
    p.elastic_damping = m.elastic_damping();
    p.diffusivity = m.diffusivity();
    if (m.has_porous()) {
      p.porous = true;
      p.swelling_modulus = m.porous().swelling_modulus();
      p.reference_saturation = m.porous().reference_saturation();
    }
    if (m.has_plasticity()) {
      const v1::J2Plasticity& pl = m.plasticity();
      p.plastic = true;
      p.yield_stress = pl.yield_stress();
      p.saturation_stress = pl.saturation_stress() > 0 ? pl.saturation_stress() : pl.yield_stress();
      p.saturation_exponent = pl.saturation_exponent();
      p.linear_hardening = pl.linear_hardening();
    }
    out.push_back(p);
  }
  return out;
}

int material_index(const std::vector<MaterialParams>& m, const std::string& name) {
  for (size_t i = 0; i < m.size(); ++i)
    if (m[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace sph
