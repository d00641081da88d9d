#!/usr/bin/env bash
# Sets up a fresh machine and runs the main job: installs the Debian packages, builds
# flexmbs, preprocesses the steel cantilever of cases/01_cantilever, preprocesses and simulates
# the flexible slider-crank of cases/02_slider_crank, simulates the bouncing ball of
# cases/03_bouncing_ball, reduces and simulates the sphere striking a rod of
# cases/04_sphere_on_rod, reduces the NAFEMS FV52 plate of cases/05_nafems_fv52 against
# CalculiX and the published frequencies, runs the beam on a stop of cases/06_beam_on_stop
# against its full FE model, reduces the L-bracket of cases/07_bracket_modes two ways against
# its full FE model and CalculiX, spins up the beam of cases/08_spin_up_beam, presses the
# sphere into the plate of cases/09_sphere_on_plate against its full FE model and drives the
# gear pair of cases/10_gear_pair on elastic teeth and swings the flexible pendulum of
# cases/11_flexible_pendulum (see their READMEs).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target flexmbs
./cases/01_cantilever/run.sh build/bin/flexmbs
./cases/02_slider_crank/run.sh build/bin/flexmbs
./cases/03_bouncing_ball/run.sh build/bin/flexmbs
./cases/04_sphere_on_rod/run.sh build/bin/flexmbs
./cases/05_nafems_fv52/run.sh build/bin/flexmbs
./cases/06_beam_on_stop/run.sh build/bin/flexmbs
./cases/07_bracket_modes/run.sh build/bin/flexmbs
./cases/08_spin_up_beam/run.sh build/bin/flexmbs
./cases/09_sphere_on_plate/run.sh build/bin/flexmbs
./cases/10_gear_pair/run.sh build/bin/flexmbs
exec ./cases/11_flexible_pendulum/run.sh build/bin/flexmbs
