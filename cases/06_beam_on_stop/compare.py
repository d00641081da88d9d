#!/usr/bin/python3
"""The reduced beam on the stop against the full FE model (full_model.py): the table and plot.

Reads OUT/full_<formulation>.npy and .json (full_model.py) and, for each reduced run
OUT/<formulation>_<modes>[c].h5 with its `simulate --json` report .json, the per-step contact
impulse: for the unilateral (LCP) runs `contacts/stop/normal_impulse`; for the penalty, the
beam's momentum change m (v_Cm,k - v_Cm,k+1) along y, v_Cm = v_WBo + R_WB (w_WB_B x p_BoCm_B)
(the modes kept are free-free, so the centre of mass moves with the frame; checked on the LCP
runs, where both exist, to MOMENTUM_CHECK). Prints per formulation and run: total impulse error, impulse-history
error (the largest difference of the impulse transferred up to a step, in m v), peak force error
(the largest impulse of a step over h), wall time; checks the limits README.md gives; writes a
plot with --plot.

Usage: /usr/bin/python3 compare.py OUT --runs 4,8c,... [--planar] [--steps H,... [--sweep F,...]] [--plot PNG]
--planar: the planar runs against the spatial ones (planar.py); --steps: the time-step sweep
(step_sweep.py) of the formulations --sweep names (default penalty).
"""
import argparse
import json
import pathlib
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, save_figure  # noqa: E402 (cases/headline.py)
import planar  # noqa: E402
import step_sweep  # noqa: E402
from beam_results import STEP, history_error, momentum_impulses  # noqa: E402

FORMULATIONS = ("velocity", "position", "penalty")
# What README.md promises (measured beside each; the LCP floors are the full model's nodal
# impacts, docs/contact.md).
LIMITS = {
    ("penalty", "peak", "4c"): 0.08,       # measured -7.9e-3
    ("penalty", "peak", "17c"): 0.0015,    # measured -1.5e-4
    ("penalty", "peak", "32c"): 5e-4,      # measured -4.7e-5
    ("penalty", "history", "17c"): 7e-4,   # [m v], measured 7.1e-5
    ("penalty", "history", "32c"): 7e-4,   # [m v], measured 6.6e-5
    ("velocity", "history", "32c"): 0.1,   # [m v], measured 0.076 (the floor)
    ("position", "history", "32c"): 0.1,   # [m v], measured 0.065
}
# The momentum change against the LCP runs' own impulses, history difference: measured up to
# 3.4e-7 m v (every run), 200 times below the penalty's errors.
MOMENTUM_CHECK = 3e-6


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", type=pathlib.Path)
    p.add_argument("--runs", required=True, help="comma-separated mode counts, 'c' for the correction mode")
    p.add_argument("--planar", action="store_true", help="compare the planar runs with the spatial ones")
    p.add_argument("--steps", help="comma-separated steps of the step sweep [s], e.g. 2e-6,2.5e-7")
    p.add_argument("--sweep", default="penalty", help="comma-separated formulations of the step sweep")
    p.add_argument("--plot")
    a = p.parse_args()
    runs = a.runs.split(",")
    checks, table = Checks(), {}
    for formulation in FORMULATIONS:
        full = np.load(a.out / f"full_{formulation}.npy")
        info = json.loads((a.out / f"full_{formulation}.json").read_text())
        print(f"{formulation}: full FE model ({info['dofs']} DOF, SciPy) impulse {full.sum():.6g} N s, "
              f"peak force {full.max() / STEP:.6g} N, {info['wall_seconds']:.2f} s")
        print(f"  {'modes':>6} {'impulse':>11} {'history [m v]':>14} {'peak force':>11} {'wall [s]':>9}")
        for run in runs:
            with h5py.File(a.out / f"{formulation}_{run}.h5", "r") as f:
                impulses = momentum_impulses(f)
                if formulation != "penalty":
                    own = f["contacts/stop/normal_impulse"][1:]
                    drift = history_error(impulses, own)
                    if drift > MOMENTUM_CHECK:
                        checks.failures.append(f"{formulation} {run}: momentum against impulses {drift:.1e}")
                    impulses = own
            seconds = json.loads((a.out / f"{formulation}_{run}.json").read_text())["wall_seconds"]
            row = {"impulse": impulses.sum() / full.sum() - 1.0, "history": history_error(impulses, full),
                   "peak": impulses.max() / full.max() - 1.0, "seconds": seconds}
            table[(formulation, run)] = row
            print(f"  {run:>6} {row['impulse']:+11.3e} {row['history']:14.3e} {row['peak']:+11.3e} {seconds:9.3f}")
    for (formulation, measure, run), limit in LIMITS.items():
        if (formulation, run) not in table:
            continue
        value = table[(formulation, run)][measure]
        checks.check(f"{formulation} {run}: {measure}", abs(value) <= limit, f"error {value:+.2e} (limit {limit:g})")
    planar_table, planar_text = None, ""
    if a.planar:
        planar_table, odd, elastic = planar.rows(a.out, FORMULATIONS)
        planar.report(planar_table, odd, elastic, checks)
        planar_text = f" (planar against spatial: {planar.largest(planar_table):.1e})"
    curves = step_sweep.report(a.out, a.steps.split(","), a.sweep.split(","), checks) if a.steps else None
    print_headline("06_beam_on_stop", abs(table[("penalty", runs[-1])]["peak"]),
                   f"penalty peak force, {runs[-1]} modes{planar_text}",
                   runtime_s=table[("penalty", runs[-1])]["seconds"], peer="full FE model (SciPy)",
                   peer_runtime_s=json.loads((a.out / "full_penalty.json").read_text())["wall_seconds"])
    checks.finish(a.plot, lambda path: plot(path, a.out, runs, table, planar_table, curves))


