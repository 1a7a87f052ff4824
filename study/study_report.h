#pragma once
// The tables of a convergence study: study.csv (one row per level, '#' comment lines with the
// case, the error definition and the fitted orders, readable by numpy.loadtxt and by
// study/plot_study.py) and study.md (the same table, the observed order and the resolution
// and cost for 1%, 5% and 10% error).
#include <string>
#include <vector>

#include "study/level_result.h"
#include "study/study_summary.h"

namespace sph::study {

struct StudyDescription {
  std::string case_name;
  std::string case_description;
  std::string error_definition;  // analysis::describe_reference
  std::string ladder;            // how the ladder was given, e.g. "--refine 3 (ratio 1.414)"
  std::string note;              // a problem worth reporting (e.g. Richardson failed), or ""
};

void write_study_csv(const std::string& path, const StudyDescription& d,
                     const std::vector<LevelResult>& levels, const StudySummary& s);

// `plot`: the name of the PNG next to it ("" when there is none).
void write_study_markdown(const std::string& path, const StudyDescription& d,
                          const std::vector<LevelResult>& levels, const StudySummary& s,
                          const std::string& plot);

// "12.3 s", "4.1 min", "2.3 h", "5.6 d".
std::string format_seconds(double s);

}  // namespace sph::study
