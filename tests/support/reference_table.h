#pragma once
// Reads the reference CSV files under tests/validation/data: '#' comment lines, one header
// line with column names, then comma-separated numbers.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sph::test {

struct ReferenceTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(std::size_t k) const {
    std::vector<double> out;
    for (const auto& r : rows) out.push_back(r.at(k));
    return out;
  }
};

inline ReferenceTable read_reference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  ReferenceTable t;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (header) {
      while (std::getline(ss, cell, ',')) t.columns.push_back(cell);
      header = false;
      continue;
    }
    std::vector<double> row;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    t.rows.push_back(row);
  }
  return t;
}

// Linear interpolation of (x, y) samples at xq (x ascending).
inline double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (xq <= x.front()) return y.front();
  for (std::size_t i = 1; i < x.size(); ++i)
    if (xq <= x[i]) return y[i - 1] + (y[i] - y[i - 1]) * (xq - x[i - 1]) / (x[i] - x[i - 1]);
  return y.back();
}

}  // namespace sph::test
