#pragma once
// Small RAII layer over the parallel HDF5 C API. Every function that touches file metadata
// (create, extend, attributes) is collective: all ranks call it with the same arguments.
#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sph::h5 {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Owns an HDF5 identifier and closes it with the right function.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id < 0) throw Error("HDF5: " + what + " failed");
  }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      close_ = o.close_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: the C API takes hid_t everywhere

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

void silence_errors();
void check(herr_t status, const std::string& what);

// Opens (create = truncate) a file for parallel access on `comm`.
Handle open_file(const std::string& path, MPI_Comm comm, bool create);
bool exists(hid_t loc, const std::string& path);
Handle open_or_create_group(hid_t loc, const std::string& path);

void write_attribute(hid_t obj, const std::string& name, const std::string& value);
void write_attribute(hid_t obj, const std::string& name, double value);
void write_attribute(hid_t obj, const std::string& name, std::int64_t value);
std::string read_string_attribute(hid_t obj, const std::string& name);
double read_double_attribute(hid_t obj, const std::string& name);
std::int64_t read_int_attribute(hid_t obj, const std::string& name);

// Collective write of a distributed particle array: each rank writes `local` rows of
// `ncomp` values at row `offset` of a dataset of `total` rows.
void write_rows(hid_t loc, const std::string& name, hid_t type, std::uint64_t total,
                std::uint64_t offset, std::uint64_t local, std::uint64_t ncomp, const void* data);
// Collective read of rows [offset, offset + local) (ncomp values each).
void read_rows(hid_t loc, const std::string& name, hid_t type, std::uint64_t offset,
               std::uint64_t local, std::uint64_t ncomp, void* data);
std::vector<std::uint64_t> dataset_shape(hid_t loc, const std::string& name);

// Extendable time series of rows with shape `row` (chunked, unlimited first dimension).
// append_rows is collective; only rank 0 transfers data (all ranks hold the same rows).
void append_rows(hid_t loc, const std::string& name, const std::vector<std::uint64_t>& row,
                 const std::vector<double>& values, std::uint64_t nrows, bool root);
void truncate_rows(hid_t loc, const std::string& name, std::uint64_t nrows);
// Reads a whole 1D double dataset (every rank).
std::vector<double> read_vector(hid_t loc, const std::string& name);

}  // namespace sph::h5
