#include "case/reference_data.h"

#include <filesystem>

#include "case/load.h"
#include "case/reference_table.h"

namespace sph {

void inline_reference_data(v1::Case& c, const std::string& base_dir) {
  if (!c.has_reference() || !c.reference().has_series_data()) return;
  auto* data = c.mutable_reference()->mutable_series_data();
  if (data->file().empty()) return;
  const std::string field = "reference.series_data.file";
  std::filesystem::path p(data->file());
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  ReferenceTable table;
  try {
    table = read_reference_table(p.string());
  } catch (const std::exception& e) {
    throw CaseLoadError(field + ": " + e.what());
  }
  const int column = data->column() == 0 ? 1 : data->column();
  if (column < 1)
    throw CaseLoadError("reference.series_data.column: must be >= 1 (column 0 is the time)");
  data->clear_times();
  data->clear_values();
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (row.size() <= static_cast<std::size_t>(column))
      throw CaseLoadError(field + ": " + p.string() + " data row " + std::to_string(r + 1) +
                          " has no column " + std::to_string(column));
    data->add_times(row[0]);
    data->add_values(row[static_cast<std::size_t>(column)]);
  }
  data->clear_file();
}

}  // namespace sph
