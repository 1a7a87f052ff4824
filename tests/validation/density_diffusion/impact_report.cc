// Prints the figures of the Colagrossi dam break's wall probe (tests/validation/impact_pressure.h)
// of each run against Buchner 2002, and of the surge front of each Martin-Moyce run against
// Koshizuka & Oka 1996, as Markdown table rows for the report of run.sh.
//
// usage: impact_report probe LABEL RUN_DIR...   |   impact_report front LABEL RUN_DIR...
// NOISE_UNTIL=T ends the noise window at t sqrt(g/H) = T (default 8).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "analysis/series_data.h"
#include "case/load.h"
#include "tests/support/reference_table.h"
#include "tests/support/result_reader.h"
#include "tests/validation/impact_pressure.h"
#include "tests/validation/surge_front.h"

namespace {

std::string data(const char* file) {
  return std::string(SPHD_SOURCE_DIR) + "/tests/validation/data/" + file;
}

int probe(int argc, char** argv) {
  const auto exp = sph::test::buchner_p1(data("dambreak_buchner2002_P1_pysph.csv"));
  const auto ref = sph::test::impact_figures(exp);
  std::printf(
      "| run | first impact peak (raw; mean over 0.05) | plateau 3.2-5.2 | second impact "
      "5.5-6.2 | noise (RMS about the running mean over 0.05, t >= 3.2) "
      "|\n|---|---|---|---|---|\n");
  std::printf("| Buchner 2002 P1 | %.2f | %.3f | %.3f | |\n", ref.peak, ref.plateau, ref.second);
  for (int k = 2; k + 1 < argc; k += 2) {
    sph::test::ResultReader rr(std::string(argv[k + 1]) + "/result.h5");
    const auto s = sph::test::probe_signal(rr.series("probes/wall_p1/time"),
                                           rr.series("probes/wall_p1/pressure"));
    sph::test::ImpactWindows w;
    if (const char* until = std::getenv("NOISE_UNTIL")) w.noise1 = std::stod(until);
    const auto f = sph::test::impact_figures(s, w);
    std::printf("| %s | %.2f (%.2fx); %.2f (%.2fx) | %.3f (%+.1f%%) | %.3f (%+.1f%%) | %.4f |\n",
                argv[k], f.peak, f.peak / ref.peak, f.smoothed_peak, f.smoothed_peak / ref.peak,
                f.plateau, 100 * (f.plateau / ref.plateau - 1), f.second,
                100 * (f.second / ref.second - 1), f.noise);
  }
  return 0;
}

int front(int argc, char** argv) {
  std::printf("| run | mean deviation from Koshizuka-Oka (T 0.5-3) |\n|---|---|\n");
  for (int k = 2; k + 1 < argc; k += 2) {
    const std::string dir = argv[k + 1];
    const auto c = sph::load_case_file(std::string(SPHD_SOURCE_DIR) +
                                       "/cases/dambreak_martin_moyce_2d.textproto");
    std::printf("| %s | %.2f%% |\n", argv[k], 100 * sph::test::surge_front_error(c, dir));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  if (what == "probe") return probe(argc, argv);
  if (what == "front") return front(argc, argv);
  std::fprintf(stderr, "usage: impact_report probe|front LABEL RUN_DIR...\n");
  return 2;
}
