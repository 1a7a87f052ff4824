#include "case/distance_grid/read_distance_grid.h"

#include <hdf5.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace sph {
namespace {

// Closes an HDF5 handle when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// Silences the library's printing of its error stack while the file is read (the messages
// below say what is wrong instead) and restores what was set before.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace

void read_distance_grid(const std::string& path, int dim, std::size_t max_nodes,
                        v1::DistanceGrid& out) {
  const std::string dataset = out.dataset().empty() ? "sdf" : out.dataset();
  const std::string where = "'" + path + "'";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error("cannot read " + where + ": no such file");
  const QuietErrors quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(where + " is not an HDF5 file");
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file.get() < 0) throw std::runtime_error("cannot open " + where + " as HDF5");
  if (H5Lexists(file.get(), dataset.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error(where + " has no dataset '" + dataset +
                             "' (DistanceGrid.dataset names it; the default is \"sdf\")");
  const Handle set(H5Dopen2(file.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) throw std::runtime_error(where + ": '" + dataset + "' is not a dataset");
  const Handle type(H5Dget_type(set.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw std::runtime_error(where + ": dataset '" + dataset +
                             "' is not numeric (floating-point or integer values needed)");
  const Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != dim)
    throw std::runtime_error(where + ": dataset '" + dataset + "' has " + std::to_string(rank) +
                             " axes; a " + std::to_string(dim) + "D case needs " +
                             std::to_string(dim) + " ([nz][ny][nx] in 3D, [ny][nx] in 2D)");
  hsize_t dims[3] = {0, 0, 0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  std::size_t nodes = 1;
  for (int a = 0; a < rank; ++a) {
    if (dims[a] < 2)
      throw std::runtime_error(where + ": dataset '" + dataset + "' has " +
                               std::to_string(dims[a]) +
                               " nodes along an axis; at least 2 are needed");
    // Counted in a way that cannot overflow: stop as soon as the limit is passed.
    if (dims[a] > max_nodes / nodes)
      throw std::runtime_error(where + ": dataset '" + dataset +
                               "' has more nodes than the case may hold; the limit is " +
                               std::to_string(max_nodes) + " grid nodes per case");
    nodes *= dims[a];
  }
  std::vector<float> values(nodes);
  if (H5Dread(set.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw std::runtime_error(where + ": cannot read dataset '" + dataset + "'");
  out.clear_counts();
  // The file's axes are C order, slowest first; counts run x, y, z.
  for (int a = rank - 1; a >= 0; --a) out.add_counts(static_cast<std::uint32_t>(dims[a]));
  out.clear_values();
  out.mutable_values()->Reserve(static_cast<int>(nodes));
  for (const float v : values) out.add_values(v);
}

}  // namespace sph
