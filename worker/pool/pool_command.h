#pragma once
// What rank 0 tells the other ranks between jobs: run this claim, or exit. The other ranks
// wait for it without spinning: a blocking MPI_Bcast busy-polls, and a pool that idles for
// hours must not burn a core per rank.
#include <mpi.h>

#include <optional>

#include "sph/v1/service.pb.h"

namespace sph::worker::pool {

// Rank 0: sends the claim to run (or, with nullopt, tells every rank to exit).
// Other ranks: receive it. Collective over `comm`.
std::optional<v1::ClaimResponse> share_command(const std::optional<v1::ClaimResponse>& on_root,
                                               MPI_Comm comm);

}  // namespace sph::worker::pool
