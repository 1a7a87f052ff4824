#include "case/study_spec_text.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "case/number_text.h"
#include "case/study_ladder.h"

namespace sph {
namespace {

bool parse_double(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end != s.c_str() && *end == '\0';
}

}  // namespace

bool set_study_field(v1::StudySpec& spec, const std::string& field, const std::string& value,
                     std::string& error) {
  if (field == "refine") {
    char* end = nullptr;
    const long n = std::strtol(value.c_str(), &end, 10);
    if (value.empty() || *end != '\0' || n < 0 || n > 1000) {
      error = "--refine needs a number of levels (got '" + value + "')";
      return false;
    }
    spec.set_refine(static_cast<int>(n));
    return true;
  }
  if (field == "ratio") {
    double r = 0;
    if (!parse_double(value, r)) {
      error = "--ratio needs a number (got '" + value + "')";
      return false;
    }
    spec.set_ratio(r);
    return true;
  }
  if (field == "dx") {
    spec.clear_dx();
    std::stringstream ss(value);
    std::string item;
    while (std::getline(ss, item, ',')) {
      double d = 0;
      if (!parse_double(item, d)) {
        error = "--dx needs comma-separated spacings, e.g. 0.04,0.02,0.01 (got '" + value + "')";
        return false;
      }
      spec.add_dx(d);
    }
    if (spec.dx_size() == 0) {
      error = "--dx needs comma-separated spacings, e.g. 0.04,0.02,0.01";
      return false;
    }
    return true;
  }
  error = "unknown study field '" + field + "'";
  return false;
}

std::string describe_study(const v1::StudySpec& spec) {
  if (spec.dx_size() > 0) {
    std::string s = "--dx ";
    for (int i = 0; i < spec.dx_size(); ++i) {
      if (i > 0) s += ",";
      s += number_text(spec.dx(i));
    }
    return s;
  }
  return std::string("--refine ") + std::to_string(spec.refine()) + " (ratio " +
         number_text(spec.has_ratio() ? spec.ratio() : kDefaultStudyRatio) + ")";
}

}  // namespace sph
