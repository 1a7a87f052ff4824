#pragma once
#include <string>

namespace sph {

// The version of the code this binary was built from: project version + `git describe`
// (commit, "-dirty" for uncommitted changes), recorded in every result's metadata.
std::string code_version();

}  // namespace sph
