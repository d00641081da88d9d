#!/usr/bin/python3
"""Checks cases/10_gear_pair's three runs against closed forms computed here (no flexmbs code).

Reads out/fe.h5 (massless FE teeth), out/movable.h5 (the same teeth movable: each tooth's
deflection a state behind its own dashpot) and out/iso.h5 (ISO 6336-1's constant c'), the
gears/mesh series of docs/results.md, and checks, from 0.1 s on (start-up settled) over whole
mesh periods 2 pi / (z1 omega1):
- the transmission error is 0 at t = 0 (the wheel's start angle from gear_geometry.py's
  involutes: the positive flanks touch);
- the mean mesh force is T / r_b2, the share of double contact epsilon_alpha - 1 (ISO 21771);
- the transmission error repeats one mesh period later;
- ISO run: along the line of action F / (c' b) in single and F / (2 c' b) in double contact,
  c' = gear_geometry.iso_stiffness() (samples 1 ms or more after a pair switch: the mesh rings
  at each switch);
- FE run, single contact: F / (c(t1, t2) b) with 1 / c = q1(t1) + q2(t2) + Weber's flattening
  at w_ref = 300 N/mm, divided by w_ref (docs/contact.md "Elastic teeth"; the tables of scene.yaml read here,
  linear between samples), the pair's roll angles from the driven pinion's angle 2 t; and the
  pinion's tooth deflection q1(t1) F / b; the same for the movable teeth (their deflections
  lever_i d_i from the states);
- movable teeth: the pinion tooth's state deflection the first-order lag of its dashpot behind
  q1(t1) F / b, (q1 F / b)(1 - tau omega1 q1'(t1) / q1) with tau = c_t q1 / b (3 ms or more after
  a switch);
- movable teeth: the transmission error the FE run's (the quasi-static series of the same
  tables) where both have settled (1 ms or more after either run's pair switch);
- both runs: the wheel's lag along the line of action from its orientation against the driven
  pinion's angle, r_b2 (phi2 - phi2(0) + (z1/z2) 2 t), equals the transmission error (rigid
  pinion);
- with out/shaft.h5 (the full mode: ISO c', the pinion on its Craig-Bampton shaft), the wheel's
  extra lag over the rigid pinion's is the shaft's compliance at the mesh, Timoshenko's clamped
  beam under the mesh force F along the line of action at the pinion (bending L^3/(3 E I), shear
  L/(kappa G A), kappa = 6(1 + nu)/(7 + 6 nu) for a solid circle) and torsion by F r_b1
  (r_b1^2 L/(G J)), all in series with the teeth.
Prints a table, one headline line; asserts the limits below; plots out/gear_pair.png.

Usage: /usr/bin/python3 compare.py OUT [--plot FILE.png]
"""
import argparse
import json
import math
import pathlib
import sys

import h5py
import numpy as np
import yaml

import gear_geometry as gg

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, save_figure  # noqa: E402 (cases/headline.py)

TORQUE, SPEED, START, RING = 10.0, 2.0, 0.1, 1e-3  # load [N m], pinion [rad/s], from [s], after a switch [s]
CALM = 3e-3  # [s] after a switch: the movable teeth' ring gone (their tooth dashpots damp it less)
E, NU, W_REF = 2.1e11, 0.3, 3e5                    # steel, the flattening's reference load [N/m]
LIMITS = {  # measured in the comments
    "start_error_m": 1e-15,       # 5.2e-18 m
    "mean_force": 1e-3,           # FE 1.3e-4, ISO 5.4e-5, movable 3.1e-4 (three whole periods from 0.1 s)
    "double_share": 3e-3,         # 3.6e-4 (sampling 1e-4 s of 0.165 s)
    "periodic": 0.1,              # of the range, 2e-4 s or more from a switch: FE 1.0e-2, ISO 6.6e-3, movable 4.1e-2 (the ring)
    "iso_levels": 1e-5,           # 7.9e-7 (what the ringing leaves 1 ms after a switch)
    "fe_single": 2e-3,            # FE 1.6e-4, movable 2.6e-4 (the dashpot as c changes along the path)
    "fe_tooth_deflection": 1e-10,  # 4.6e-14
    "lag_is_error_m": 2e-15,      # FE 1.9e-16, ISO 2.1e-16, movable 7.1e-17 m: the wheel's lag from its orientation = the error
    "movable_vs_fe": None,        # movable teeth only (MOVABLE_LIMITS)
    "movable_tooth_lag": None,    # movable teeth only (MOVABLE_LIMITS)
    "shaft_lag": 0.05,            # -1.6e-2: the 3-D shaft (tet10, rigid end face, clamped end) stiffer than the beam
}
MOVABLE_LIMITS = {  # the movable teeth' column where it differs from LIMITS; measured in the comments
    "fe_tooth_deflection": 2e-3,  # 1.7e-4: the state lags q1 F / b by about c_t/k_t times its rate
    "movable_tooth_lag": 1e-4,    # 2.4e-5 (1.6e-5 from 30 ms after a switch; 7.0e-5 from 1 ms: the ring); below
                                  # the 1.7e-4 the state would miss by without its lag, so the dashpot is seen
    "movable_vs_fe": 1e-3,        # 8.7e-5 (8.7e-11 m): the dashpots' lag and the ring 1 ms after a switch
}
RUNS = ("fe", "iso", "movable")
SHAFT_LENGTH, SHAFT_RADIUS = 0.1, 0.015  # [m] (shaft.geo)


