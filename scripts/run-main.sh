#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: installs the Debian packages, builds
# flexmbs, and preprocesses the real case in cases/01_cantilever (see its README).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target flexmbs
exec ./cases/01_cantilever/run.sh build/bin/flexmbs
