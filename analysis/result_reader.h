#pragma once
// Reads result.h5 files (serial HDF5; the layout is documented in solver/io/result_file.h):
// snapshots with their extra per-particle fields, time series and metadata. Used by the
// error evaluators of convergence studies and by the tests.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sph::analysis {

struct Snapshot {
  double time = 0;
  std::int64_t step = 0;
  std::vector<double> position, velocity;  // N x 3
  std::vector<double> density, pressure, mass;
  std::vector<std::int64_t> id;
  std::vector<std::uint8_t> kind;  // 0 fluid, 1 wall, 2 rigid
  std::size_t size() const { return id.size(); }
};

class ResultReader {
 public:
  // Throws std::runtime_error when the file cannot be opened.
  explicit ResultReader(const std::string& path);
  ~ResultReader();
  ResultReader(const ResultReader&) = delete;
  ResultReader& operator=(const ResultReader&) = delete;

  int snapshot_count() const;
  Snapshot snapshot(int k) const;
  Snapshot last() const { return snapshot(snapshot_count() - 1); }
  // An extra per-particle dataset of snapshot k (e.g. "temperature", "concentration").
  std::vector<double> snapshot_field(int k, const std::string& name) const;

  bool has_series(const std::string& name) const;
  // "/series/<name>" flattened (samples x row).
  std::vector<double> series(const std::string& name) const;
  // Extents of a series dataset: {samples, ...} (e.g. {samples, bodies, D} for bodies/position).
  std::vector<std::size_t> series_shape(const std::string& name) const;
  // The sample times of a series: "G/time" of its group ("probes/P/time" for probe series;
  // phase/* is sampled with the bodies, so "bodies/time"; elastic/* with the diagnostics, so
  // "diagnostics/time").
  std::vector<double> series_time(const std::string& name) const;
  static std::string time_series_of(const std::string& name);

  // A string attribute of /meta; throws when absent.
  std::string meta(const std::string& name) const;

 private:
  bool exists(const std::string& path) const;
  double attr_double(const std::string& obj, const char* name) const;
  template <class T>
  std::vector<T> read(const std::string& path, hid_t type) const;
  hid_t file_;
};

}  // namespace sph::analysis
