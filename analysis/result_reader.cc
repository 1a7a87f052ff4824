#include "analysis/result_reader.h"

#include <cstdio>
#include <stdexcept>

namespace sph::analysis {
namespace {

std::string snapshot_group(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "/snapshots/%06d", k);
  return buf;
}

}  // namespace

ResultReader::ResultReader(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw std::runtime_error("cannot open " + path);
}

ResultReader::~ResultReader() {
  H5Fclose(file_);
}

bool ResultReader::exists(const std::string& path) const {
  // H5Lexists needs every intermediate group to exist: check them one by one.
  for (std::size_t pos = path.find('/', 1);; pos = path.find('/', pos + 1)) {
    const std::string prefix = path.substr(0, pos);
    if (H5Lexists(file_, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (pos == std::string::npos) return true;
  }
}

int ResultReader::snapshot_count() const {
  int n = 0;
  while (exists(snapshot_group(n))) ++n;
  return n;
}

Snapshot ResultReader::snapshot(int k) const {
  if (k < 0 || !exists(snapshot_group(k)))
    throw std::runtime_error("the result has no snapshot " + std::to_string(k));
  Snapshot s;
  const std::string g = snapshot_group(k);
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

std::vector<double> ResultReader::snapshot_field(int k, const std::string& name) const {
  return read<double>(snapshot_group(k) + "/" + name, H5T_NATIVE_DOUBLE);
}

bool ResultReader::has_series(const std::string& name) const {
  return exists("/series/" + name);
}

std::vector<double> ResultReader::series(const std::string& name) const {
  return read<double>("/series/" + name, H5T_NATIVE_DOUBLE);
}

std::vector<std::size_t> ResultReader::series_shape(const std::string& name) const {
  hid_t d = H5Dopen2(file_, ("/series/" + name).c_str(), H5P_DEFAULT);
  if (d < 0) throw std::runtime_error("no series " + name);
  hid_t sp = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(sp);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank > 0 ? rank : 0));
  H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
  H5Sclose(sp);
  H5Dclose(d);
  return std::vector<std::size_t>(dims.begin(), dims.end());
}

std::string ResultReader::time_series_of(const std::string& name) {
  if (name.rfind("phase/", 0) == 0) return "bodies/time";
  // The elastic unit's series are sampled with the diagnostics (its sample() runs in
  // Simulation::record_series) and have no time series of their own.
  if (name.rfind("elastic/", 0) == 0) return "diagnostics/time";
  const auto slash = name.rfind('/');
  return (slash == std::string::npos ? std::string() : name.substr(0, slash + 1)) + "time";
}

std::vector<double> ResultReader::series_time(const std::string& name) const {
  return series(time_series_of(name));
}

std::string ResultReader::meta(const std::string& name) const {
  hid_t g = H5Gopen2(file_, "/meta", H5P_DEFAULT);
  if (g < 0) throw std::runtime_error("the result has no /meta group");
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

double ResultReader::attr_double(const std::string& obj, const char* name) const {
  hid_t o = H5Oopen(file_, obj.c_str(), H5P_DEFAULT);
  hid_t a = H5Aopen(o, name, H5P_DEFAULT);
  double v = 0;
  H5Aread(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  H5Oclose(o);
  return v;
}

template <class T>
std::vector<T> ResultReader::read(const std::string& path, hid_t type) const {
  hid_t d = exists(path) ? H5Dopen2(file_, path.c_str(), H5P_DEFAULT) : -1;
  if (d < 0) throw std::runtime_error("the result has no dataset " + path);
  hid_t sp = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(sp);
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0) H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(sp);
  H5Dclose(d);
  return out;
}

}  // namespace sph::analysis