def plot(path, out, runs, table, planar_table, curves):
    """The penalty's stop force, every run's history error against its wall time, and where
    they ran, the planar runs' tip against the spatial one and the step sweep's errors."""
    plt = pyplot()
    fig, ((left, right), (lower_left, lower_right)) = plt.subplots(2, 2, figsize=(11, 8.4))
    t = 1e3 * STEP * np.arange(1, 1001)
    full = np.load(out / "full_penalty.npy")
    left.plot(t, full / STEP / 1e3, "k", linewidth=2, label="full FE model (SciPy)")
    for run in runs[-2:]:
        with h5py.File(out / f"penalty_{run}.h5", "r") as f:
            left.plot(t, momentum_impulses(f) / STEP / 1e3, "--", label=f"reduced, {run}")
    left.set_xlabel("t [ms]")
    left.set_ylabel("stop force [kN] (penalty 1e7 N/m per vertex)")
    left.legend(fontsize=8)
    left.grid(alpha=0.3)
    for formulation, marker in zip(FORMULATIONS, "os^"):
        seconds = [table[(formulation, run)]["seconds"] for run in runs]
        errors = [table[(formulation, run)]["history"] for run in runs]
        right.loglog(seconds, errors, marker, label=formulation)
        for s, e, run in zip(seconds, errors, runs):
            right.annotate(run, (s, e), fontsize=7)
    right.set_xlabel("wall time of flexmbs simulate [s]")
    right.set_ylabel("impulse-history error [m v]")
    right.legend(fontsize=8)
    right.grid(alpha=0.3, which="both")
    if planar_table:
        planar.plot(lower_left, planar_table, STEP)
    else:
        lower_left.set_axis_off()
    if curves:
        step_sweep.plot(lower_right, curves)
    else:
        lower_right.set_axis_off()
    fig.suptitle("beam on a stop: reduced (modes, c = pad correction mode) against the full FE model")
    save_figure(fig, path)


if __name__ == "__main__":
    main()
