// Instantiations of the 3D simulation.
#include "solver/core/kernel.h"
#include "solver/run/simulation_impl.h"

namespace sph {
template class Simulation<3, QuinticSpline<3>>;
template class Simulation<3, WendlandC2<3>>;
}  // namespace sph
