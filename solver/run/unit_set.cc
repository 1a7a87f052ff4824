#include "solver/run/unit_set.h"

#include <algorithm>
#include <limits>

#include <mpi.h>

#include "solver/core/kernel.h"
#include "solver/elastic/concentration_hold.h"
#include "solver/elastic/elastic_solid.h"
#include "solver/elastic/porous_diffusion.h"
#include "solver/physics/density_diffusion.h"
#include "solver/physics/particle_shifting.h"
#include "solver/physics/riemann_dissipation.h"
#include "solver/physics/scalar_transport.h"
#include "solver/physics/surface_tension.h"
#include "solver/physics/wall_motion.h"

namespace sph {

template <int D>
UnitSet<D>::UnitSet(std::vector<std::unique_ptr<Unit<D>>> units) : units_(std::move(units)) {
  for (const auto& u : units_)
    for (std::size_t p = 0; p < kStepPhaseCount; ++p)
      if (u->phases() & phase_bit(static_cast<StepPhase>(p))) by_phase_[p].push_back(u.get());
}

template <int D>
void UnitSet<D>::run(StepPhase phase, StepContext<D>& ctx, std::map<std::string, double>& timers) {
  for (Unit<D>* u : by_phase_[static_cast<std::size_t>(phase)]) {
    const double t0 = MPI_Wtime();
    u->run(phase, ctx);
    timers[u->name()] += MPI_Wtime() - t0;
  }
}

template <int D>
double UnitSet<D>::max_time_step() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& u : units_) dt = std::min(dt, u->max_time_step());
  return dt;
}

// The wiring: one line per unit, in the order the units run within a phase (forces add up
// in this order, which every rank follows, so sums stay rank-independent).
template <int D>
std::vector<std::unique_ptr<Unit<D>>> make_units(const UnitBuildContext<D>& b) {
  std::vector<std::unique_ptr<Unit<D>>> units;
  if (b.c.fluid_model().has_density_diffusion()) {
    // Validation admits it with one fluid material only (solver/physics/density_diffusion.h).
    std::size_t fluid = 0;
    while (fluid < b.fluids.size() && !b.fluids[fluid].fluid) ++fluid;
    if (fluid < b.fluids.size()) {
      const BodyForce<D> none(Vec<D>::Zero(), 0.0, Vec<D>::Zero());
      units.push_back(std::make_unique<DensityDiffusion<D>>(
          b.c.fluid_model().density_diffusion(), b.fluids[fluid],
          b.body_force ? *b.body_force : none, b.h, b.wall_volume, b.cfl_factor));
    }
  }
  if (b.c.fluid_model().has_riemann_dissipation()) {
    // Validation admits it with one fluid material only (solver/physics/riemann_dissipation.h);
    // its momentum term runs first in kForces, right after the fluid forces it completes.
    std::size_t fluid = 0;
    while (fluid < b.fluids.size() && !b.fluids[fluid].fluid) ++fluid;
    if (fluid < b.fluids.size()) {
      const BodyForce<D> none(Vec<D>::Zero(), 0.0, Vec<D>::Zero());
      units.push_back(std::make_unique<RiemannDissipation<D>>(
          b.c.fluid_model().riemann_dissipation(), b.fluids[fluid],
          b.body_force ? *b.body_force : none, b.wall_volume));
    }
  }
  if (b.wall_index) {
    std::vector<MotionPath> paths;
    for (const auto& w : b.c.walls()) paths.emplace_back(w.motion(), D);
    if (WallMotion<D>::any_moves(paths))
      units.push_back(std::make_unique<WallMotion<D>>(
          b.particles, std::move(paths), *b.wall_index,
          b.particles.has("transport_velocity")
              ? &b.particles.template get<Vec<D>>("transport_velocity")
              : nullptr));
  }
  using Scalar = typename ScalarTransport<D>::Field;
  if (b.c.has_thermal())
    units.push_back(std::make_unique<ScalarTransport<D>>(Scalar::kTemperature, b.c, b.materials,
                                                         b.particles, b.h, b.wall_volume,
                                                         b.cfl_factor, b.wall_index));
  Column<double>* concentration = nullptr;
  if (b.c.has_diffusion()) {
    auto diffusion =
        std::make_unique<ScalarTransport<D>>(Scalar::kConcentration, b.c, b.materials, b.particles,
                                             b.h, b.wall_volume, b.cfl_factor, b.wall_index);
    concentration = &diffusion->values();
    units.push_back(std::move(diffusion));
  }
  // The elastic solid, built for the case's kernel (its sums evaluate it at reference
  // distances): after the concentration, whose column its pore pressure reads, and before the
  // porous diffusion, which reads its reference columns, but run after that and the holds, which
  // change the concentration it reads.
  std::unique_ptr<Unit<D>> elastic;
  if (b.c.elastic_bodies_size() > 0) {
    const bool wendland = b.c.kernel() == v1::WENDLAND_C2;
    if (wendland)
      elastic = std::make_unique<ElasticSolid<D, WendlandC2<D>>>(b);
    else
      elastic = std::make_unique<ElasticSolid<D, QuinticSpline<D>>>(b);
    if (concentration && PorousDiffusion<D, WendlandC2<D>>::wanted(b.materials)) {
      if (wendland)
        units.push_back(std::make_unique<PorousDiffusion<D, WendlandC2<D>>>(
            b.c, b.materials, b.particles, b.h, b.cfl_factor, *concentration));
      else
        units.push_back(std::make_unique<PorousDiffusion<D, QuinticSpline<D>>>(
            b.c, b.materials, b.particles, b.h, b.cfl_factor, *concentration));
    }
  }
  // After the diffusion in each phase, before the elastic bodies read the concentration.
  if (concentration && ConcentrationHolds<D>::wanted(b.c))
    units.push_back(std::make_unique<ConcentrationHolds<D>>(b.c, b.particles, *concentration));
  if (elastic) units.push_back(std::move(elastic));
  if (b.c.has_surface_tension())
    units.push_back(std::make_unique<SurfaceTension<D>>(b.c, b.materials, b.particles, b.h,
                                                        b.wall_volume, b.cfl_factor, b.wall_index));
  // Last: it moves the particles at the end of the step, after every unit has read them.
  if (b.c.fluid_model().has_particle_shifting())
    units.push_back(std::make_unique<ParticleShifting<D>>(
        b.c.fluid_model().particle_shifting(), b.fluids, b.particles, b.h, b.wall_volume,
        b.self_kernel, b.c.fluid_model().density() == v1::CONTINUITY));
  return units;
}

template class UnitSet<2>;
template class UnitSet<3>;
template std::vector<std::unique_ptr<Unit<2>>> make_units<2>(const UnitBuildContext<2>&);
template std::vector<std::unique_ptr<Unit<3>>> make_units<3>(const UnitBuildContext<3>&);

}  // namespace sph
