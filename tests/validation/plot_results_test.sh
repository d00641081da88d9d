#!/usr/bin/env bash
# scripts/plot_results.py on two runs made here: the bouncing ball event-driven
# (cases/03_bouncing_ball) and the spur gear pair (tests/data/spur_gear_pair.yaml). Checks the
# summary's lines against closed forms and the file's data (constraint drift, time per part), and
# that every picture is a non-empty PNG.
# Usage: plot_results_test.sh path/to/flexmbs out_dir
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
flexmbs="$1"
out="$2"
mkdir -p "$out"
failures=0

# The summary line starting with $1 must contain $2.
expect() {
  local line
  line="$(grep -F -- "$1" "$summary" || true)"
  if [[ "$line" != *"$2"* ]]; then
    echo "FAIL: expected a line '$1 ... $2 ...', got '${line}'"
    failures=$((failures + 1))
  fi
}

# The number after $2 on the summary line starting with $1 lies within relative $4 of $3.
near() {
  local value
  value="$(grep -F -- "$1" "$summary" | sed -n "s/.*$2 \([-0-9.e+]*\).*/\1/p")"
  if ! awk -v v="$value" -v x="$3" -v tol="$4" 'BEGIN { d = v - x; if (d < 0) d = -d; exit !(v != "" && d <= tol * x) }'; then
    echo "FAIL: $1 $2 $value, expected $3 within relative $4"
    failures=$((failures + 1))
  else
    echo "ok: $1 $2 $value (expected $3, relative $4)"
  fi
}

