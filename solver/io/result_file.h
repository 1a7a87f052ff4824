#pragma once
// The one result file of a run, result.h5, and its XDMF sidecar result.xmf:
//   /meta                      attributes: case text, code version, ranks, active units, status
//   /snapshots/NNNNNN          per output time: position (N x 3), velocity (N x 3), density,
//                              pressure, mass, id, kind, material; attributes time, step, count
//   /series/<group>/<name>     time series (first dimension = samples), each group with "time"
//   /xdmf/polyvertex_<N>       0 .. N-1: the vertex cells result.xmf gives snapshots of N
//                              particles (solver/io/xdmf.h), one dataset per particle count
// The file is opened for each write and closed after it, so a killed run leaves a readable
// file with everything up to its last output. All functions are collective.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/core/particle_store.h"
#include "solver/io/hdf5.h"
#include "solver/io/xdmf.h"
#include "solver/parallel/comm.h"

namespace sph {

class ResultFile {
 public:
  ResultFile(const Comm& comm, const std::string& dir);
  const std::string& h5_path() const { return h5_; }
  const std::string& xmf_path() const { return xmf_; }

  // Series "group/name" are named in one place, where they are sampled: put() appends a
  // sample, and while declare() runs the sampling code once before create() or carry_over(),
  // put() declares the series with the shape of one sample (empty: scalar) instead.
  template <class Sample>
  void declare(Sample&& sample) {
    declaring_ = true;
    sample();
    declaring_ = false;
  }
  void put(const std::string& name, double value) { put(name, {value}, {}); }
  void put(const std::string& name, const std::vector<double>& row,
           std::vector<std::uint64_t> shape);

  // Starts a new result file.
  void create(const std::map<std::string, std::string>& meta);
  // Continues `previous` (an earlier attempt's result, possibly this very file): keeps its
  // snapshots and series samples up to time t and drops later ones. Returns false, and
  // starts a new file, when `previous` is missing or unreadable.
  bool carry_over(const std::string& previous, double t,
                  const std::map<std::string, std::string>& meta);

  // Extra per-particle fields written with every snapshot (body index, temperature, ...).
  void add_field(const Column<std::int32_t>& c) {
    extra_.push_back({&c, H5T_NATIVE_INT32, "Int", 4});
  }
  void add_field(const Column<double>& c) { extra_.push_back({&c, H5T_NATIVE_DOUBLE, "Float", 8}); }
  void add_field(const Column<std::uint8_t>& c) {
    extra_.push_back({&c, H5T_NATIVE_UINT8, "UChar", 1});
  }

  template <int D>
  void write_snapshot(const ParticleStore<D>& s, double t, std::int64_t step);
  // Writes pending series samples.
  void flush();
  void set_meta(const std::map<std::string, std::string>& kv);
  std::size_t snapshot_count() const { return snapshots_.size(); }

 private:
  struct Series {
    std::vector<std::uint64_t> row;
    std::vector<double> pending;
    std::uint64_t pending_rows = 0;
  };
  void flush_into(hid_t file);
  void write_xdmf_on_root() const;

  Comm comm_;
  std::string dir_, h5_, xmf_;
  std::vector<SnapshotEntry> snapshots_;
  std::map<std::string, Series> series_;
  std::vector<XdmfField> fields_;
  struct ExtraField {
    const ColumnBase* column;
    hid_t type;
    const char* xdmf_type;
    int precision;
  };
  std::vector<ExtraField> extra_;
  bool declaring_ = false;
};

}  // namespace sph
