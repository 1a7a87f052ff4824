#pragma once
// study.png from study.csv with matplotlib (study/plot_study.py, compiled into the program).
// The interpreter is started with posix_spawn, never fork(): pool processes run gRPC threads,
// and gRPC does not survive a fork (shared/NOTES.md).
#include <string>

namespace sph::study {

// The interpreter: $SPHD_PYTHON, else /usr/bin/python3 (Debian's, with matplotlib).
std::string default_python();

// Returns "" on success, else why no plot was made (no interpreter, no matplotlib, ...).
// Gives up after timeout_seconds.
std::string plot_study(const std::string& python, const std::string& csv_path,
                       const std::string& png_path, double timeout_seconds = 120);

}  // namespace sph::study
