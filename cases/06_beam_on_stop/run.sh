#!/usr/bin/env bash
# The free steel beam at 1 m/s onto a rigid stop under its tip (the pad, its last cell's face):
# reduces it with 4-32 free-free modes, with and without the pad's static correction mode,
# simulates each in three formulations (impact on velocity level, on position level, a penalty
# spring per pad vertex; Moreau-Jean by 1 us for 1 ms), integrates the full FE model in each
# formulation with SciPy (full_model.py, flexmbs' K and M) and prints the table of impulse,
# history and peak-force errors against wall time, with a plot (compare.py). Beside it: the beam
# posed in the plane (beam_planar.geo, 17 modes + c) run spatial and with `planar: xy` in each
# formulation, and Moreau-Jean's step sweep of the 17 + c runs (an output every step).
# --short: 17 modes with the correction mode only, the planar runs, the sweep's 2 us against 0.25 us
# (CTest).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
runs="4,8,17,32,4c,8c,17c,32c"
steps="8e-6,4e-6,2e-6,5e-7,1.25e-7"
sweep="penalty,velocity"
if [ "${2:-}" = "--short" ]; then
  runs="17c"
  steps="2e-6,2.5e-7"
  sweep="penalty"
fi

# Writes the three formulations' scenes of run $1 with the body file $2 (the first line $3 if
# given) and simulates each: $out/<formulation>_$1.{yaml,h5,json}.
simulate() {
  local run="$1" sid="$2" first="${3:-}" formulation
  { if [ -n "$first" ]; then echo "$first"; fi; sed "s|file: out/beam.sid.h5|file: $sid|" scene_lcp.yaml; } \
    > "$out/velocity_$run.yaml"
  sed -e "s|theta: 0.5|theta: 1|" -e "s|impact_level: velocity|impact_level: position|" "$out/velocity_$run.yaml" \
    > "$out/position_$run.yaml"
  { if [ -n "$first" ]; then echo "$first"; fi; sed "s|file: out/beam.sid.h5|file: $sid|" scene_penalty.yaml; } \
    > "$out/penalty_$run.yaml"
  for formulation in velocity position penalty; do
    "$flexmbs" simulate "$out/${formulation}_$run.yaml" -o "$out/${formulation}_$run.h5" --json \
      > "$out/${formulation}_$run.json"
  done
}

"$flexmbs" mesh beam.yaml --matrix-market "$out/beam" > /dev/null
for formulation in velocity position penalty; do
  /usr/bin/python3 full_model.py "$out/beam" ../../meshes/beam_stop.geo "$formulation" "$out/full_$formulation.npy" \
    > "$out/full_$formulation.json"
done
for run in ${runs//,/ }; do
  body="$out/beam_$run"
  # The body file with the run's modes (and without the correction mode unless the run has 'c').
  sed -e "s|file: ../../meshes/|file: $here/../../meshes/|" -e "s|  modes: 17|  modes: ${run%c}|" beam.yaml |
    { if [ "${run%c}" = "$run" ]; then grep -v -e "correction_modes:" -e "node_set: pad, direction"; else cat; fi; } \
    > "$body.yaml"
  "$flexmbs" reduce "$body.yaml" -o "$body.sid.h5" > /dev/null
  simulate "$run" "$body.sid.h5"
done

# The posed beam (17 modes and the correction mode), spatial and planar.
sed "s|file: ../../meshes/beam_stop.geo|file: $here/beam_planar.geo|" beam.yaml > "$out/beam_planar.yaml"
"$flexmbs" reduce "$out/beam_planar.yaml" -o "$out/beam_planar.sid.h5" > /dev/null
simulate posed "$out/beam_planar.sid.h5"
simulate planar "$out/beam_planar.sid.h5" "planar: xy"

# The step sweep: the 17 + c runs at the other steps, an output every step.
for formulation in ${sweep//,/ }; do
  for step in ${steps//,/ }; do
    sed -e "s|output_interval: 1.0e-6|output_interval: $step|" -e "s|step: 1.0e-6|step: $step|" \
      "$out/${formulation}_17c.yaml" > "$out/step_${formulation}_$step.yaml"
    "$flexmbs" simulate "$out/step_${formulation}_$step.yaml" -o "$out/step_${formulation}_$step.h5" --json \
      > "$out/step_${formulation}_$step.json"
  done
done
/usr/bin/python3 compare.py "$out" --runs "$runs" --planar --steps "$steps" --sweep "$sweep" \
  --plot "$out/beam_on_stop.png"
