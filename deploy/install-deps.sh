#!/usr/bin/env bash
# Installs everything sphd needs to build, test and run on Debian 12, from Debian packages.
# Idempotent; uses sudo when not run as root.
set -euo pipefail
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
  libgtest-dev libbenchmark-dev                # tests
  clang libclang-rt-14-dev                     # the fuzz targets (libFuzzer, sanitizers)
  python3 python3-numpy python3-h5py python3-matplotlib  # result checks and report plots
  python3-grpcio python3-protobuf python3-pandas  # the sphd Python package (docs/python.md)
  python3-pytest python3-venv python3-pip python3-setuptools  # its tests, its pip install
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
echo "sphd dependencies installed"
