#!/usr/bin/env bash
# Preprocesses the steel cantilever: the FE model report, then two reduced bodies (clamped
# normal modes; Craig-Bampton with a tip marker, a contact surface, damping and geometric
# stiffening), its summary and its SIMPACK ASCII SID export, written to out/; then checks what
# README.md says the case shows (check.py; exit 1 if a check fails).
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
"$flexmbs" mesh "$here/beam.yaml"
"$flexmbs" mesh "$here/beam.yaml" --json > "$out/beam.mesh.json"
"$flexmbs" reduce "$here/beam.yaml" -o "$out/beam.sid.h5"
"$flexmbs" reduce "$here/beam_cb.yaml" -o "$out/beam_cb.sid.h5"
"$flexmbs" compare "$out/beam.sid.h5" "$out/beam_cb.sid.h5"
"$flexmbs" info "$out/beam_cb.sid.h5"
"$flexmbs" export "$out/beam_cb.sid.h5" -o "$out/beam_cb.SID_FEM" --format sid-ascii
"$flexmbs" info "$out/beam.sid.h5" --json > "$out/beam.info.json"
"$flexmbs" info "$out/beam_cb.sid.h5" --json > "$out/beam_cb.info.json"
/usr/bin/python3 "$here/check.py" "$out"
/usr/bin/python3 "$here/../mode_shapes.py" "$out/beam.sid.h5" "$out/beam_modes.png" --view 20 -70
echo "wrote $out/beam.mesh.json, $out/beam.sid.h5, $out/beam_cb.sid.h5, $out/beam_cb.SID_FEM, $out/beam_modes.png"
