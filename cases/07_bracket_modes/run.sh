#!/usr/bin/env bash
# Reduces the steel L-bracket twice with 12 columns each — its 12 lowest normal modes
# (fixed_interface, bolted at base) and a Craig-Bampton body (6 constraint modes of an averaging
# marker on the leg's top face, 6 fixed-interface modes) —, compares each with the full FE model
# (`flexmbs compare`), has CalculiX solve the full model on the same mesh (tests/peers/ccx_modal.py),
# and checks the numbers README.md gives (check.py), with a plot and the normal-mode body's
# mode shapes (out/bracket_mode_shapes.png, ../mode_shapes.py). --short: the coarse mesh
# (meshes/l_bracket_coarse.geo; CTest).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
geo=l_bracket.geo
[ "${2:-}" = "--short" ] && geo=l_bracket_coarse.geo
for basis in modal cb; do
  body="$out/bracket_$basis"
  sed "s|file: ../../meshes/l_bracket.geo|file: $here/../../meshes/$geo|" "bracket_$basis.yaml" > "$body.yaml"
  "$flexmbs" reduce "$body.yaml" -o "$body.sid.h5" --json > "$body.reduce.json"
  "$flexmbs" compare "$body.sid.h5" "$body.yaml" --modes 12 --json > "$out/compare_$basis.json"
done
/usr/bin/python3 ../../tests/peers/ccx_modal.py "../../meshes/$geo" --order 2 --youngs-modulus 2.1e11 --poisson-ratio 0.3 \
  --density 7850 --modes 12 --hold base:xyz > "$out/full.ccx.json"
/usr/bin/python3 check.py "$out" --plot "$out/bracket_modes.png"
/usr/bin/python3 ../mode_shapes.py "$out/bracket_modal.sid.h5" "$out/bracket_mode_shapes.png"
