#!/usr/bin/env bash
# Sets up a fresh machine and runs every test: installs the Debian packages, builds
# warning-free (-Werror) in build/, and runs the GoogleTest suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFLEXMBS_WERROR=ON
cmake --build build -j"$(nproc)"
# Open MPI refuses to run as root without these (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 900
