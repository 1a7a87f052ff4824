// Instantiations of the 2D simulation (one translation unit per dimension keeps builds
// parallel).
#include "solver/core/kernel.h"
#include "solver/run/simulation_impl.h"

namespace sph {
template class Simulation<2, QuinticSpline<2>>;
template class Simulation<2, WendlandC2<2>>;
}  // namespace sph
