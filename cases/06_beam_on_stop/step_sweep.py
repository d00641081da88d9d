"""Case 06's time-step sweep (issue 20): Moreau-Jean's runs of 17 modes with the correction mode
at other steps (OUT/step_<formulation>_<h>.h5, an output every step) beside the case's 1 us run
(OUT/<formulation>_17c.h5), each against the finest: total impulse and (penalty) peak force
error against the run's CPU seconds (statistics/), and the observed order in h."""
import math

import h5py

from beam_results import STEP, stop_impulses

# The penalty run is smooth, theta = 1/2 the trapezoidal rule: order 2 expected. Measured
# against 0.125 us: order 2.01 (peak force) and 1.95 (impulse) from 2 to 1 us; at 1 us the
# errors 4.2e-5 and 4.3e-6, the peak's a third of the 17 modes' own (1.5e-4).
ORDER = (1.7, 2.3)
LIMITS_AT_STEP = {"peak": 4e-4, "impulse": 4e-5}


def rows(out, formulation, steps):
    """[(h, impulse [N s], peak force [N], CPU [s])] for the steps and the case's own, by h."""
    files = {float(h): out / f"step_{formulation}_{h}.h5" for h in steps}
    files[STEP] = out / f"{formulation}_17c.h5"
    result = []
    for h in sorted(files, reverse=True):
        with h5py.File(files[h], "r") as f:
            impulses = stop_impulses(f, formulation)
            result.append((h, impulses.sum(), impulses.max() / h, float(f["statistics/cpu_seconds"][-1])))
    return result


def errors(sweep):
    """[(h, impulse error, peak error, CPU)] of every run but the finest, against the finest."""
    _, impulse, peak, _ = sweep[-1]
    return [(h, abs(i / impulse - 1.0), abs(p / peak - 1.0), cpu) for h, i, p, cpu in sweep[:-1]]


def report(out, steps, formulations, checks):
    """Prints each formulation's sweep; checks the penalty's order and its errors at the case's
    step. Returns {formulation: errors} for the plot."""
    curves = {}
    for formulation in formulations:
        sweep = rows(out, formulation, steps)
        curves[formulation] = table = errors(sweep)
        print(f"step sweep, {formulation}, 17 + c modes, against h = {sweep[-1][0] * 1e6:g} us "
              f"({sweep[-1][3]:.3g} s CPU):")
        print(f"  {'h [us]':>7} {'impulse':>9} {'peak force':>10} {'CPU [s]':>8}")
        for h, impulse, peak, cpu in table:
            peak_text = f"{peak:10.2e}" if formulation == "penalty" else f"{'-':>10}"
            print(f"  {h * 1e6:7.3g} {impulse:9.2e} {peak_text} {cpu:8.3g}")
        if formulation != "penalty":
            continue
        by_h = {h: (impulse, peak) for h, impulse, peak, _ in table}
        for index, measure in enumerate(("impulse", "peak")):
            order = math.log(by_h[2 * STEP][index] / by_h[STEP][index]) / math.log(2.0)
            checks.check(f"step sweep {measure}: order from 2 to 1 us", ORDER[0] <= order <= ORDER[1],
                         f"{order:.2f} (limits {ORDER[0]:g} .. {ORDER[1]:g})")
            value = by_h[STEP][index]
            checks.check(f"step sweep {measure}: error at 1 us", value <= LIMITS_AT_STEP[measure],
                         f"{value:.2e} (limit {LIMITS_AT_STEP[measure]:g})")
    return curves


def plot(axis, curves):
    """Each error against the run's CPU seconds, the points marked by h."""
    for formulation, table in curves.items():
        cpu = [row[3] for row in table]
        measures = (("impulse", 1), ("peak force", 2)) if formulation == "penalty" else (("impulse", 1),)
        for label, index in measures:
            axis.loglog(cpu, [row[index] for row in table], "o-", label=f"{formulation}: {label}")
        for h, impulse, _, seconds in table:
            axis.annotate(f"{h * 1e6:g} us", (seconds, impulse), fontsize=7)
    axis.set_xlabel("CPU of flexmbs simulate [s] (statistics/)")
    axis.set_ylabel("relative error against the finest step")
    axis.set_title("Moreau-Jean's step sweep, 17 + c modes", fontsize=9)
    axis.legend(fontsize=8)
    axis.grid(alpha=0.3, which="both")
