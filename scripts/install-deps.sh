#!/usr/bin/env bash
# Installs every Debian package flexmbs needs to build, test and benchmark.
# Idempotent: safe to run on a machine that already has them.
set -euo pipefail

packages=(
  # toolchain and test framework
  build-essential cmake ninja-build pkg-config git
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  # core numerics
  libeigen3-dev libspectra-dev libarpack2-dev libsuitesparse-dev
  # BLAS and LAPACK: the reference headers and link libraries, OpenBLAS at run time
  libblas-dev liblapack-dev libopenblas0-pthread
  # meshing
  libgmsh-dev gmsh
  # distributed eigen-solves
  petsc-dev slepc-dev openmpi-bin libmumps-dev libmetis-dev
  # file format, time integration, contact
  libhdf5-dev libhdf5-openmpi-dev libsundials-dev libsiconos-numerics-dev libfcl-dev
  # command line, input, logging
  libcli11-dev libyaml-cpp-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  # provenance hashes (SHA-256); the content digest of bodies and results (XXH3-128), and
  # xxHash's own programs the tests check it against (xxhsum, python3-xxhash)
  libssl-dev libxxhash-dev xxhash python3-xxhash
  # independent peers for validation and benchmarks
  calculix-ccx python3-dolfinx python3-gmsh python3-numpy python3-scipy
  python3-matplotlib python3-h5py python3-meshio python3-siconos
  # sanitizers and fuzzing (scripts/check-sanitizers.sh, fuzz/)
  clang-14 libclang-rt-14-dev libfuzzer-14-dev
  # independent reader of the ParaView output in tests
  python3-vtk9
  # peak-memory measurement in bench/
  time
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
