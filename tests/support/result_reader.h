#pragma once
// Reads result.h5 files in tests (serial HDF5 access; the layout is documented in
// solver/io/result_file.h).
#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sph::test {

struct Snapshot {
  double time = 0;
  std::int64_t step = 0;
  std::vector<double> position, velocity;  // N x 3
  std::vector<double> density, pressure, mass;
  std::vector<std::int64_t> id;
  std::vector<std::uint8_t> kind;
  std::size_t size() const { return id.size(); }
};

class ResultReader {
 public:
  explicit ResultReader(const std::string& path) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) throw std::runtime_error("cannot open " + path);
  }
  ~ResultReader() { H5Fclose(file_); }
  ResultReader(const ResultReader&) = delete;
  ResultReader& operator=(const ResultReader&) = delete;

  int snapshot_count() const {
    int n = 0;
    while (exists(group(n))) ++n;
    return n;
  }
  Snapshot snapshot(int k) const {
    Snapshot s;
    const std::string g = group(k);
    s.time = attr_double(g, "time");
    s.step = static_cast<std::int64_t>(attr_double(g, "step"));
    s.position = read<double>(g + "/position", H5T_NATIVE_DOUBLE);
    s.velocity = read<double>(g + "/velocity", H5T_NATIVE_DOUBLE);
    s.density = read<double>(g + "/density", H5T_NATIVE_DOUBLE);
    s.pressure = read<double>(g + "/pressure", H5T_NATIVE_DOUBLE);
    s.mass = read<double>(g + "/mass", H5T_NATIVE_DOUBLE);
    s.id = read<std::int64_t>(g + "/id", H5T_NATIVE_INT64);
    s.kind = read<std::uint8_t>(g + "/kind", H5T_NATIVE_UINT8);
    return s;
  }
  Snapshot last() const { return snapshot(snapshot_count() - 1); }
  // A per-particle dataset of snapshot k that only some runs have (temperature, material).
  std::vector<double> snapshot_field(int k, const std::string& name) const {
    return read<double>(group(k) + "/" + name, H5T_NATIVE_DOUBLE);
  }
  std::vector<double> series(const std::string& name) const {
    return read<double>("/series/" + name, H5T_NATIVE_DOUBLE);
  }
  bool has_series(const std::string& name) const {
    // H5Lexists needs every intermediate group to exist.
    std::string path = "/series";
    if (H5Lexists(file_, path.c_str(), H5P_DEFAULT) <= 0) return false;
    std::size_t from = 0;
    while (from <= name.size()) {
      const std::size_t slash = name.find('/', from);
      path.append(1, '/').append(name, from,
                                 slash == std::string::npos ? std::string::npos : slash - from);
      if (H5Lexists(file_, path.c_str(), H5P_DEFAULT) <= 0) return false;
      if (slash == std::string::npos) break;
      from = slash + 1;
    }
    return true;
  }
  // Extents of a series dataset: {samples, ...}.
  std::vector<std::size_t> series_shape(const std::string& name) const {
    hid_t d = H5Dopen2(file_, ("/series/" + name).c_str(), H5P_DEFAULT);
    if (d < 0) throw std::runtime_error("no series " + name);
    hid_t sp = H5Dget_space(d);
    const int rank = H5Sget_simple_extent_ndims(sp);
    std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
    H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
    H5Sclose(sp);
    H5Dclose(d);
    return std::vector<std::size_t>(dims.begin(), dims.end());
  }
  std::string meta(const std::string& name) const {
    hid_t g = H5Gopen2(file_, "/meta", H5P_DEFAULT);
    hid_t a = H5Aopen(g, name.c_str(), H5P_DEFAULT);
    if (a < 0) {
      H5Gclose(g);
      throw std::runtime_error("no /meta attribute " + name);
    }
    hid_t t = H5Aget_type(a);
    std::string s(H5Tget_size(t), '\0');
    H5Aread(a, t, s.data());
    H5Tclose(t);
    H5Aclose(a);
    H5Gclose(g);
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
  }

 private:
  static std::string group(int k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/snapshots/%06d", k);
    return buf;
  }
  bool exists(const std::string& path) const {
    return H5Lexists(file_, "/snapshots", H5P_DEFAULT) > 0 &&
           H5Lexists(file_, path.c_str(), H5P_DEFAULT) > 0;
  }
  double attr_double(const std::string& obj, const char* name) const {
    hid_t o = H5Oopen(file_, obj.c_str(), H5P_DEFAULT);
    hid_t a = H5Aopen(o, name, H5P_DEFAULT);
    double v = 0;
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    H5Oclose(o);
    return v;
  }
  template <class T>
  std::vector<T> read(const std::string& path, hid_t type) const {
    hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (d < 0) throw std::runtime_error("no dataset " + path);
    hid_t sp = H5Dget_space(d);
    const hssize_t n = H5Sget_simple_extent_npoints(sp);
    std::vector<T> out(static_cast<std::size_t>(n));
    if (n > 0) H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    H5Sclose(sp);
    H5Dclose(d);
    return out;
  }
  hid_t file_;
};

}  // namespace sph::test
