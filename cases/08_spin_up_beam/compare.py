#!/usr/bin/python3
"""The spin-up runs against the 1-D rotating beam (tests/validation/spin_up_reference.py).

For each results file RUN.h5 (`flexmbs simulate`, scene.yaml or a variant run.sh writes), the
tip deflection in the hub frame, the y_B component of R_WB^T (p_WTip - p_WBo) (the tip face's
averaging marker; its rest position (10, 0, 0)), against the reference computed by the script
with the run's spin rate and stiffening at the same output times: the largest difference over
the run (or up to --until), relative to the reference's largest |deflection| there. Prints
both histories; exits 1 if the difference exceeds --limit or, with --diverges-past, if the
deflection stays below that [m] at the end. Writes a plot with --plot (all runs given).

Usage: /usr/bin/python3 compare.py --run RUN.h5 SPIN STIFFENING(0|1) LIMIT [UNTIL] ... [--plot PNG]
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, save_figure  # noqa: E402 (cases/headline.py)
from results_frames import rotation  # noqa: E402 (cases/results_frames.py)

REFERENCE = pathlib.Path(__file__).resolve().parents[2] / "tests" / "validation" / "spin_up_reference.py"


def tip_deflection(path):
    """The output times after the start [s], the tip deflection there [m] and the run's total wall
    time (statistics/) [s]."""
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        p_o, e = f["bodies/beam/position"][:], f["bodies/beam/orientation"][:]
        tip = f["bodies/beam/markers/tip"][:]
        wall = float(f["statistics/wall_seconds"][list(f["statistics/parts"].asstr()[:]).index("total")])
    return t[1:], np.array([(rotation(e[k]).T @ (tip[k] - p_o[k]))[1] for k in range(1, len(t))]), wall


def reference(spin, stiffening, times):
    """The 1-D beam's tip deflection at `times` [m] and the wall time of its run [s]."""
    command = ["/usr/bin/python3", str(REFERENCE), repr(spin), str(stiffening)] + [repr(t) for t in times]
    start = time.perf_counter()
    out = subprocess.run(command, capture_output=True, text=True, check=True,
                         env={"PYTHONDONTWRITEBYTECODE": "1", "PATH": "/usr/bin:/bin"}).stdout
    return np.array(json.loads(out)["tip"]), time.perf_counter() - start


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--run", nargs="+", action="append", required=True, metavar="ARG",
                   help="RUN.h5 SPIN STIFFENING LIMIT [UNTIL]")
    p.add_argument("--diverges-past", type=float, help="[m]: the unstiffened runs' end deflection exceeds this")
    p.add_argument("--plot")
    a = p.parse_args()
    checks, curves, stiffened = Checks(), [], []
    for args in a.run:
        path, spin, stiffening, limit = args[0], float(args[1]), int(args[2]), float(args[3])
        until = float(args[4]) if len(args) > 4 else np.inf
        t, tip, wall = tip_deflection(path)
        ref, reference_wall = reference(spin, stiffening, t)
        within = t <= until + 1e-9
        error = np.abs(tip - ref)[within].max() / np.abs(ref[within]).max()
        name = f"{spin:g} rad/s, {'with' if stiffening else 'without'} stiffening"
        print(f"{name} ({path}):")
        for tk, a_k, r_k in zip(t, tip, ref):
            print(f"  t = {tk:4.1f} s: tip {a_k:+.5f} m, 1-D {r_k:+.5f} m ({a_k - r_k:+.1e} m)")
        checks.check(name, error <= limit, f"largest difference / largest |deflection| {error:.1e}"
                     f"{'' if np.isinf(until) else f' up to {until:g} s'} (limit {limit:g})")
        if not stiffening and a.diverges_past is not None:
            checks.check(f"{name} diverges", abs(tip[-1]) > a.diverges_past,
                         f"|tip| {abs(tip[-1]):.3g} m at {t[-1]:g} s (> {a.diverges_past:g} m)")
        curves.append((name, t, tip, ref))
        if stiffening:
            stiffened.append((error, wall, reference_wall))
    if stiffened:
        errors, walls, reference_walls = zip(*stiffened)
        print_headline("08_spin_up_beam", max(errors), "tip deflection / its largest value, stiffened runs",
                       runtime_s=sum(walls), peer="1-D rotating beam (SciPy)", peer_runtime_s=sum(reference_walls))
    checks.finish(a.plot, lambda path: plot(path, curves))


def plot(path, curves):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for name, t, tip, ref in curves:
        line, = ax.plot(t, tip, "o", label=f"flexmbs, {name}")
        ax.plot(t, ref, "-", color=line.get_color(), label=f"1-D beam, {name}")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("tip deflection in the hub frame [m]")
    ax.set_ylim(-1.5, 0.5)
    ax.set_title("Kane's spin-up beam: reduced 3-D body (4 modes) against the 1-D rotating beam")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    save_figure(fig, path)


if __name__ == "__main__":
    main()
