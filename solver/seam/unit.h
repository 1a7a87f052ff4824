#pragma once
// The seam every physics unit plugs into. A unit is one effect (a force, a field, a
// constraint) that a scene composes, like a PySPH equation. It
//  - has a name, which names its timer, its bytes and its entry in the result's active units;
//  - adds the per-particle columns it needs in its constructor, owned by that name
//    (ParticleStore::add(column, name(), persistent)), so memory_by_owner() counts them;
//  - names the step phases it runs in (solver/seam/step_phase.h) and runs there;
//  - adds its force into s.a in StepPhase::kForces and never assigns it: every force unit
//    sees the sum of those before it and leaves it for those after;
//  - adds its snapshot fields once and samples its series (named where they are sampled)
//    when the run does;
//  - gives its columns their initial values for the scene's particles, may stop the run
//    with its own guard, and saves and loads what it keeps outside the particle columns with
//    a checkpoint.
// A case that does not call for a unit never builds it: no column, no timer, no pass.
// docs/adding_a_unit.md walks through adding one.
#include <cstddef>
#include <limits>
#include <string>

#include "solver/core/checkpoint_state.h"
#include "solver/io/result_file.h"
#include "solver/scene/scene_builder.h"
#include "solver/seam/step_context.h"
#include "solver/seam/step_phase.h"

namespace sph {

template <int D>
class Unit {
 public:
  virtual ~Unit() = default;
  virtual const char* name() const = 0;
  virtual PhaseMask phases() const = 0;
  // Runs the unit's work of `phase` on the owned particles (collective where it exchanges).
  virtual void run(StepPhase phase, StepContext<D>& ctx) = 0;
  // The largest time step the unit allows (infinity: no bound). Read after every step; a bound
  // that depends on the state (the elastic solid's, from its speeds) is computed in run() and
  // reduced over the ranks there, so every rank returns the same value.
  virtual double max_time_step() const { return std::numeric_limits<double>::infinity(); }
  // Scratch storage beyond its columns (the columns are counted with the particle store).
  virtual std::size_t scratch_bytes() const { return 0; }
  // Adds the unit's snapshot fields (result.add_field) once, before the result file exists.
  virtual void declare_output(ResultFile& /*result*/) {}
  // One sample of each of its series, result.put("group/name", ...) (collective); the same
  // call declares them before the file is created (ResultFile::declare).
  virtual void sample(ResultFile& /*result*/, const StepContext<D>& /*ctx*/) {}
  // Initial values of the unit's columns for scene particle p, stored in row i.
  virtual void initialize(std::size_t /*i*/, const SceneParticle& /*p*/) {}
  // The unit's own guard at the end of a step: empty, or why the run cannot go on, naming
  // the particle (describe_particle in solver/diagnostics/stability_guards.h).
  virtual std::string check(const StepContext<D>& /*ctx*/) const { return {}; }
  virtual void save(CheckpointState& /*state*/) const {}
  virtual void load(const CheckpointState& /*state*/) {}
};

}  // namespace sph
