#pragma once
// A number as it appears in messages and generated case text: printf's %g with `digits`
// significant digits (6 for messages; 10 when a test writes a case whose values must survive).
#include <cstdio>
#include <string>

namespace sph {

inline std::string number_text(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace sph
