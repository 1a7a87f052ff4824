#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_target.h"

namespace sph::fuzz {

void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "FUZZ FINDING: %s: %s\n", what, detail.substr(0, 4000).c_str());
  std::abort();
}

}  // namespace sph::fuzz
