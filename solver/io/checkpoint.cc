#include "solver/io/checkpoint.h"

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "solver/io/hdf5.h"

namespace sph {

template <int D>
void write_checkpoint(const Comm& comm, const std::string& path, const ParticleStore<D>& s,
                      const CheckpointState& state) {
  const std::string tmp = path + ".tmp";
  if (comm.root()) std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  comm.barrier();
  const std::uint64_t local = s.owned();
  std::uint64_t offset = 0, total = 0;
  MPI_Exscan(&local, &offset, 1, MPI_UINT64_T, MPI_SUM, comm.raw());
  if (comm.root()) offset = 0;
  MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm.raw());
  {
    h5::Handle f = h5::open_file(tmp, comm.raw(), true);
    h5::Handle st = h5::open_or_create_group(f, "/state");
    h5::write_attribute(st, "dimension", static_cast<std::int64_t>(D));
    for (const auto& [k, v] : state) h5::write_attribute(st, k, v);
    h5::Handle pg = h5::open_or_create_group(f, "/particles");
    for (const auto& c : s.columns()) {
      if (!c->persistent()) continue;
      h5::write_rows(pg, c->name(), H5T_NATIVE_UINT8, total, offset, local, c->elem_bytes(),
                     c->bytes());
    }
  }
  comm.barrier();
  if (comm.root()) std::filesystem::rename(tmp, path);
  comm.barrier();
}

template <int D>
CheckpointState read_checkpoint(const Comm& comm, const std::string& path, ParticleStore<D>& s) {
  h5::Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "fapl");
  h5::check(H5Pset_fapl_mpio(fapl, comm.raw(), MPI_INFO_NULL), "H5Pset_fapl_mpio");
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "opening checkpoint " + path);
  h5::Handle st(H5Gopen2(f, "/state", H5P_DEFAULT), H5Gclose, "checkpoint /state");
  if (h5::read_int_attribute(st, "dimension") != D)
    throw std::runtime_error("checkpoint " + path + " is for a different dimension");
  CheckpointState state;
  H5Aiterate2(
      st, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t loc, const char* name, const H5A_info_t*, void* data) -> herr_t {
        auto* out = static_cast<CheckpointState*>(data);
        if (std::string(name) != "dimension") (*out)[name] = h5::read_double_attribute(loc, name);
        return 0;
      },
      &state);
  const auto shape = h5::dataset_shape(f, "/particles/id");
  const std::uint64_t total = shape.empty() ? 0 : shape[0];
  const std::uint64_t P = static_cast<std::uint64_t>(comm.size()),
                      r = static_cast<std::uint64_t>(comm.rank());
  const std::uint64_t first = total * r / P, last = total * (r + 1) / P;
  s.resize(last - first, last - first);
  for (const auto& c : s.columns()) {
    if (!c->persistent()) continue;
    const std::string name = "/particles/" + c->name();
    if (!h5::exists(f, name) && c->zero_if_absent()) {
      if (last > first) std::memset(c->bytes(), 0, (last - first) * c->elem_bytes());
      continue;
    }
    if (!h5::exists(f, name))
      throw std::runtime_error("checkpoint " + path + " has no column '" + c->name() +
                               "': it was written for a different case configuration");
    const auto sh = h5::dataset_shape(f, name);
    if (sh.size() < 2 ? c->elem_bytes() != 1 : sh[1] != c->elem_bytes())
      throw std::runtime_error("checkpoint column '" + c->name() +
                               "' has a different element size");
    h5::read_rows(f, name, H5T_NATIVE_UINT8, first, last - first, c->elem_bytes(), c->bytes());
  }
  return state;
}

template void write_checkpoint<2>(const Comm&, const std::string&, const ParticleStore<2>&,
                                  const CheckpointState&);
template void write_checkpoint<3>(const Comm&, const std::string&, const ParticleStore<3>&,
                                  const CheckpointState&);
template CheckpointState read_checkpoint<2>(const Comm&, const std::string&, ParticleStore<2>&);
template CheckpointState read_checkpoint<3>(const Comm&, const std::string&, ParticleStore<3>&);

}  // namespace sph
