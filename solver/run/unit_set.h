#pragma once
// The units a case calls for, built once from the case (make_units, unit_set.cc: the one
// place a new unit is wired in) and run by the step loop at each phase in the order they were
// built, each under its own timer.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "case/materials.h"
#include "solver/physics/body_force.h"
#include "solver/physics/fluid_table.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

// What a unit's constructor may read: the case, its resolved materials and the resolution.
template <int D>
struct UnitBuildContext {
  const v1::Case& c;
  const std::vector<MaterialParams>& materials;
  const std::vector<FluidConstants>& fluids;  // per material, fluids and solids alike
  ParticleStore<D>& particles;                // to add the unit's columns to
  double dx = 0, h = 0;
  double wall_volume = 0;  // dx^D, the volume of a wall or rigid particle
  double self_kernel = 0;  // W(0)
  double cfl_factor = 1;   // time.cfl_factor (1 when unset)
  const Column<std::uint16_t>* wall_index = nullptr;  // which wall a wall particle is (or null)
  const BodyForce<D>* body_force = nullptr;           // on the fluid (null: none)
};

template <int D>
class UnitSet {
 public:
  UnitSet() = default;
  explicit UnitSet(std::vector<std::unique_ptr<Unit<D>>> units);
  bool empty() const { return units_.empty(); }
  const std::vector<std::unique_ptr<Unit<D>>>& units() const { return units_; }
  // Runs the units of `phase`, in the order built, adding each one's seconds to timers[name].
  void run(StepPhase phase, StepContext<D>& ctx, std::map<std::string, double>& timers);
  // The smallest max_time_step() of the units (infinity without a bound).
  double max_time_step() const;

 private:
  std::vector<std::unique_ptr<Unit<D>>> units_;
  // Per phase, the units that run in it (no test per unit and phase in the step).
  std::vector<Unit<D>*> by_phase_[kStepPhaseCount];
};

// The seam units the case calls for, in the order they run within a phase.
template <int D>
std::vector<std::unique_ptr<Unit<D>>> make_units(const UnitBuildContext<D>& b);

}  // namespace sph
