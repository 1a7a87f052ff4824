// Materials: names, phases, equations of state, viscosities, and references to them.
#include "case/validate/validator.h"

namespace sph::case_validation {
namespace {

// Largest Material.hourglass_control (Ganzenmueller's alpha) accepted.
constexpr double kMaxHourglassControl = 10;

}  // namespace

void Validator::materials() {
  for (int i = 0; i < c_.materials_size(); ++i) {
    const auto& m = c_.materials(i);
    const std::string f = idx("materials", i);
    if (m.name().empty())
      error(cat(f, "name"), "must not be empty");
    else if (!names_.insert(m.name()).second)
      error(cat(f, "name"), "duplicate material name '" + m.name() + "'");
    phase_[m.name()] = m.phase() == v1::SOLID ? v1::SOLID : v1::FLUID;
    positive(m.density(), cat(f, "density"));
    if (m.phase() != v1::SOLID) {
      const auto& e = m.eos();
      const std::string ef = cat(f, "eos");
      if (e.has_sound_speed() == e.has_reference_pressure())
        error(ef, "give exactly one of sound_speed and reference_pressure");
      if (e.has_sound_speed()) positive(e.sound_speed(), cat(ef, "sound_speed"));
      if (e.has_reference_pressure())
        positive(e.reference_pressure(), cat(ef, "reference_pressure"));
      if (e.has_gamma()) {
        positive(e.gamma(), cat(ef, "gamma"));
        if (e.kind() != v1::TAIT) error(cat(ef, "gamma"), "only used with kind: TAIT");
      }
      if (!finite(e.background_pressure())) error(cat(ef, "background_pressure"), "must be finite");
      if (m.has_dynamic_viscosity() && m.has_kinematic_viscosity())
        error(f, "give at most one of dynamic_viscosity and kinematic_viscosity");
      if (m.has_dynamic_viscosity())
        non_negative(m.dynamic_viscosity(), cat(f, "dynamic_viscosity"));
      if (m.has_kinematic_viscosity())
        non_negative(m.kinematic_viscosity(), cat(f, "kinematic_viscosity"));
      if (m.has_transport_background_pressure()) {
        non_negative(m.transport_background_pressure(), cat(f, "transport_background_pressure"));
        if (!c_.fluid_model().transport_velocity())
          error(cat(f, "transport_background_pressure"),
                "set, but fluid_model.transport_velocity is not enabled");
      }
    } else if (m.has_eos()) {
      error(cat(f, "eos"), "a SOLID material has no equation of state");
    }
    elastic_constants(m, f);
    // Thermal and diffusion properties: checked against the effects the case enables.
    if (m.has_heat_capacity()) positive(m.heat_capacity(), cat(f, "heat_capacity"));
    if (m.has_thermal_conductivity())
      non_negative(m.thermal_conductivity(), cat(f, "thermal_conductivity"));
    if (m.has_diffusivity()) non_negative(m.diffusivity(), cat(f, "diffusivity"));
    if (!c_.has_thermal() && (m.has_heat_capacity() || m.has_thermal_conductivity()))
      error(cat(f, m.has_heat_capacity() ? "heat_capacity" : "thermal_conductivity"),
            "set, but heat conduction is not enabled (add a `thermal { }` block)");
    if (!c_.has_diffusion() && (m.has_diffusivity() || m.fixed_concentration()))
      error(cat(f, m.has_diffusivity() ? "diffusivity" : "fixed_concentration"),
            "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
  }
}

// Elastic constants (thesis sec. 2.1, eq. 2.6): set on a SOLID material only, each in its
// range. Whether an elastic body's material has them is checked with the body.
void Validator::elastic_constants(const v1::Material& m, const std::string& f) {
  if (m.phase() != v1::SOLID) {
    const std::string why =
        "set on a FLUID material; elastic constants belong to the SOLID "
        "material of an elastic body";
    if (m.has_youngs_modulus()) error(cat(f, "youngs_modulus"), why);
    if (m.has_poisson_ratio()) error(cat(f, "poisson_ratio"), why);
    if (m.elastic_law() != v1::ELASTIC_LAW_UNSPECIFIED) error(cat(f, "elastic_law"), why);
    if (m.elastic_damping() != 0) error(cat(f, "elastic_damping"), why);
    if (m.has_hourglass_control()) error(cat(f, "hourglass_control"), why);
    if (m.has_plasticity()) error(cat(f, "plasticity"), why);
    if (m.has_porous()) error(cat(f, "porous"), why);
    return;
  }
  if (m.has_youngs_modulus())
    positive(m.youngs_modulus(), cat(f, "youngs_modulus"), "must be > 0 [Pa]");
  if (m.has_poisson_ratio() && !(m.poisson_ratio() >= 0 && m.poisson_ratio() < 0.5))
    error(cat(f, "poisson_ratio"),
          "must be in [0, 0.5) (got " + num(m.poisson_ratio()) +
              "); 0.5 is incompressible: the bulk modulus E / (3 (1 - 2 nu)) and with it the "
              "sound speed are infinite, and explicit total Lagrangian SPH cannot run it");
  non_negative(m.elastic_damping(), cat(f, "elastic_damping"));
  // Ganzenmueller's alpha scales a spring of stiffness alpha E / 2 per pair: beyond about 10 it
  // outweighs the material's own stiffness at the particle scale, and the step it needs (bounded
  // by 0.6 / omega_hg, solver/elastic/hourglass_control.h) shrinks as 1 / sqrt(alpha).
  if (m.has_hourglass_control() &&
      !(m.hourglass_control() >= 0 && m.hourglass_control() <= kMaxHourglassControl))
    error(cat(f, "hourglass_control"), "must be in [0, " + num(kMaxHourglassControl) + "] (got " +
                                           num(m.hourglass_control()) +
                                           "); 0 turns the hourglass control off");
  if (m.has_plasticity()) plasticity(m, f);
  if (m.has_porous()) porous(m, f);
  if (!v1::ElasticLaw_IsValid(m.elastic_law()))
    error(cat(f, "elastic_law"), "unknown value " + std::to_string(m.elastic_law()) +
                                     " (SAINT_VENANT_KIRCHHOFF or NEO_HOOKEAN)");
}

// J2 plasticity (thesis eq. 40; solver/elastic/j2_plasticity.h): a positive initial flow
// stress, saturation at or above it, non-negative hardening, and the thesis' elastic energy.
void Validator::plasticity(const v1::Material& m, const std::string& mf) {
  const v1::J2Plasticity& p = m.plasticity();
  const std::string f = cat(mf, "plasticity");
  positive(p.yield_stress(), cat(f, "yield_stress"), "must be > 0 [Pa]");
  if (!finite(p.saturation_stress()) ||
      (p.saturation_stress() != 0 && !(p.saturation_stress() >= p.yield_stress())))
    error(cat(f, "saturation_stress"), "must be >= yield_stress (" + num(p.yield_stress()) +
                                           " Pa) or 0 for none (got " + num(p.saturation_stress()) +
                                           ")");
  non_negative(p.saturation_exponent(), cat(f, "saturation_exponent"));
  non_negative(p.linear_hardening(), cat(f, "linear_hardening"));
  if (m.elastic_law() == v1::SAINT_VENANT_KIRCHHOFF)
    error(cat(mf, "elastic_law"),
          "SAINT_VENANT_KIRCHHOFF with plasticity: the elasto-plastic law's elastic part is the "
          "neo-Hookean-type energy of the thesis (eqs. 33-34); leave elastic_law unset or "
          "NEO_HOOKEAN");
}

void Validator::material_ref(const std::string& name, v1::MaterialPhase want,
                             const std::string& field, bool required) {
  if (name.empty()) {
    if (required) error(field, "is required");
    return;
  }
  auto it = phase_.find(name);
  if (it == phase_.end()) {
    // A few names are enough to spot a typo; all of them, in each of a thousand such errors,
    // would be megabytes.
    std::string known;
    int listed = 0;
    for (const auto& n : names_) {
      if (listed == kMaterialsListed) {
        known += " and " + std::to_string(names_.size() - listed) + " more";
        break;
      }
      known += (known.empty() ? "" : ", ") + n;
      ++listed;
    }
    error(field,
          "unknown material '" + name + "' (defined: " + (known.empty() ? "none" : known) + ")");
  } else if (it->second != want) {
    error(field, "material '" + name + "' is " + (it->second == v1::SOLID ? "SOLID" : "FLUID") +
                     ", expected " + (want == v1::SOLID ? "SOLID" : "FLUID"));
  }
}

int Validator::material_position(const std::string& name) const {
  for (int k = 0; k < c_.materials_size(); ++k)
    if (c_.materials(k).name() == name) return k;
  return -1;
}

}  // namespace sph::case_validation
