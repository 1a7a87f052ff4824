#include "solver/io/hdf5.h"

#include <numeric>

namespace sph::h5 {

void silence_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Error("HDF5: " + what + " failed");
}

Handle open_file(const std::string& path, MPI_Comm comm, bool create) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "fapl");
  check(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL), "H5Pset_fapl_mpio");
  // The 1.8 file format (readable by every HDF5 since 2008) stores an attribute larger than
  // 64 KiB densely instead of refusing it: /meta/case_text holds the whole case, and a case
  // with meshes or point sets inlined exceeds that.
  if (create)
    check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V110), "H5Pset_libver_bounds");
  if (create)
    return Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
                  "creating " + path);
  return Handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl), H5Fclose, "opening " + path);
}

bool exists(hid_t loc, const std::string& path) {
  // Check each component: H5Lexists on "a/b" fails if "a" is missing.
  std::string partial;
  size_t start = 0;
  while (start <= path.size()) {
    size_t slash = path.find('/', start);
    if (slash == std::string::npos) slash = path.size();
    partial = path.substr(0, slash);
    if (!partial.empty() && partial != "/") {
      const htri_t e = H5Lexists(loc, partial.c_str(), H5P_DEFAULT);
      if (e <= 0) return false;
    }
    start = slash + 1;
  }
  return true;
}

Handle open_or_create_group(hid_t loc, const std::string& path) {
  if (exists(loc, path))
    return Handle(H5Gopen2(loc, path.c_str(), H5P_DEFAULT), H5Gclose, "open group " + path);
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "lcpl");
  check(H5Pset_create_intermediate_group(lcpl, 1), "intermediate groups");
  return Handle(H5Gcreate2(loc, path.c_str(), lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                "create group " + path);
}

namespace {
void replace_attribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) > 0)
    check(H5Adelete(obj, name.c_str()), "delete attribute " + name);
}
template <class T>
void write_scalar_attr(hid_t obj, const std::string& name, hid_t type, T value) {
  replace_attribute(obj, name);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create attribute " + name);
  check(H5Awrite(attr, type, &value), "write attribute " + name);
}
}  // namespace

void write_attribute(hid_t obj, const std::string& name, const std::string& value) {
  replace_attribute(obj, name);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, std::max<size_t>(value.size(), 1)), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string pad");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create attribute " + name);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attr, type, padded.data()), "write attribute " + name);
}

void write_attribute(hid_t obj, const std::string& name, double value) {
  write_scalar_attr(obj, name, H5T_NATIVE_DOUBLE, value);
}

void write_attribute(hid_t obj, const std::string& name, std::int64_t value) {
  write_scalar_attr(obj, name, H5T_NATIVE_INT64, value);
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
  const size_t n = H5Tget_size(type);
  std::string s(n, '\0');
  Handle mem(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(mem, n), "string size");
  // Null-padded like the stored string: the default null-terminated type of the same size
  // keeps its last byte for the terminator, which cut the last character off.
  check(H5Tset_strpad(mem, H5T_STR_NULLPAD), "string pad");
  check(H5Aread(attr, mem, s.data()), "read attribute " + name);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

double read_double_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  double v = 0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

std::int64_t read_int_attribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  std::int64_t v = 0;
  check(H5Aread(attr, H5T_NATIVE_INT64, &v), "read attribute " + name);
  return v;
}

void write_rows(hid_t loc, const std::string& name, hid_t type, std::uint64_t total,
                std::uint64_t offset, std::uint64_t local, std::uint64_t ncomp, const void* data) {
  const int rank = ncomp == 1 ? 1 : 2;
  const hsize_t dims[2] = {total, ncomp};
  Handle fspace(H5Screate_simple(rank, dims, nullptr), H5Sclose, "file space");
  Handle dset(H5Dcreate2(loc, name.c_str(), type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose, "create dataset " + name);
  const hsize_t start[2] = {offset, 0}, count[2] = {local, ncomp};
  const hsize_t one[2] = {1, ncomp};
  Handle mspace(H5Screate_simple(rank, local > 0 ? count : one, nullptr), H5Sclose, "memory space");
  if (local > 0) {
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), "hyperslab");
  } else {
    check(H5Sselect_none(fspace), "select none");
    check(H5Sselect_none(mspace), "select none");
  }
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "dxpl");
  check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "collective transfer");
  check(H5Dwrite(dset, type, mspace, fspace, dxpl, data), "write " + name);
}

