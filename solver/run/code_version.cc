#include "solver/run/code_version.h"
// Generated at every build by cmake/write_version.cmake (target sphd_version).
#include "sphd_version.h"

namespace sph {

std::string code_version() {
  return SPHD_VERSION;
}

}  // namespace sph
