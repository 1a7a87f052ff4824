#include "worker/pool/pool_command.h"

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

namespace sph::worker::pool {

std::optional<v1::ClaimResponse> share_command(const std::optional<v1::ClaimResponse>& on_root,
                                               MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string payload;
  std::int64_t size = -1;  // -1: exit
  if (rank == 0 && on_root) {
    payload = on_root->SerializeAsString();
    size = static_cast<std::int64_t>(payload.size());
  }
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_INT64_T, 0, comm, &request);
  int done = 0;
  while (true) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (size < 0) return std::nullopt;
  payload.resize(static_cast<size_t>(size));
  MPI_Bcast(payload.data(), static_cast<int>(size), MPI_BYTE, 0, comm);
  v1::ClaimResponse claim;
  claim.ParseFromString(payload);
  return claim;
}

}  // namespace sph::worker::pool
