#pragma once
// Tests read result.h5 files with the analysis library's reader (analysis/result_reader.h).
#include "analysis/result_reader.h"

namespace sph::test {

using analysis::ResultReader;
using analysis::Snapshot;

}  // namespace sph::test
