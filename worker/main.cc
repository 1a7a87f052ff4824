// sph-worker: runs cases. Local mode (--case FILE --out DIR) needs no server; pool mode
// (--server ADDR) pulls jobs from sph-server. Run under mpirun for several ranks.
#include <mpi.h>

#include <cstring>

#include "worker/local_run.h"
#include "worker/pool/pool_run.h"

namespace {

bool has_flag(int argc, char** argv, const char* flag) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], flag) == 0) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const int rc = has_flag(argc, argv, "--server") ? sph::worker::pool::run_pool(argc, argv)
                                                  : sph::worker::run_local(argc, argv);
  MPI_Finalize();
  return rc;
}
