// Probes.
#include "case/validate/validator.h"

#include <set>

namespace sph::case_validation {

void Validator::probes() {
  std::set<std::string> seen;
  for (int i = 0; i < c_.probes_size(); ++i) {
    const auto& p = c_.probes(i);
    const std::string f = idx("probes", i);
    if (p.name().empty())
      error(cat(f, "name"), "must not be empty");
    else if (!seen.insert(p.name()).second)
      error(cat(f, "name"), "duplicate probe name '" + p.name() + "'");
    vec(p.position(), cat(f, "position"));
    vec(p.line_end(), cat(f, "line_end"));
    if (p.count() < 0 || p.count() > 10000) error(cat(f, "count"), "must be in [0, 10000]");
  }
}

}  // namespace sph::case_validation
