#pragma once
// The phases of one time step, in the order the step loop runs them. This is the one place
// that order is written down; a unit (solver/seam/unit.h) names the phases it runs in and the
// step loop calls it there, after the built-in work of the phase. Kick-drift-kick after
// Fuchs 2021 "Time integration" (eqs. 30-40) and Adami 2012 sec. 3.3:
//
//   kick u^{n+1/2} = u^n + dt/2 a^n (eq. 30), [u~ = u + dt/2 a~, Adami, Hu, Adams 2013],
//   drift r^{n+1} (eq. 32), bodies (eqs. 31, 33-36)            -> kAfterDrift
//                                    (prescribed wall motion, wall values of t^{n+1})
//   open boundaries, migrate + ghosts + neighbour lists       -> kAfterSearch
//   density (summation, eq. 14, or continuity, Adami 2012 eq. 6), EOS (eq. 18; Adami 2012
//   eqs. 3-4), ghost rho and p                                -> kDensity
//   wall condition (Adami 2012 eqs. 22-28), ghost wall values -> kWallState
//                                    (heat and species transport, eqs. 28, 37)
//   a^{n+1} cleared, fluid forces (eqs. 15-16) and the rigid coupling (eq. 19) added
//                                                             -> kForces (more forces added)
//   constraints on a^{n+1} (open-boundary buffers)            -> kConstraints
//   kick u^{n+1} = u^{n+1/2} + dt/2 a^{n+1} (eq. 38), bodies (eqs. 39-40)
//                                                             -> kEndOfStep
//
// The same phases run once, without the kicks and drift, when a run starts (priming a^0).
#include <array>
#include <cstdint>

namespace sph {

enum class StepPhase : std::uint8_t {
  kAfterDrift,   // r^{n+1} and t^{n+1} of owned particles; before the ghosts are sent
  kAfterSearch,  // neighbour lists and the pair kernel are those of r^{n+1}; ghosts current
  kDensity,      // rho^{n+1} and p^{n+1} of owned particles and ghosts
  kWallState,    // wall and rigid particles carry the wall condition's p, rho and velocity
  kForces,       // accumulate into a^{n+1}: s.a[i] += ... (never assign)
  kConstraints,  // prescribed motion overrides a^{n+1} of the particles it owns
  kEndOfStep,    // u^{n+1} final; before the checks, output and the next time step
};

inline constexpr std::size_t kStepPhaseCount = 7;

struct StepPhaseInfo {
  StepPhase phase;
  const char* name;
  const char* equations;  // what the built-in work of the phase implements
};

inline constexpr std::array<StepPhaseInfo, kStepPhaseCount> kStepPhases = {{
    {StepPhase::kAfterDrift, "after_drift", "Fuchs 2021 eqs. 30-36"},
    {StepPhase::kAfterSearch, "after_search", "neighbour search (Fuchs 2021 sec. 4)"},
    {StepPhase::kDensity, "density", "Fuchs 2021 eqs. 14, 18; Adami 2012 eqs. 3-6"},
    {StepPhase::kWallState, "wall_state", "Adami 2012 eqs. 22-28"},
    {StepPhase::kForces, "forces", "Fuchs 2021 eqs. 15-16, 19"},
    {StepPhase::kConstraints, "constraints", "open-boundary buffers (Tafuni 2018)"},
    {StepPhase::kEndOfStep, "end_of_step", "Fuchs 2021 eqs. 38-40"},
}};

// A set of phases, one bit each.
using PhaseMask = std::uint32_t;
constexpr PhaseMask phase_bit(StepPhase p) {
  return PhaseMask{1} << static_cast<unsigned>(p);
}
template <class... P>
constexpr PhaseMask phases(P... p) {
  return (phase_bit(p) | ... | PhaseMask{0});
}

}  // namespace sph
