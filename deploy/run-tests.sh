#!/usr/bin/env bash
# Builds sphd and runs the whole test suite (unit, validation, MPI, service).
#   deploy/run-tests.sh [BUILD_DIR]          (default: build)
# Set SPHD_SANITIZE=ON to build and test with AddressSanitizer + UBSan instead.
# Then the fuzz targets run SPHD_FUZZ_SECONDS (default 60) each (tests/fuzz/run.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
sanitize=${SPHD_SANITIZE:-OFF}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSPHD_SANITIZE="$sanitize"
cmake --build "$build" -j"$(nproc)"
# Root may run mpirun in containers (shared/NOTES.md).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
# Single-process tests start MPI as singletons: without a runtime daemon (isolated) and with the
# ob1 layer over shared memory instead of UCX, MPI_Init takes 0.04 s instead of 0.44 s, which
# was most of a unit test's time (docs/ci.md). Multi-rank runs are on one node here anyway.
export OMPI_MCA_ess_singleton_isolated=1 OMPI_MCA_pml=ob1
# Unit and validation tests run one per core; the MPI, service, Python and ParaView tests
# (several processes each, servers with leases) run alone (RUN_SERIAL in their CMakeLists).
ctest --test-dir "$build" --output-on-failure --timeout 900 -j"$(nproc)"
# The fuzz targets for a bounded time (tests/fuzz/README.md): clang, libFuzzer, ASan, UBSan.
"$root/tests/fuzz/run.sh" "${SPHD_FUZZ_SECONDS:-60}" "$build-fuzz"
