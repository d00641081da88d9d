#!/usr/bin/env bash
# The spur pair driven against a load torque on massless FE teeth, on the same FE teeth movable
# (each tooth's deflection a state behind its own dashpot, implicit) and on ISO 6336-1's constant
# c', and (full mode) on c' with the pinion on its flexible shaft (shaft.yaml, Craig-Bampton):
# puts the wheel's start angle (gear_geometry.py) into scene.yaml, writes the variants,
# simulates them (0.6 s, 3.6 mesh periods; the shaft 0.3 s) and checks the mesh force, the
# contact ratio's single/double pattern, the transmission error and the shaft's share of the
# wheel's lag against closed forms (compare.py), with a plot. --short: without the shaft (CTest).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
angle="$(/usr/bin/python3 gear_geometry.py)"
sed "s|WHEEL_ANGLE|$angle|" scene.yaml > "$out/fe.yaml"
sed '/^    teeth:/,/0.00084956\]}/c\    mesh_stiffness: iso' "$out/fe.yaml" > "$out/iso.yaml"
# Movable teeth: each tooth's dashpot c_t = 1.4e4 N s/m (c_t / k_t = 1.0e-5 s, k_t = 1.404e9 N/m
# the pinion tooth's at the pitch point) instead of the pair's damping; the states are stiff: implicit.
sed -e '/^    damping: 8e3$/d' -e 's|^\( *0.0012192, 0.00084956\]}\)$|\1\n      movable: {damping: 1.4e4}|' \
    -e 's|method: explicit|method: implicit|' "$out/fe.yaml" > "$out/movable.yaml"
runs="fe iso movable"
rm -f "$out/shaft.h5"
if [ "${2:-}" != "--short" ]; then
  sed "s|file: shaft.geo|file: $here/shaft.geo|" shaft.yaml > "$out/shaft.yaml"
  "$flexmbs" reduce "$out/shaft.yaml" -o "$out/shaft.sid.h5" > /dev/null
  # The pinion becomes the shaft: its body, the driven joint on the shaft's frame, the mesh on
  # the shaft's 'gear' marker; 0.3 s.
  sed -e "s|    rigid: {mass: 0.18, .*|    flexible: {file: $out/shaft.sid.h5}|" -e '0,/markers: {axis:/{/markers: {axis:/d}' \
      -e "s|j: {body: pinion, marker: axis}|j: {body: pinion, marker: origin}|" \
      -e "s|wheel1: {body: pinion, marker: axis}|wheel1: {body: pinion, marker: gear}|" \
      -e "s|end_time: 0.6|end_time: 0.3|" "$out/iso.yaml" > "$out/shaft_scene.yaml"
  runs="$runs shaft"
fi
for run in $runs; do
  scene="$out/$run.yaml"
  [ "$run" = shaft ] && scene="$out/shaft_scene.yaml"
  "$flexmbs" simulate "$scene" -o "$out/$run.h5" --json > "$out/$run.json"
done
/usr/bin/python3 compare.py "$out" --plot "$out/gear_pair.png"
