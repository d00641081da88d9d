#!/usr/bin/env bash
# The flexible pendulum: reduces the steel strip (gmsh hex20, 10 modes clamped at the pin, the tip
# marker, geometric stiffening) and lets it swing down from the horizontal under gravity on a
# revolute joint with its four in-plane bending modes, with its first mode alone and with the four
# but no stiffening, up to the stored reference's end (reference.json: 2 s, the whole swing there
# and back); compares swing angle and tip deflection (compare.py) with the planar co-rotational
# beam (reference.py, SciPy, 160 elements: 122 s of CPU for 2 s), whose first 0.3 s it reruns
# (0.02 s in the short mode) to check the table is the script's; a plot out/flexible_pendulum.png.
# --short: the four-mode run alone (CTest). The reference reruns on one BLAS thread
# (OPENBLAS_NUM_THREADS=1: its 160 x 160 solves gain nothing from threads on a shared machine).
# Usage: run.sh [path/to/flexmbs] [--short]
set -euo pipefail
source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
short=0
[ "${2:-}" = "--short" ] && short=1
"$flexmbs" reduce pendulum.yaml -o "$out/pendulum.sid.h5" > /dev/null
# The runs end where the stored reference does (reference.json's last time), the short one at
# 0.5 s.
end_time=$(/usr/bin/python3 -c "import json; print(json.load(open('reference.json'))['times'][-1])")
[ $short = 1 ] && end_time=0.5
sed -e "s|file: out/pendulum.sid.h5|file: $out/pendulum.sid.h5|" -e "s|end_time: 2$|end_time: $end_time|" \
  scene.yaml > "$out/modes_4.yaml"
if [ $short = 1 ]; then
  OPENBLAS_NUM_THREADS=1 /usr/bin/python3 reference.py verify reference.json 0.02
  "$flexmbs" simulate "$out/modes_4.yaml" -o "$out/modes_4.h5" --json > "$out/modes_4.json"
  /usr/bin/python3 compare.py reference.json --run "$out/modes_4.h5" "4 modes" 0.05 1e-3 \
    --plot "$out/flexible_pendulum.png"
  exit 0
fi
sed "s|names: \[normal_1, normal_3, normal_4, normal_6\]|names: [normal_1]|" "$out/modes_4.yaml" > "$out/modes_1.yaml"
sed "s|      modes: {names|      geometric_stiffening: false\n      modes: {names|" "$out/modes_4.yaml" \
  > "$out/unstiffened.yaml"
for run in modes_4 modes_1 unstiffened; do
  "$flexmbs" simulate "$out/$run.yaml" -o "$out/$run.h5" --json > "$out/$run.json"
done
OPENBLAS_NUM_THREADS=1 /usr/bin/python3 reference.py verify reference.json 0.3
/usr/bin/python3 compare.py reference.json --run "$out/modes_4.h5" "4 modes" 0.1 1.5e-3 \
  --run "$out/modes_1.h5" "1 mode" 2 0.03 --run "$out/unstiffened.h5" "4 modes, no stiffening" 2 0.01 \
  --plot "$out/flexible_pendulum.png"
