#!/usr/bin/python3
"""The flexible pendulum's runs against the planar co-rotational beam (reference.py).

For each results file RUN.h5 (`flexmbs simulate`, scene.yaml or a variant run.sh writes): the
swing angle, the beam frame's turn about W z (the frame sits on the pin section: its modes are
clamped there), and the tip deflection in that frame, the y_B component of R_WB^T (p_WTip - p_WBo)
(the tip face's averaging marker), against the reference's theta_0 and tip deflection at the same
output times, computed once for all runs (reference.py's output: the stored reference.json to
2 s, which a run may end before, or run.sh's rerun). Differences: the tip's largest over the run relative to the reference's largest |tip|,
the angle's largest in rad. Prints both, exits 1 if one exceeds its limit; writes a plot with
--plot (the histories, and each run's tip difference against its CPU time, statistics/) and one
headline line for bench/ (the first run's tip difference).

Usage: /usr/bin/python3 compare.py REFERENCE.json --run RUN.h5 NAME TIP_LIMIT ANGLE_LIMIT_RAD ... [--plot PNG]
"""
import argparse
import json
import pathlib
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, save_figure  # noqa: E402 (cases/headline.py)
from results_frames import rotation  # noqa: E402 (cases/results_frames.py)


def swing(path):
    """times [s], the frame's angle about W z [rad] (unwrapped) and the tip deflection [m],
    flexmbs' wall time [s] from the run's report when it is beside the results, and the run's
    total CPU time [s] (statistics/)."""
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        p_o, e = f["bodies/beam/position"][:], f["bodies/beam/orientation"][:]
        tip = f["bodies/beam/markers/tip"][:]
        cpu = float(f["statistics/cpu_seconds"][list(f["statistics/parts"].asstr()[:]).index("total")])
    R = [rotation(ek) for ek in e]
    angle = np.unwrap([np.arctan2(Rk[1, 0], Rk[0, 0]) for Rk in R])
    deflection = np.array([(Rk.T @ (tk - pk))[1] for Rk, tk, pk in zip(R, tip, p_o)])
    report = pathlib.Path(path).with_suffix(".json")
    seconds = json.loads(report.read_text())["wall_seconds"] if report.exists() else None
    return t, angle, deflection, seconds, cpu


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("reference")
    p.add_argument("--run", nargs=4, action="append", required=True, metavar=("RUN.h5", "NAME", "TIP_LIMIT", "ANGLE_LIMIT"))
    p.add_argument("--plot")
    a = p.parse_args()
    ref = json.loads(pathlib.Path(a.reference).read_text())
    t_ref = np.array(ref["times"])
    angle_ref, tip_ref = np.unwrap(ref["angle"]), np.array(ref["tip"])
    print(f"reference: co-rotational beam, {ref['elements']} elements, rtol {ref['rtol']:g}, "
          f"{ref['cpu_seconds']} s CPU, energy drift {ref['energy_drift_j']:.1e} J")
    checks, curves, headline = Checks(), [], None
    for path, name, tip_limit, angle_limit in a.run:
        t, angle, tip, seconds, cpu = swing(path)
        if len(t) > len(t_ref) or np.max(np.abs(t - t_ref[:len(t)])) > 1e-9:
            sys.exit(f"{path}: output times differ from the reference's ({len(t)} against {len(t_ref)})")
        t_ref, angle_ref, tip_ref = t_ref[:len(t)], angle_ref[:len(t)], tip_ref[:len(t)]
        tip_error = np.max(np.abs(tip - tip_ref)) / np.max(np.abs(tip_ref))
        angle_error = np.max(np.abs(angle - angle_ref))
        print(f"{name} ({path}):")
        for k in range(0, len(t), max(1, len(t) // 10)):
            print(f"  t = {t[k]:5.3f} s: angle {angle[k]:+.5f} rad (reference {angle_ref[k]:+.5f}), "
                  f"tip {tip[k] * 1e3:+.4f} mm (reference {tip_ref[k] * 1e3:+.4f})")
        for what, error, limit, unit in (("tip difference / largest |tip|", tip_error, float(tip_limit), ""),
                                         ("angle difference", angle_error, float(angle_limit), " rad")):
            checks.check(f"{name}: {what}", error <= limit, f"{error:.2e}{unit} (limit {limit:g}{unit})")
        print(f"     {name}: flexmbs simulate {'' if seconds is None else f'{seconds:.3f} s wall, '}{cpu:.3f} s CPU")
        if headline is None:
            headline = (tip_error, seconds)
        curves.append((name, t, angle, tip, tip_error, cpu))
    print_headline("11_flexible_pendulum", headline[0], "tip deflection / its largest value",
                   runtime_s=headline[1], peer="co-rotational beam (SciPy)", peer_runtime_s=ref["cpu_seconds"])
    checks.finish(a.plot, lambda path: plot(path, t_ref, angle_ref, tip_ref, curves, ref["cpu_seconds"]))


def plot(path, t_ref, angle_ref, tip_ref, curves, reference_cpu):
    plt = pyplot()
    fig = plt.figure(figsize=(12, 6.5))
    grid = fig.add_gridspec(2, 2, width_ratios=(2.2, 1))
    top = fig.add_subplot(grid[0, 0])
    bottom = fig.add_subplot(grid[1, 0], sharex=top)
    cost = fig.add_subplot(grid[:, 1])
    top.plot(t_ref, np.degrees(angle_ref), "k-", label="co-rotational beam (SciPy)")
    bottom.plot(t_ref, tip_ref * 1e3, "k-", label="co-rotational beam (SciPy)")
    for name, t, angle, tip, tip_error, cpu in curves:
        top.plot(t, np.degrees(angle), "--", label=f"flexmbs, {name}")
        line, = bottom.plot(t, tip * 1e3, "--", label=f"flexmbs, {name}")
        cost.loglog(cpu, tip_error, "o", color=line.get_color(), label=name)
    top.set_ylabel("swing angle [deg]")
    bottom.set_ylabel("tip deflection in the pin's frame [mm]")
    bottom.set_xlabel("t [s]")
    top.set_title("Flexible pendulum: reduced 3-D strip against a planar co-rotational beam")
    cost.set_xlabel("flexmbs simulate, CPU [s]")
    cost.set_ylabel("largest tip difference / largest |tip|")
    cost.set_title(f"error against CPU (the reference: {reference_cpu:g} s)", fontsize=9)
    for ax in (top, bottom, cost):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    save_figure(fig, path)


if __name__ == "__main__":
    main()
