#!/usr/bin/env bash
# NAFEMS FV52: reduces the thick square plate held as the benchmark holds it (bottom edges in z,
# in-plane rigid motions removed on the mid-plane's centre lines) and held on its side faces,
# has CalculiX solve the same meshes and supports (and the benchmark's support alone), and
# checks the frequencies against each other and against the published ones (check.py), with a
# plot out/fv52.png and the benchmark body's mode shapes out/fv52_modes.png (../mode_shapes.py;
# fv52_coarse_modes.png in the short mode). Full run: hex20 20 x 20 x 4, and 8 x 8 x 2 for the
# refinement check; --short: 8 x 8 x 2 only (CTest).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"

# CalculiX on mesh GEO (tests/peers/ccx_modal.py), the plate's material, the given modes and supports.
ccx() {
  local geo="$1"; shift
  /usr/bin/python3 ../../tests/peers/ccx_modal.py "$here/../../meshes/$geo" --order 2 --youngs-modulus 2.0e11 --poisson-ratio 0.3 \
    --density 8000 "$@"
}

# run_mesh GEO DIR: the body files on mesh GEO reduced by flexmbs, and CalculiX with the same
# supports (as the body files give them) and with the benchmark's support alone (in-plane
# motions free: three rigid modes first), in DIR.
run_mesh() {
  local geo="$1" dir="$2"
  mkdir -p "$dir"
  for body in plate plate_faces; do
    sed "s|file: ../../meshes/nafems_fv52_plate.geo|file: $here/../../meshes/$geo|" "$body.yaml" > "$dir/$body.yaml"
    "$flexmbs" reduce "$dir/$body.yaml" -o "$dir/$body.sid.h5" --json > "$dir/$body.reduce.json"
  done
  ccx "$geo" --modes 6 --hold bottom_edges:z --hold mid_x:x --hold mid_y:y > "$dir/plate.ccx.json"
  ccx "$geo" --modes 6 --hold sides_x:yz --hold sides_y:xz > "$dir/plate_faces.ccx.json"
  ccx "$geo" --modes 12 --hold bottom_edges:z > "$dir/plate_free.ccx.json"
}

run_mesh nafems_fv52_plate_coarse.geo "$out/coarse"
if [ "${2:-}" = "--short" ]; then
  /usr/bin/python3 check.py "$out/coarse" --mesh coarse --plot "$out/fv52_coarse.png"
  /usr/bin/python3 ../mode_shapes.py "$out/coarse/plate.sid.h5" "$out/fv52_coarse_modes.png"
else
  run_mesh nafems_fv52_plate.geo "$out"
  /usr/bin/python3 check.py "$out" --mesh full --coarse-out "$out/coarse" --plot "$out/fv52.png"
  /usr/bin/python3 ../mode_shapes.py "$out/plate.sid.h5" "$out/fv52_modes.png"
fi