std::vector<std::uint64_t> dataset_shape(hid_t loc, const std::string& name) {
  Handle dset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle space(H5Dget_space(dset), H5Sclose, "dataset space");
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return {dims.begin(), dims.end()};
}

void read_rows(hid_t loc, const std::string& name, hid_t type, std::uint64_t offset,
               std::uint64_t local, std::uint64_t ncomp, void* data) {
  Handle dset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle fspace(H5Dget_space(dset), H5Sclose, "file space");
  const int rank = H5Sget_simple_extent_ndims(fspace);
  const hsize_t start[2] = {offset, 0}, count[2] = {local, ncomp}, one[2] = {1, ncomp};
  Handle mspace(H5Screate_simple(rank, local > 0 ? count : one, nullptr), H5Sclose, "memory space");
  if (local > 0) {
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), "hyperslab");
  } else {
    check(H5Sselect_none(fspace), "select none");
    check(H5Sselect_none(mspace), "select none");
  }
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "dxpl");
  check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "collective transfer");
  check(H5Dread(dset, type, mspace, fspace, dxpl, data), "read " + name);
}

void append_rows(hid_t loc, const std::string& name, const std::vector<std::uint64_t>& row,
                 const std::vector<double>& values, std::uint64_t nrows, bool root) {
  const int rank = 1 + static_cast<int>(row.size());
  std::vector<hsize_t> dims(static_cast<size_t>(rank)), maxdims(static_cast<size_t>(rank)),
      chunk(static_cast<size_t>(rank));
  hsize_t row_values = 1;
  for (size_t k = 0; k < row.size(); ++k) {
    dims[k + 1] = maxdims[k + 1] = chunk[k + 1] = row[k];
    row_values *= row[k];
  }
  maxdims[0] = H5S_UNLIMITED;
  chunk[0] = std::max<hsize_t>(1, 4096 / std::max<hsize_t>(row_values, 1));
  hsize_t old_rows = 0;
  Handle dset;
  if (!exists(loc, name)) {
    dims[0] = 0;
    Handle space(H5Screate_simple(rank, dims.data(), maxdims.data()), H5Sclose, "series space");
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dcpl");
    check(H5Pset_chunk(dcpl, rank, chunk.data()), "chunk");
    Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "lcpl");
    check(H5Pset_create_intermediate_group(lcpl, 1), "intermediate groups");
    dset = Handle(H5Dcreate2(loc, name.c_str(), H5T_NATIVE_DOUBLE, space, lcpl, dcpl, H5P_DEFAULT),
                  H5Dclose, "create series " + name);
  } else {
    dset = Handle(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "open series " + name);
    Handle space(H5Dget_space(dset), H5Sclose, "series space");
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    old_rows = dims[0];
  }
  if (nrows == 0) return;
  dims[0] = old_rows + nrows;
  check(H5Dset_extent(dset, dims.data()), "extend series " + name);
  Handle fspace(H5Dget_space(dset), H5Sclose, "series space");
  std::vector<hsize_t> start(static_cast<size_t>(rank), 0), count = dims;
  start[0] = old_rows;
  count[0] = nrows;
  Handle mspace(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, "memory space");
  if (root) {
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "hyperslab");
  } else {
    check(H5Sselect_none(fspace), "select none");
    check(H5Sselect_none(mspace), "select none");
  }
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "dxpl");
  check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "collective transfer");
  check(H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, dxpl, values.data()),
        "write series " + name);
}

void truncate_rows(hid_t loc, const std::string& name, std::uint64_t nrows) {
  Handle dset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "open series " + name);
  Handle space(H5Dget_space(dset), H5Sclose, "series space");
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  dims[0] = std::min<hsize_t>(dims[0], nrows);
  check(H5Dset_extent(dset, dims.data()), "truncate series " + name);
}

std::vector<double> read_vector(hid_t loc, const std::string& name) {
  const auto shape = dataset_shape(loc, name);
  std::uint64_t n = 1;
  for (auto d : shape) n *= d;
  std::vector<double> out(n);
  if (n == 0) return out;
  Handle dset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  check(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
        "read " + name);
  return out;
}

}  // namespace sph::h5
