#pragma once
// Heat conduction (Fuchs 2021 eq. 28, with latent heat, Remark 3) and species diffusion
// (Remark 4) as units on the seam: the case's `thermal { }` or `diffusion { }` block wired into
// a ScalarDiffusion (solver/physics/scalar_diffusion.h, the physics), run at
//   kAfterDrift  the prescribed wall values of t^{n+1} (before the ghosts are sent);
//   kWallState   the explicit update of eq. 37: rates from T^n at r^{n+1} and rho^{n+1},
//                after the wall condition, with Dirichlet walls' mirror values refreshed
//                on the ghosts first.
// Under quasi-static loading (TimeControl.quasi_static) the update runs at kAfterDrift instead,
// before the elastic bodies relax in the same phase: the thesis' outer loop applies the slow
// process first, then relaxes the solid to it (digest sec. 6.2), so a porous body's shape at
// t^{n+1} is the equilibrium of its saturation at t^{n+1}. The bodies have not moved since the
// last search (their inner steps ran in the previous kAfterDrift), so the rates are those of
// T^n at r^n from that search's lists.
// The value column is persistent, so checkpoints carry it; snapshots write it, and the series
// diagnostics/<name>_min, _max and the content (thermal energy sum m h(T), latent heat
// included; species mass sum m C) follow it. A non-finite value stops the run: an explicit
// diffusion step past its bound (eq. 41) overflows the scalar while the flow is still sound.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "case/materials.h"
#include "case/time_function.h"
#include "solver/diagnostics/stability_guards.h"
#include "solver/physics/scalar_diffusion.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class ScalarTransport final : public Unit<D> {
 public:
  enum class Field { kTemperature, kConcentration };

  ScalarTransport(Field field, const v1::Case& c, const std::vector<MaterialParams>& materials,
                  ParticleStore<D>& s, double h, double wall_volume, double cfl_factor,
                  const Column<std::uint16_t>* wall_index)
      : field_(field),
        c_(c),
        materials_(materials),
        wall_index_(wall_index ? wall_index : &no_walls_),
        before_relaxation_(c.time().has_quasi_static()),
        diffusion_(s, column_name(), diffusion_materials(h, cfl_factor), wall_values(),
                   wall_materials(), wall_volume,
                   field == Field::kTemperature ? c.thermal().volumetric_heat_source() : 0.0,
                   name()) {}

  const char* name() const override {
    return field_ == Field::kTemperature ? "heat_conduction" : "concentration_diffusion";
  }
  PhaseMask phases() const override {
    return sph::phases(StepPhase::kAfterDrift, StepPhase::kWallState);
  }
  Column<double>& values() { return diffusion_.values(); }

  void run(StepPhase phase, StepContext<D>& ctx) override {
    if (phase == StepPhase::kAfterDrift) {
      if (wall_index_ != &no_walls_) diffusion_.set_wall_values(ctx.t, *wall_index_);
      if (!before_relaxation_) return;
    } else if (before_relaxation_) {
      return;
    }
    if (ctx.dt <= 0) return;  // priming: no update
    if (diffusion_.has_dirichlet_walls()) {
      // The mirror values use this step's fluid values at the new positions.
      diffusion_.extrapolate_walls(ctx.neighbors, ctx.pairs, ctx.t, *wall_index_);
      ctx.halo.update(ctx.particles, {&diffusion_.values()});
    }
    diffusion_.run(ctx.neighbors, ctx.pairs, ctx.dt, *wall_index_);
  }

  double max_time_step() const override { return max_dt_; }
  std::size_t scratch_bytes() const override { return diffusion_.bytes(); }
  void declare_output(ResultFile& result) override { result.add_field(diffusion_.values()); }

  void initialize(std::size_t i, const SceneParticle& p) override {
    diffusion_.values()[i] = initial_value(p);
  }

  std::string check(const StepContext<D>& ctx) const override {
    const ParticleStore<D>& s = ctx.particles;
    for (std::size_t i = 0; i < s.owned(); ++i)
      if (s.kind[i] != Kind::kWall && !std::isfinite(diffusion_.values()[i]))
        return "non-finite " + diffusion_.name() +
               describe_particle(s, materials_, i, ctx.step, ctx.t);
    return {};
  }

  // Extremes and content of the owned fluid and rigid particles.
  void sample(ResultFile& result, const StepContext<D>& ctx) override {
    const ParticleStore<D>& s = ctx.particles;
    std::vector<double> ext = {-std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()};
    double content = 0;
    for (std::size_t i = 0; i < s.owned(); ++i) {
      if (s.kind[i] == Kind::kWall) continue;
      const double v = diffusion_.values()[i];
      ext[0] = std::max(ext[0], -v);
      ext[1] = std::max(ext[1], v);
      content += s.m[i] * diffusion_.content(s.material[i], v);
    }
    ctx.comm.max_inplace(ext);
    content = ctx.comm.sum(content);
    const bool heat = field_ == Field::kTemperature;
    const std::string base = heat ? "diagnostics/temperature_" : "diagnostics/concentration_";
    result.put(base + "min", -ext[0]);
    result.put(base + "max", ext[1]);
    result.put(heat ? "diagnostics/thermal_energy" : "diagnostics/species_mass", content);
  }

 private:
  std::string column_name() const {
    return field_ == Field::kTemperature ? "temperature" : "concentration";
  }

  // Per material, with the unit's time-step bound (Fuchs 2021 eq. 41): conduction
  // 0.1 rho c_p h^2 / kappa, diffusion 0.1 rho h^2 / D.
  std::vector<DiffusionMaterial> diffusion_materials(double h, double cfl_factor) {
    std::vector<DiffusionMaterial> m;
    const bool heat = field_ == Field::kTemperature;
    for (const auto& pm : c_.materials()) {
      DiffusionMaterial dm;
      dm.coefficient = heat ? pm.thermal_conductivity() : pm.diffusivity();
      dm.capacity = heat && pm.has_heat_capacity() ? pm.heat_capacity() : 1.0;
      dm.density = pm.density();
      if (!heat) dm.fixed = pm.fixed_concentration();
      // Porous elastic bodies diffuse their saturation themselves
      // (solver/elastic/porous_diffusion.h); here they exchange nothing.
      if (!heat && pm.has_porous()) dm.coefficient = 0;
      // Both materials of a transition with latent heat take it up over the same interval
      // (Fuchs 2021 Remark 3), so a particle's enthalpy does not jump when it changes phase.
      if (heat)
        for (const auto& pt : c_.phase_transitions())
          if (pt.has_latent_heat() &&
              (pt.solid_material() == pm.name() || pt.fluid_material() == pm.name())) {
            dm.latent = pt.latent_heat();
            dm.latent_lo = pt.transition_value() - 0.5 * pt.latent_heat_interval();
            dm.latent_hi = pt.transition_value() + 0.5 * pt.latent_heat_interval();
          }
      if (dm.coefficient > 0)
        max_dt_ = std::min(max_dt_,
                           cfl_factor * 0.1 * pm.density() * dm.capacity * h * h / dm.coefficient);
      m.push_back(dm);
    }
    return m;
  }

  // The schedule of each wall (absent: insulated).
  std::vector<std::optional<TimeFunction>> wall_values() const {
    std::vector<std::optional<TimeFunction>> walls;
    const bool heat = field_ == Field::kTemperature;
    for (const auto& w : c_.walls()) {
      const bool has = heat ? w.has_temperature() : w.has_concentration();
      walls.push_back(has ? std::optional<TimeFunction>(TimeFunction(
                                heat ? w.temperature().value() : w.concentration().value()))
                          : std::nullopt);
    }
    return walls;
  }

  std::vector<int> wall_materials() const {
    std::vector<int> out;
    for (const auto& w : c_.walls())
      out.push_back(w.material().empty() ? -1 : material_index(materials_, w.material()));
    return out;
  }

  // The value a scene particle starts with: its region's, body's, wall's or inflow's, else
  // the block's initial value.
  double initial_value(const SceneParticle& p) const {
    const bool heat = field_ == Field::kTemperature;
    const double fallback =
        heat ? c_.thermal().initial_temperature() : c_.diffusion().initial_concentration();
    switch (p.kind) {
      case Kind::kFluid: {
        if (p.open >= 0) {
          const auto& o = c_.open_boundaries(p.open);
          if (heat && o.has_temperature()) return o.temperature();
          if (!heat && o.has_concentration()) return o.concentration();
          return fallback;
        }
        const auto& r = c_.fluids(p.region);
        if (heat && r.has_initial_temperature()) return r.initial_temperature();
        if (!heat && r.has_initial_concentration()) return r.initial_concentration();
        return fallback;
      }
      case Kind::kRigid: {
        const auto& b = c_.bodies(p.body);
        if (heat && b.has_initial_temperature()) return b.initial_temperature();
        if (!heat && b.has_initial_concentration()) return b.initial_concentration();
        return fallback;
      }
      case Kind::kElastic: {  // conducts like a rigid body (thesis sec. 5.1)
        const auto& b = c_.elastic_bodies(p.elastic);
        if (heat && b.has_initial_temperature()) return b.initial_temperature();
        if (!heat && b.has_initial_concentration()) return b.initial_concentration();
        return fallback;
      }
      case Kind::kWall: {
        const auto& w = c_.walls(p.wall);
        if (heat && w.has_temperature()) return TimeFunction(w.temperature().value()).value(0.0);
        if (!heat && w.has_concentration())
          return TimeFunction(w.concentration().value()).value(0.0);
        return fallback;
      }
    }
    return fallback;
  }

  Field field_;
  const v1::Case& c_;
  const std::vector<MaterialParams>& materials_;
  Column<std::uint16_t> no_walls_{"wall_index", "walls", false};
  const Column<std::uint16_t>* wall_index_;
  bool before_relaxation_;  // quasi-static loading: update at kAfterDrift
  double max_dt_ = std::numeric_limits<double>::infinity();
  ScalarDiffusion<D> diffusion_;  // last: built from the helpers above, which set max_dt_
};

}  // namespace sph
