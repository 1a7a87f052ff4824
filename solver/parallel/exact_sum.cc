#include "solver/parallel/exact_sum.h"

#include <mpi.h>

namespace sph::detail {
namespace {

extern "C" void add_int128(void* in, void* inout, int* len, MPI_Datatype*) {
  const auto* a = static_cast<const Int128*>(in);
  auto* b = static_cast<Int128*>(inout);
  for (int i = 0; i < *len; ++i) b[i] += a[i];
}

struct Int128Ops {
  MPI_Datatype type;
  MPI_Op op;
  Int128Ops() {
    MPI_Type_contiguous(sizeof(Int128), MPI_BYTE, &type);
    MPI_Type_commit(&type);
    MPI_Op_create(&add_int128, /*commute=*/1, &op);
  }
};

}  // namespace

void sum_int128(std::vector<Int128>& v, const Comm& comm) {
  if (comm.size() == 1 || v.empty()) return;
  static const Int128Ops ops;  // created once, after MPI_Init (first use is inside a run)
  MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), ops.type, ops.op, comm.raw());
}

}  // namespace sph::detail
