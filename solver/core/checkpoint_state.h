#pragma once
// The integrator, body and boundary state a checkpoint carries besides the particle columns:
// named numbers, stored as attributes of /state. A value that is missing means the checkpoint
// was written for a different case (fewer bodies, other open-boundary zones) or by an older
// version; the lookup says which value, instead of std::map::at's bare "map::at".
#include <map>
#include <stdexcept>
#include <string>

namespace sph {

using CheckpointState = std::map<std::string, double>;

inline double state_value(const CheckpointState& state, const std::string& key) {
  const auto it = state.find(key);
  if (it == state.end())
    throw std::runtime_error("the checkpoint has no state value '" + key +
                             "': it was written for a different case or by an older version");
  return it->second;
}

}  // namespace sph
