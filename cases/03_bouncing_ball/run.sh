#!/usr/bin/env bash
# Simulates the bouncing ball event-driven and by Moreau-Jean time stepping (h = 1 ms, and 4, 2,
# 0.5 ms for the error's order and its cost), and compares them with the closed form (impact
# times, rest at the accumulation time, energy), writing the plot out/bouncing_ball.png. No
# preprocessing: the ball is rigid.
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
"$flexmbs" simulate scene_event_driven.yaml -o "$out/event_driven.h5"
"$flexmbs" simulate scene_moreau_jean.yaml -o "$out/moreau_jean.h5"
# Moreau-Jean's step sweep (an output every step): its impact-time error against h and CPU.
steps=()
for h in 0.004 0.002 0.0005; do
  sed -e "s|  output_interval: 0.001|  output_interval: $h|" -e "s|  step: 0.001|  step: $h|" \
    scene_moreau_jean.yaml > "$out/moreau_jean_$h.yaml"
  "$flexmbs" simulate "$out/moreau_jean_$h.yaml" -o "$out/moreau_jean_$h.h5" > /dev/null
  steps+=(--step-run "$out/moreau_jean_$h.h5")
done
/usr/bin/python3 compare.py "$out/event_driven.h5" "$out/moreau_jean.h5" "${steps[@]}" --plot "$out/bouncing_ball.png"