def read(path, g):
    with h5py.File(path, "r") as f:
        m = f["gears/mesh"]
        t, e = f["time"][:], f["bodies/wheel/orientation"][:]
        phi2 = np.unwrap(2 * np.arctan2(e[:, 3], e[:, 0]))  # the wheel's turn about z
        return {"t": t, "te": m["transmission_error_length"][:], "n": m["active_pairs"][:],
                "force": m["mesh_force"][:], "d1": m["tooth1_deflection"][:].sum(axis=1),
                "d2": m["tooth2_deflection"][:].sum(axis=1),
                "lag": g["rb"][1] * (phi2 - phi2[0] + gg.TEETH[0] / gg.TEETH[1] * SPEED * t)}


def shaft_compliance(g):
    """[m/N] along the line of action at the pinion's flank: the clamped shaft's bending, shear
    and torsion (by the lever r_b1), Timoshenko's beam."""
    e, g_mod = E, E / (2 * (1 + NU))
    area, second = math.pi * SHAFT_RADIUS ** 2, math.pi * SHAFT_RADIUS ** 4 / 4
    kappa = 6 * (1 + NU) / (7 + 6 * NU)
    return (SHAFT_LENGTH ** 3 / (3 * e * second) + SHAFT_LENGTH / (kappa * g_mod * area)
            + g["rb"][0] ** 2 * SHAFT_LENGTH / (g_mod * 2 * second))