# Each named file exists, is non-empty and starts with the PNG signature.
expect_png() {
  for png in "$@"; do
    if [[ ! -s "$png" ]] || [[ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" != 89504e470d0a1a0a ]]; then
      echo "FAIL: $png is not a non-empty PNG"
      failures=$((failures + 1))
    fi
  done
}

# The ball: 1 kg, centre dropped from 1.1 m (r = 0.1 m), e = 0.9, at rest from 8.58 s to 9.5 s.
(cd "$root/cases/03_bouncing_ball" && "$flexmbs" simulate scene_event_driven.yaml -o "$out/event_driven.h5" >/dev/null)
summary="$out/event_driven.txt"
/usr/bin/python3 "$root/scripts/plot_results.py" "$out/event_driven.h5" | tee "$summary"
expect "termination:" "end time reached (complete 1)"
expect "duration:" "0 .. 9.5 s, 9501 samples"
expect "events:" "102 (impact 102, separation 0, stick 0, slip 0)"  # the 102 impacts of cases/03's README
expect "contact floor" "sliding in 0,"             # frictionless
near "energy total:" start 10.791 1e-9             # m g h = 10.791 J at rest, 1.1 m up
near "energy total:" end 0.981 1e-8                # m g r at rest on the floor (measured 0.981)
# Starting and ending at rest, the floor's impulse over [0, T] balances gravity's: m g T.
near "contact floor" "normal impulse" 93.195 1e-5  # measured 93.1950953 (1.0e-6)
expect_png "$out/event_driven_energy.png" "$out/event_driven_contact_floor.png"

# The gears: 10 N m on the wheel held by the mesh force along the line of action, T / r_b2 with
# r_b2 = m z2 cos(20 deg) / 2 = 0.0291305 m, one or two pairs in contact (contact ratio 1.5).
"$flexmbs" simulate "$root/tests/data/spur_gear_pair.yaml" -o "$out/gears.h5" >/dev/null
summary="$out/gears.txt"
/usr/bin/python3 "$root/scripts/plot_results.py" "$out/gears.h5" --out "$out/gear_plots" | tee "$summary"
expect "gear mesh" "pairs in contact 1 .. 2"
r_b2="$(awk 'BEGIN { print 2e-3 * 31 * cos(20 * atan2(0, -1) / 180) / 2 }')"
near "gear mesh" "mean mesh force" "$(awk -v r="$r_b2" 'BEGIN { printf "%.9g", 10 / r }')" 3.5e-3  # measured 3.4e-4 (the start's ringing)
expect "joint wheel_axis" "largest |force|"
expect_png "$out/gear_plots/gears_energy.png" "$out/gear_plots/gears_gear_mesh.png" "$out/gear_plots/gears_constraints.png"

# The report's constraint drift and time lines against the file's data: the largest residual, its
# time and the end's value as constraints/ holds them, each part's wall and CPU seconds as
# statistics/ holds them, the total their sum, the parts non-negative; the explicit run's drift
# within its projection (|g| <= 1e-8).
/usr/bin/python3 - "$out/gears.h5" "$summary" <<'PY' || failures=$((failures + 1))
import re
import sys

import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
lines = open(sys.argv[2]).read().splitlines()
bad = []


def line(start):
    found = [l for l in lines if l.startswith(start)]
    if len(found) != 1:
        bad.append(f"no single line '{start}'")
        return ""
    return found[0]


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(b), 1e-300)


t = f["time"][:]
for name in ("position", "velocity"):
    r = f[f"constraints/{name}_residual"][:]
    m = re.search(r"largest (\S+) .* at t = (\S+) s, end (\S+)$", line(f"constraint drift {name}:"))
    if not m or not close(float(m[1]), r.max(), 5e-3) or not close(float(m[2]), t[np.argmax(r)], 1e-5) \
            or not close(float(m[3]), r[-1], 5e-3):
        bad.append(f"constraint drift {name}: {m and m.groups()} against {r.max()}, {t[np.argmax(r)]}, {r[-1]}")
if f["constraints/position_residual"][:].max() > 1e-8:
    bad.append(f"position drift {f['constraints/position_residual'][:].max():.3g} above 1e-8")
parts = [p.decode() for p in f["statistics/parts"][:]]
wall, cpu = f["statistics/wall_seconds"][:], f["statistics/cpu_seconds"][:]
if parts != ["setup", "integration", "output", "total"] or (wall < 0).any() or (cpu < 0).any() \
        or not close(wall[3], wall[:3].sum(), 1e-12) or not close(cpu[3], cpu[:3].sum(), 1e-12) or wall[1] <= 0:
    bad.append(f"statistics {parts} {wall} {cpu}")
for part, w, c in zip(parts, wall, cpu):
    m = re.search(r"wall (\S+) s, cpu (\S+) s$", line(f"time {part}:"))
    if not m or not close(float(m[1]), w, 1e-3) or not close(float(m[2]), c, 1e-3):
        bad.append(f"time {part}: {m and m.groups()} against {w}, {c}")
# The gears have no unilateral contacts: no contact solves.
contact = f["statistics/contact_solve_cpu_seconds"][()]
if contact != 0.0 or not re.search(r"^time contact solves: cpu 0 s, 0 of the integration's cpu$",
                                     line("time contact solves:")):
    bad.append(f"contact solves {contact}: {line('time contact solves:')}")
print("\n".join(f"FAIL: {b}" for b in bad) or "ok: constraint drift and time lines match constraints/ and statistics/")
sys.exit(1 if bad else 0)
PY

# Not a results file: one line naming it and why, exit 1.
refused() {
  local message
  if message="$(/usr/bin/python3 "$root/scripts/plot_results.py" "$1" 2>&1)" \
      || [[ "$message" != "$1: $2"* ]] || [[ "$message" == *$'\n'* ]]; then
    echo "FAIL: $1 accepted or refused with '$message'"
    failures=$((failures + 1))
  fi
}
refused "$root/tests/data/cube.yaml" "cannot open as HDF5"
/usr/bin/python3 -c "import h5py, sys; h5py.File(sys.argv[1], 'w').attrs['format'] = 'other'" "$out/other.h5"
refused "$out/other.h5" "not a flexmbs results file (attribute format)"

if ((failures > 0)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all checks passed"
