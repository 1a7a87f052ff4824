#!/usr/bin/env bash
# Installs everything sphd needs to build, test and run on Debian 12, from Debian packages.
# Idempotent; uses sudo when not run as root.
#   deploy/install-deps.sh [--with-paraview]
# --with-paraview adds ParaView 5.11 (pvpython) and xvfb, which the ParaView test (ctest -L
# paraview) needs: 145 packages, 146 MB to download, 807 MB on disk (70 s on the test machine
# with part of it in the apt cache), so CI (.ci/run) leaves it out.
set -euo pipefail
with_paraview=0
for arg in "$@"; do
  case "$arg" in
    --with-paraview) with_paraview=1 ;;
    *) echo "usage: deploy/install-deps.sh [--with-paraview]" >&2; exit 2 ;;
  esac
done
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake pkg-config git
  libeigen3-dev                                # vectors and small matrices
  libopenmpi-dev openmpi-bin                   # domain decomposition
  libhdf5-openmpi-dev hdf5-tools               # parallel HDF5 output
  libprotobuf-dev protobuf-compiler            # the case schema
  libgrpc++-dev libgrpc-dev protobuf-compiler-grpc libssl-dev  # the service (gRPC config needs all)
  libsqlite3-dev                               # the job queue
  libcpp-httplib-dev                           # sph-server --metrics-address (Prometheus)
  libgtest-dev libbenchmark-dev                # tests
  clang libclang-rt-14-dev                     # the fuzz targets (libFuzzer, sanitizers)
  python3 python3-numpy python3-h5py python3-matplotlib  # result checks and report plots
  python3-grpcio python3-protobuf python3-pandas  # the sphd Python package (docs/python.md)
  python3-pytest python3-venv python3-pip python3-setuptools  # its tests, its pip install
)
if [ "$with_paraview" -eq 1 ]; then
  packages+=(paraview python3-paraview xvfb xauth)  # tests/paraview/: pvpython under xvfb-run
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
echo "sphd dependencies installed"
