#!/usr/bin/env bash
# Kane, Ryan & Banerjee's spin-up beam: reduces the 3-D beam (10 fixed-interface modes, the tip
# marker, geometric stiffening), spins it up to 6 and 10 rad/s with stiffening and to 6 rad/s
# without it, and compares the tip deflection with the 1-D rotating beam (compare.py, which runs
# tests/validation/spin_up_reference.py), with a plot out/spin_up.png.
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
"$flexmbs" reduce beam.yaml -o "$out/beam.sid.h5" > /dev/null
sed "s|file: out/beam.sid.h5|file: $out/beam.sid.h5|" scene.yaml > "$out/spin_6.yaml"
sed "s|rate: 6,|rate: 10,|" "$out/spin_6.yaml" > "$out/spin_10.yaml"
sed -e "s|      modes: {names|      geometric_stiffening: false\n      modes: {names|" -e "s|end_time: 20|end_time: 11|" \
  "$out/spin_6.yaml" > "$out/spin_6_unstiffened.yaml"
for run in spin_6 spin_10 spin_6_unstiffened; do
  "$flexmbs" simulate "$out/$run.yaml" -o "$out/$run.h5" > "$out/$run.txt"
done
/usr/bin/python3 compare.py --run "$out/spin_6.h5" 6 1 0.011 --run "$out/spin_10.h5" 10 1 0.025 \
  --run "$out/spin_6_unstiffened.h5" 6 0 0.017 8 --diverges-past 1 --plot "$out/spin_up.png"
