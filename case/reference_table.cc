#include "case/reference_table.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "case/case_limits.h"
#include "case/data_lines.h"

namespace sph {

std::vector<double> ReferenceTable::column(std::size_t k) const {
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& r : rows) out.push_back(r.at(k));
  return out;
}

ReferenceTable read_reference_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  ReferenceTable t;
  std::string line;
  bool header = true;
  DataLines lines(in, path);
  while (lines.next(line)) {
    const int lineno = lines.line_number();
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (header) {
      while (std::getline(ss, cell, ',')) t.columns.push_back(cell);
      header = false;
      continue;
    }
    if (t.rows.size() >= static_cast<std::size_t>(kMaxReferenceRows))
      throw std::runtime_error(path + ": more than " + std::to_string(kMaxReferenceRows) +
                               " data rows; the limit is " + std::to_string(kMaxReferenceRows));
    std::vector<double> row;
    while (std::getline(ss, cell, ',')) {
      try {
        std::size_t used = 0;
        row.push_back(std::stod(cell, &used));
        if (cell.find_first_not_of(" \t", used) != std::string::npos)
          throw std::invalid_argument(cell);
      } catch (const std::logic_error&) {
        throw std::runtime_error(path + ":" + std::to_string(lineno) + ": '" + cell +
                                 "' is not a number");
      }
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (x.empty()) return 0;
  if (xq <= x.front()) return y.front();
  for (std::size_t i = 1; i < x.size(); ++i)
    if (xq <= x[i]) {
      const double span = x[i] - x[i - 1];
      return span > 0 ? y[i - 1] + (y[i] - y[i - 1]) * (xq - x[i - 1]) / span : y[i];
    }
  return y.back();
}

}  // namespace sph