def pair_stiffness(t1, t2, teeth, g):
    """c(t1, t2) [N/m^2]: both teeth's compliance and Weber's flattening in series."""
    one, two = teeth["gear1"], teeth["gear2"]
    rho1, rho2 = g["rb"][0] * t1, g["rb"][1] * t2
    half_width = math.sqrt(8 * W_REF * rho1 * rho2 / (rho1 + rho2) * (1 - NU ** 2) / (math.pi * E))
    h1, h2 = np.interp(t1, one["roll"], one["centre_depth"]), np.interp(t2, two["roll"], two["centre_depth"])
    flattening = 2 * W_REF * (1 - NU ** 2) / (math.pi * E) * (
        math.log(2 * h1 / half_width) + math.log(2 * h2 / half_width) - NU / (1 - NU))
    return 1 / (np.interp(t1, one["roll"], one["compliance"]) + np.interp(t2, two["roll"], two["compliance"])
                + flattening / W_REF)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--plot")
    args = parser.parse_args()
    g = gg.geometry()
    force = TORQUE / g["rb"][1]
    width = gg.FACE_WIDTH
    period = 2 * math.pi / (gg.TEETH[0] * SPEED)
    with open("scene.yaml") as f:
        teeth = yaml.safe_load(f.read().replace("WHEEL_ANGLE", "0"))["forces"][1]["teeth"]
    runs = {name: read(f"{args.out}/{name}.h5", g) for name in RUNS}
    with open(f"{args.out}/movable.yaml") as f:
        tooth_damping = float(yaml.safe_load(f)["forces"][1]["teeth"]["movable"]["damping"])  # c_t [N s/m]
    measured, checks = {}, Checks()
    for name, r in runs.items():
        t = r["t"]
        whole = (t >= START) & (t < START + period * math.floor((t[-1] - START) / period))
        switches = t[np.r_[0, np.flatnonzero(np.diff(r["n"]) != 0) + 1]]
        settled = whole & (t - switches[np.searchsorted(switches, t, side="right") - 1] >= RING)
        later = np.interp(t[whole] + period, t, r["te"])
        # Away from the switches by two samples at t and t + period (the error jumps there).
        near = np.minimum(np.min(np.abs(t[whole][:, None] - switches[None, :]), axis=1),
                          np.min(np.abs(t[whole][:, None] + period - switches[None, :]), axis=1))
        apart = (near >= 2e-4) & (t[whole] + period <= t[-1])
        span = np.ptp(r["te"][whole])
        measured[name] = {
            "start_error_m": abs(r["te"][0]),
            "mean_force": abs(r["force"][whole].mean() / force - 1),
            "double_share": abs((r["n"][whole] == 2).mean() - (g["contact_ratio"] - 1)),
            "periodic": np.max(np.abs(later - r["te"][whole])[apart]) / span,
            "lag_is_error_m": np.max(np.abs(r["lag"] - r["te"])[t >= START]),
        }
        single, double = settled & (r["n"] == 1), settled & (r["n"] == 2)
        if name == "movable":  # against the FE run, both settled
            fe = runs["fe"]
            both = np.union1d(switches, fe["t"][np.flatnonzero(np.diff(fe["n"]) != 0) + 1])
            rung = whole & (t - both[np.maximum(np.searchsorted(both, t, side="right") - 1, 0)] >= RING)
            measured[name]["movable_vs_fe"] = np.max(np.abs(r["te"][rung] / fe["te"][rung] - 1))
            measured[name]["movable_vs_fe_m"] = np.max(np.abs(r["te"][rung] - fe["te"][rung]))
        if name == "iso":
            c = gg.iso_stiffness()
            measured[name]["iso_levels"] = max(np.max(np.abs(r["te"][single] * c * width / r["force"][single] - 1)),
                                               np.max(np.abs(r["te"][double] * 2 * c * width / r["force"][double] - 1)))
        else:
            s = g["rb"][0] * (g["alpha_w"] + g["psi_b"][0] + SPEED * t[single])
            s -= g["p_b"] * np.floor((s - g["s_e"] + g["p_b"]) / g["p_b"])  # the pair in single contact
            t1, t2 = s / g["rb"][0], (g["line"] - s) / g["rb"][1]
            c = np.array([pair_stiffness(a, b, teeth, g) for a, b in zip(t1, t2)])
            f = r["force"][single]
            measured[name]["fe_single"] = np.max(np.abs(r["te"][single] * c * width / f - 1))
            q1 = np.interp(t1, teeth["gear1"]["roll"], teeth["gear1"]["compliance"])
            measured[name]["fe_tooth_deflection"] = np.max(np.abs(r["d1"][single] / (q1 * f / width) - 1))
            if name == "movable":
                # The state behind its dashpot, c_t d' + (b / q1) d = F, to first order in tau = c_t q1 / b:
                # d = (q1 F / b)(1 - tau omega1 q1'(t1) / q1) (F steady in single contact once its
                # ring has gone: 3 ms after a switch; q1' the table's slope, linear between samples).
                calm = (t - switches[np.searchsorted(switches, t, side="right") - 1] >= CALM)[single]
                roll, comp = np.array(teeth["gear1"]["roll"]), np.array(teeth["gear1"]["compliance"])
                slope = (np.diff(comp) / np.diff(roll))[np.clip(np.searchsorted(roll, t1) - 1, 0, len(roll) - 2)]
                lagging = q1 * f / width * (1 - tooth_damping * SPEED * slope / width)  # tau omega1 q1' / q1
                measured[name]["movable_tooth_lag"] = np.max(np.abs(r["d1"][single] / lagging - 1)[calm])
            measured[name]["levels_um"] = (r["te"][single].min() * 1e6, r["te"][single].max() * 1e6,
                                           r["te"][double].max() * 1e6)
            measured[name]["teeth_share"] = (np.min((r["d1"] + r["d2"])[single] / r["te"][single]),
                                             np.max((r["d1"] + r["d2"])[single] / r["te"][single]))
    shaft = pathlib.Path(f"{args.out}/shaft.h5")
    if shaft.exists():
        r, rigid = read(shaft, g), runs["iso"]
        single = (r["t"] >= START) & (r["n"] == 1)
        extra = np.median(r["lag"][single]) - np.median(rigid["lag"][(rigid["t"] >= START) & (rigid["n"] == 1)])
        expected = force * shaft_compliance(g)
        measured["iso"]["shaft_lag"] = abs(extra / expected - 1)
        print(f"pinion on its shaft: the wheel lags {extra * 1e6:.4f} um more than on the rigid pinion; "
              f"Timoshenko's clamped shaft {expected * 1e6:.4f} um ({extra / expected - 1:+.2e}); "
              f"transmission error {np.median(r['te'][single]) * 1e6:.4f} um (measured at the pinion's marker)")
    print(f"pair: epsilon_alpha = {g['contact_ratio']:.6f}, T / r_b2 = {force:.4f} N, "
          f"ISO 6336-1 c' = {gg.iso_stiffness() / 1e9:.3f} N/(mm um), mesh period {period * 1e3:.2f} ms")
    print("| check | FE teeth | ISO c' | movable teeth | limit | movable's limit |")
    print("|---|---:|---:|---:|---:|---:|")
    for key, limit in LIMITS.items():
        cells = []
        for name in RUNS:  # the shaft's check sits in the ISO column
            value = measured[name].get(key)
            cells.append("" if value is None else f"{value:.2e}")
            bound = MOVABLE_LIMITS.get(key, limit) if name == "movable" else limit
            if value is not None and not value <= bound:
                checks.failures.append(f"{name}: {key} {value:.3e} > {bound}")
        own = MOVABLE_LIMITS.get(key, limit)
        print(f"| {key} | {' | '.join(cells)} | {'' if limit is None else f'{limit:g}'} | "
              f"{'' if own is None else f'{own:g}'} |")
    lo, hi, dbl = measured["fe"]["levels_um"]
    share = measured["fe"]["teeth_share"]
    print(f"FE teeth: transmission error {lo:.3f} ... {hi:.3f} um in single contact, <= {dbl:.3f} um in double; "
          f"the teeth take {share[0]:.3f} ... {share[1]:.3f} of it in single contact (the flattening the rest); "
          f"ISO c': {force / (gg.iso_stiffness() * width) * 1e6:.3f} and {force / (2 * gg.iso_stiffness() * width) * 1e6:.3f} um")
    lo, hi, dbl = measured["movable"]["levels_um"]
    share = measured["movable"]["teeth_share"]
    print(f"movable teeth: transmission error {lo:.3f} ... {hi:.3f} um in single contact, <= {dbl:.3f} um in double; "
          f"the teeth take {share[0]:.3f} ... {share[1]:.3f} of it; against the FE run where both settled "
          f"{measured['movable']['movable_vs_fe_m']:.3e} m")
    for name in RUNS:
        with open(f"{args.out}/{name}.json") as f:
            report = json.load(f)
        if name == "fe":
            wall = report["wall_seconds"]
        print(f"{name}: {report['steps']} steps, {report.get('newton_iterations', 0)} Newton iterations, "
              f"{report['wall_seconds']:.2f} s")
    print_headline("10_gear_pair", measured["fe"]["fe_single"],
                   "FE teeth' single-contact transmission error against the teeth and Weber's flattening in series",
                   runtime_s=wall, peer="closed forms, ISO 6336-1 c'")
    if args.plot:
        plt = pyplot()
        rows = 4 if shaft.exists() else 3
        fig, axes = plt.subplots(rows, 1, figsize=(9, 2.7 * rows), sharex=True)
        for name, label in (("fe", "FE teeth"), ("iso", "ISO 6336-1 c'"), ("movable", "movable FE teeth")):
            r = runs[name]
            cycles = r["t"] / period
            axes[0].plot(cycles, r["te"] * 1e6, lw=0.8 if name == "movable" else 1.5, label=label)
            axes[1].plot(cycles, r["force"], lw=0.8 if name == "movable" else 1.5, label=label)
        r = runs["fe"]
        axes[0].set(ylabel="transmission error [um]", title="spur pair z 19/31 driven at 2 rad/s against 10 N m")
        axes[0].legend(fontsize=8)
        axes[1].axhline(force, color="k", ls="--", lw=0.8, label="T / r_b2")
        axes[1].set(ylabel="mesh force [N]", ylim=(0, 2 * force))
        axes[1].legend(fontsize=8)
        axes[2].plot(r["t"] / period, r["d1"] * 1e6, label="pinion tooth")
        axes[2].plot(r["t"] / period, r["d2"] * 1e6, label="wheel tooth")
        m = runs["movable"]
        axes[2].plot(m["t"] / period, m["d1"] * 1e6, "--", lw=0.8, label="pinion tooth, movable (state)")
        axes[2].plot(m["t"] / period, m["d2"] * 1e6, "--", lw=0.8, label="wheel tooth, movable (state)")
        axes[2].plot(r["t"] / period, r["n"], "k", lw=0.6, label="pairs in contact")
        axes[2].set(ylabel="teeth' deflections, summed [um]")
        axes[-1].set_xlabel("mesh periods")
        axes[2].legend(fontsize=8)
        if shaft.exists():
            on_shaft = read(shaft, g)
            for r, label in ((runs["iso"], "rigid pinion"), (on_shaft, "pinion on its shaft")):
                axes[3].plot(r["t"] / period, r["lag"] * 1e6, label=label)
            axes[3].axhline((force / (gg.iso_stiffness() * width) + force * shaft_compliance(g)) * 1e6, color="k",
                            ls="--", lw=0.8, label="single contact: F/(c' b) + Timoshenko's shaft")
            axes[3].set(ylabel="wheel lag on the line [um]", ylim=(0, None))
            axes[3].legend(fontsize=8)
        save_figure(fig, args.plot, dpi=110)
    checks.finish()


if __name__ == "__main__":
    main()
