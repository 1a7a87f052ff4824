#pragma once
// Pool mode: `mpirun -np N sph-worker --server ADDR`. Rank 0 claims a job from sph-server and
// shares it; all ranks run it; rank 0 reports progress and checkpoints while it runs and
// finishes the attempt with the result manifest; then the next job.
namespace sph::worker::pool {

// Called on every rank after MPI_Init. Returns the process exit code.
int run_pool(int argc, char** argv);

}  // namespace sph::worker::pool
