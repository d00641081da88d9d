#!/usr/bin/env bash
# The free steel beam at 1 m/s onto a rigid stop under its tip (the pad, its last cell's face):
# reduces it with 4-32 free-free modes, with and without the pad's static correction mode,
# simulates each in three formulations (impact on velocity level, on position level, a penalty
# spring per pad vertex; Moreau-Jean by 1 us for 1 ms), integrates the full FE model in each
# formulation with SciPy (full_model.py, flexmbs' K and M) and prints the table of impulse,
# history and peak-force errors against wall time, with a plot (compare.py). --short: 4 and 16
# modes with the correction mode only (CTest).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
runs="4,8,16,32,4c,8c,16c,32c"
[ "${2:-}" = "--short" ] && runs="4c,16c"

"$flexmbs" mesh beam.yaml --matrix-market "$out/beam" > /dev/null
for formulation in velocity position penalty; do
  /usr/bin/python3 full_model.py "$out/beam" ../../meshes/beam_stop.geo "$formulation" "$out/full_$formulation.npy" \
    > "$out/full_$formulation.json"
done
for run in ${runs//,/ }; do
  body="$out/beam_$run"
  # The body file with the run's modes (and without the correction mode unless the run has 'c').
  sed -e "s|file: ../../meshes/|file: $here/../../meshes/|" -e "s|  modes: 16|  modes: ${run%c}|" beam.yaml |
    { if [ "${run%c}" = "$run" ]; then grep -v -e "correction_modes:" -e "node_set: pad, direction"; else cat; fi; } \
    > "$body.yaml"
  "$flexmbs" reduce "$body.yaml" -o "$body.sid.h5" > /dev/null
  sed "s|file: out/beam.sid.h5|file: $body.sid.h5|" scene_lcp.yaml > "$out/velocity_$run.yaml"
  sed -e "s|theta: 0.5|theta: 1|" -e "s|impact_level: velocity|impact_level: position|" "$out/velocity_$run.yaml" \
    > "$out/position_$run.yaml"
  sed "s|file: out/beam.sid.h5|file: $body.sid.h5|" scene_penalty.yaml > "$out/penalty_$run.yaml"
  for formulation in velocity position penalty; do
    "$flexmbs" simulate "$out/${formulation}_$run.yaml" -o "$out/${formulation}_$run.h5" --json \
      > "$out/${formulation}_$run.json"
  done
done
/usr/bin/python3 compare.py "$out" --runs "$runs" --plot "$out/beam_on_stop.png"
