"""The connecting rod's midpoint deflection of a `flexmbs simulate` run of this case against the
geometrically exact planar beam of tests/validation/slider_crank_exact.py (SciPy, absolute nodal
coordinates, 16 elements: no modal truncation, every inertia load stiffens it exactly; stored in
tests/validation/slider_crank_exact.json).

The deflection is the distance of marker `mid` from the chord through the rod's frame origin
(end_a) and marker `end_b`, positive along z_W x chord, as in tests/validation/slider_crank_model.h.

Usage: /usr/bin/python3 compare.py results.h5 [--limit 0.05] [--plot PNG]
Prints both peaks and the largest difference; exits 1 if that difference exceeds `limit` times the
reference's peak. --plot: both histories and their difference.
"""
import argparse
import json
import pathlib
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, save_figure  # noqa: E402 (cases/headline.py)

REFERENCE = pathlib.Path(__file__).resolve().parents[2] / "tests" / "validation" / "slider_crank_exact.json"


def midpoint_deflection(results):
    with h5py.File(results, "r") as f:
        t = f["time"][:]
        p_a = f["bodies/rod/position"][:, :2]
        p_b = f["bodies/rod/markers/end_b"][:, :2]
        p_mid = f["bodies/rod/markers/mid"][:, :2]
    chord = p_b - p_a
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / np.linalg.norm(chord, axis=1)[:, None]
    return t, np.sum((p_mid - p_a) * normal, axis=1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("results")
    parser.add_argument("--limit", type=float, default=0.05)
    parser.add_argument("--plot")
    args = parser.parse_args()
    t, w = midpoint_deflection(args.results)
    reference = json.loads(REFERENCE.read_text())
    t_ref = np.array(reference["times"])
    w_ref = np.array(reference["mid"])
    window = t_ref <= t[-1]
    t_ref, w_ref = t_ref[window], w_ref[window]
    difference = np.max(np.abs(np.interp(t_ref, t, w) - w_ref))
    peak_ref = np.max(np.abs(w_ref))
    print(f"midpoint deflection: flexmbs peak {1e3 * np.max(np.abs(w)):.4g} mm at {t[np.argmax(np.abs(w))]:.4g} s, "
          f"reference peak {1e3 * peak_ref:.4g} mm at {t_ref[np.argmax(np.abs(w_ref))]:.4g} s; largest difference "
          f"{1e3 * difference:.3g} mm = {difference / peak_ref:.3g} of the reference's peak (limit {args.limit:g})")
    print_headline("02_slider_crank", difference / peak_ref, "midpoint deflection history / its peak",
                   peer="planar beam model (tests/validation/slider_crank_exact.json)")
    checks = Checks()
    checks.check("midpoint deflection", difference <= args.limit * peak_ref,
                 f"largest difference / the reference's peak {difference / peak_ref:.3g} (limit {args.limit:g})")
    checks.finish(args.plot, lambda path: plot(path, t, w, t_ref, w_ref))


def plot(path, t, w, t_ref, w_ref):
    plt = pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    top.plot(t_ref, w_ref * 1e3, "k-", label="geometrically exact planar beam (SciPy, ANCF)")
    top.plot(t, w * 1e3, "--", label="flexmbs, reduced 3-D rod")
    top.set_ylabel("midpoint deflection [mm]")
    top.set_title("Flexible slider-crank (Simo & Vu-Quoc): the rod's midpoint deflection")
    top.legend(fontsize=8)
    bottom.plot(t_ref, (np.interp(t_ref, t, w) - w_ref) * 1e3, "-")
    bottom.set_ylabel("difference [mm]")
    bottom.set_xlabel("t [s]")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    save_figure(fig, path)


if __name__ == "__main__":
    main()
