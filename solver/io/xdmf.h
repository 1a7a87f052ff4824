#pragma once
// XDMF sidecar describing the particle snapshots of result.h5 as a temporal collection of
// Polyvertex grids, which ParaView 5.11 opens as a time series (shared/NOTES.md). Each grid's
// topology names its connectivity explicitly (0 .. N-1, one vertex cell per particle): without
// it ParaView's default reader (Xdmf3) loads the points and arrays but no cells, and draws
// nothing until a filter is added; the legacy XDMF reader draws either form.
#include <cstdint>
#include <string>
#include <vector>

namespace sph {

struct SnapshotEntry {
  std::string group;  // e.g. "/snapshots/000012"
  double time = 0;
  std::uint64_t count = 0;
};

struct XdmfField {
  std::string name;
  int components = 1;       // 1 scalar, 3 vector
  std::string number_type;  // Float, Int, UInt, UChar
  int precision = 8;
};

// The connectivity dataset of a snapshot of `count` particles, shared by every snapshot of that
// count: "/xdmf/polyvertex_<count>", int64 0 .. count-1.
std::string polyvertex_dataset(std::uint64_t count);

// Writes `path` (atomically: temporary file then rename).
void write_xdmf(const std::string& path, const std::string& h5_name,
                const std::vector<SnapshotEntry>& snapshots, const std::vector<XdmfField>& fields);

}  // namespace sph
