#pragma once
// The surge front of the Martin-Moyce dam break (cases/dambreak_martin_moyce_2d: a 1 x 2
// column) against Koshizuka & Oka's 1996 experiment: the mean deviation of the run's front
// series (the case's reference series) from the measured points. Shared by the density
// diffusion and particle shifting tests and their full-size report
// (tests/validation/density_diffusion/impact_report.cc).
#include <string>

#include "analysis/series_data.h"
#include "sph/v1/case.pb.h"
#include "tests/support/reference_table.h"
#include "tests/support/result_reader.h"

namespace sph::test {

// `c`: the case the run used (its reference names the front series); `result_dir`: its output.
inline double surge_front_error(const v1::Case& c, const std::string& result_dir) {
  auto ref = c.reference().series_data();
  ResultReader rr(result_dir + "/result.h5");
  const auto t = rr.series("diagnostics/time");
  const auto front = analysis::series_component(rr.series(ref.series()), t.size(), ref.component(),
                                                false, "front");
  ref.clear_times();
  ref.clear_values();
  for (const auto& row :
       read_reference(std::string(SPHD_SOURCE_DIR) + "/tests/validation/data/"
                                                     "dambreak_koshizuka_oka1996_front_exp.csv")
           .rows) {
    ref.add_times(row[0]);
    ref.add_values(row[1]);
  }
  return analysis::series_data_error(t, front, ref).error;
}

}  // namespace sph::test
