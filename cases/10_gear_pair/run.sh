#!/usr/bin/env bash
# The spur pair driven against a load torque on massless FE teeth and on ISO 6336-1's constant
# c': puts the wheel's start angle (gear_geometry.py) into scene.yaml, writes the ISO variant,
# simulates both (0.6 s, 3.6 mesh periods) and checks the mesh force, the contact ratio's
# single/double pattern and the transmission error against closed forms (compare.py), with a
# plot. About 5 s: CTest runs it whole.
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
angle="$(/usr/bin/python3 gear_geometry.py)"
sed "s|WHEEL_ANGLE|$angle|" scene.yaml > "$out/fe.yaml"
sed '/^    teeth:/,/0.00084956\]}/c\    mesh_stiffness: iso' "$out/fe.yaml" > "$out/iso.yaml"
for run in fe iso; do
  "$flexmbs" simulate "$out/$run.yaml" -o "$out/$run.h5" --json > "$out/$run.json"
done
/usr/bin/python3 compare.py "$out" --plot "$out/gear_pair.png"
