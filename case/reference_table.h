#pragma once
// Tabulated reference data (tests/validation/data/*.csv and the files a case's
// reference.series_data names): '#' comment lines, one header line with column names, then
// comma-separated numbers.
#include <string>
#include <vector>

namespace sph {

struct ReferenceTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  // Column k of every row; throws std::out_of_range when a row is too short.
  std::vector<double> column(std::size_t k) const;
};

// Throws std::runtime_error naming the file (and line) when it cannot be read or parsed, or
// breaks kMaxReferenceRows or kMaxDataLineBytes (case/case_limits.h).
ReferenceTable read_reference_table(const std::string& path);

// Linear interpolation of samples (x ascending) at xq, clamped to the end values outside.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq);

}  // namespace sph
