#!/usr/bin/env bash
# Reduces the struck rod (gmsh hex8 bar, free-free modes to 45 kHz and the end face's static
# correction mode), simulates the steel sphere striking its end face at 1 m/s (Hertz, implicit
# method, 120 us) and compares the contact force history with Goldsmith's sphere-on-a-long-rod
# reference computed by SciPy, writing the plot out/sphere_on_rod.png.
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
"$flexmbs" reduce rod.yaml -o "$out/rod.sid.h5"
sed "s|file: out/rod.sid.h5|file: $out/rod.sid.h5|" scene.yaml > "$out/scene.yaml"
"$flexmbs" simulate "$out/scene.yaml" -o "$out/results.h5"
/usr/bin/python3 compare.py "$out/results.h5" --plot "$out/sphere_on_rod.png"
