#!/usr/bin/env bash
# Simulates the bouncing ball twice, event-driven and by Moreau-Jean time stepping, and compares
# both with the closed form (impact times, rest at the accumulation time, energy), writing the
# plot out/bouncing_ball.png. No preprocessing: the ball is rigid.
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
"$flexmbs" simulate scene_event_driven.yaml -o "$out/event_driven.h5"
"$flexmbs" simulate scene_moreau_jean.yaml -o "$out/moreau_jean.h5"
/usr/bin/python3 compare.py "$out/event_driven.h5" "$out/moreau_jean.h5" --plot "$out/bouncing_ball.png"
