#!/usr/bin/python3
"""Checks what cases/05_nafems_fv52/README.md says the case shows, on the files run.sh wrote.

Reads from OUT the `flexmbs reduce --json` reports (plate.reduce.json, plate_faces.reduce.json)
and CalculiX's (tests/peers/ccx_modal.py: plate.ccx.json, plate_faces.ccx.json, and plate_free.ccx.json
for the benchmark's support alone, in-plane motions free); with --coarse-out DIR also the coarse
mesh's reports there (the full run's refinement check). Checks:
- flexmbs against CalculiX on the same mesh and supports, every mode, both variants;
- the in-plane restraint leaves the bending modes as they are: flexmbs' held plate against
  CalculiX's free-in-plane plate (modes 4-7, after its three rigid ones);
- the side-face variant's bending modes against NAFEMS' published 45.897, 109.44, 109.44,
  167.89 Hz within the README's 1 %;
- the in-plane modes of the free-in-plane plate (CalculiX) against the published 193.59 and
  206.19 Hz within 0.2 %;
- the benchmark's bottom-edge support: bending modes below the published ones, and (with
  --coarse-out) lower on the fine mesh than on the coarse one.
Writes a plot of every frequency's deviation from the published value with --plot.

Usage: /usr/bin/python3 check.py OUT --mesh full|coarse [--coarse-out DIR] [--plot PNG]
Prints one line per check; exits 1 if any fails.
"""
import argparse
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, reduce_seconds, save_figure  # noqa: E402 (cases/headline.py)

# NAFEMS, Selected Benchmarks for Natural Frequency Analysis (R0015, 1987), test FV52, modes
# 4-10 (the first three are the in-plane rigid motions). Bending: (1,1), (1,2) twice, (2,2);
# in-plane: the last three.
PUBLISHED_BENDING_HZ = [45.897, 109.44, 109.44, 167.89]
PUBLISHED_IN_PLANE_HZ = [193.59, 206.19, 206.19]
# The held plates' modes that are the published bending ones (flexmbs and CalculiX order; the
# side-face variant has an in-plane pair, modes 4 and 5, below the (2,2) mode).
BENDING_INDEX = {"plate": [0, 1, 2, 3], "plate_faces": [0, 1, 2, 5]}
# CalculiX's free-in-plane plate: 3 rigid modes, bending from index 3; the in-plane modes'
# indices differ with the mesh (the (1,3) bending pair lies below them on the fine mesh only).
FREE_BENDING_INDEX = [3, 4, 5, 6]
FREE_IN_PLANE_INDEX = {"full": [9, 10, 11], "coarse": [7, 10, 11]}
# CalculiX prints 7 significant digits (rounding up to 5e-7 relative): measured 3.2e-7.
CALCULIX = 1e-6
# The mid-plane lines' restraint against the free-in-plane plate, bending modes: measured
# 1.5e-4 (coarse) and 9.4e-5 (full), the (2,2) mode.
RESTRAINT = 1e-3
# Side faces held: discretisation (+0.16 .. +0.56 % full, +0.22 .. +0.81 % coarse) plus the
# difference between the 3-D simply supported plate and NAFEMS' reference model.
FACES_TO_PUBLISHED = 0.01
# In-plane modes: measured 6.3e-4 (full), 3.9e-4 (coarse).
IN_PLANE_TO_PUBLISHED = 0.002


def load(folder, name):
    return json.loads((folder / name).read_text())


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", type=pathlib.Path)
    p.add_argument("--mesh", choices=("full", "coarse"), required=True)
    p.add_argument("--coarse-out", type=pathlib.Path)
    p.add_argument("--plot")
    a = p.parse_args()
    checks = Checks()
    check = checks.check

    ours = {v: load(a.out, f"{v}.reduce.json")["frequency_hz"] for v in BENDING_INDEX}
    ccx = {v: load(a.out, f"{v}.ccx.json")["frequencies_hz"] for v in BENDING_INDEX}
    free = load(a.out, "plate_free.ccx.json")["frequencies_hz"]

    for v in BENDING_INDEX:
        worst = max(abs(f / c - 1.0) for f, c in zip(ours[v], ccx[v]))
        check(f"{v}: flexmbs = CalculiX on the same mesh", len(ours[v]) == len(ccx[v]) and worst <= CALCULIX,
              f"largest relative difference {worst:.1e} over {len(ours[v])} modes")

    held = [ours["plate"][i] for i in BENDING_INDEX["plate"]]
    unheld = [free[i] for i in FREE_BENDING_INDEX]
    worst = max(abs(f / c - 1.0) for f, c in zip(held, unheld))
    check("the in-plane restraint leaves the bending modes", worst <= RESTRAINT,
          f"held {[f'{f:.5g}' for f in held]} Hz, free in plane {unheld} Hz: {worst:.1e}")

    faces = [ours["plate_faces"][i] for i in BENDING_INDEX["plate_faces"]]
    deviation = [f / r - 1.0 for f, r in zip(faces, PUBLISHED_BENDING_HZ)]
    check("side faces held: bending modes against NAFEMS", max(abs(d) for d in deviation) <= FACES_TO_PUBLISHED,
          ", ".join(f"{f:.5g} Hz ({100 * d:+.2f} %)" for f, d in zip(faces, deviation)))

    in_plane = [free[i] for i in FREE_IN_PLANE_INDEX[a.mesh]]
    deviation = [f / r - 1.0 for f, r in zip(in_plane, PUBLISHED_IN_PLANE_HZ)]
    check("in-plane modes (CalculiX, free in plane) against NAFEMS",
          max(abs(d) for d in deviation) <= IN_PLANE_TO_PUBLISHED,
          ", ".join(f"{f:.5g} Hz ({100 * d:+.3f} %)" for f, d in zip(in_plane, deviation)))

    deviation = [f / r - 1.0 for f, r in zip(held, PUBLISHED_BENDING_HZ)]
    check("bottom edges held: bending modes below NAFEMS'", max(deviation) < 0.0,
          ", ".join(f"{f:.5g} Hz ({100 * d:+.2f} %)" for f, d in zip(held, deviation)))
    if a.coarse_out:
        coarse = load(a.coarse_out, "plate.reduce.json")["frequency_hz"]
        coarse_held = [coarse[i] for i in BENDING_INDEX["plate"]]
        check("bottom edges held: softer on the finer mesh", all(f < c for f, c in zip(held, coarse_held)),
              f"20 x 20 x 4 {[f'{f:.5g}' for f in held]} Hz, 8 x 8 x 2 {[f'{c:.5g}' for c in coarse_held]} Hz")

    print_headline("05_nafems_fv52", max(abs(f / c - 1.0) for v in BENDING_INDEX for f, c in zip(ours[v], ccx[v])),
                   "frequencies against CalculiX on the same mesh (NAFEMS: the table)",
                   runtime_s=reduce_seconds(load(a.out, "plate.reduce.json")), peer="CalculiX (C3D20)",
                   peer_runtime_s=load(a.out, "plate.ccx.json")["seconds"])
    checks.finish(a.plot, lambda path: plot(path, held, faces, in_plane, a.mesh))


def plot(path, held, faces, in_plane, mesh):
    plt = pyplot()
    labels = ["(1,1)", "(1,2)", "(2,1)", "(2,2)", "in-plane", "in-plane", "in-plane"]
    published = PUBLISHED_BENDING_HZ + PUBLISHED_IN_PLANE_HZ
    fig, ax = plt.subplots(figsize=(8, 4.5))
    x = range(len(published))
    ax.axhline(0.0, color="black", linewidth=0.8)
    ax.plot(x[:4], [100 * (f / r - 1) for f, r in zip(held, published)], "o", label="bottom edges held in z (the benchmark)")
    ax.plot(x[:4], [100 * (f / r - 1) for f, r in zip(faces, published)], "s", label="side faces held (3-D simply supported)")
    ax.plot(x[4:], [100 * (f / r - 1) for f, r in zip(in_plane, published[4:])], "^",
            label="in-plane modes, free in plane (CalculiX)")
    ax.set_xticks(list(x), [f"{l}\n{r} Hz" for l, r in zip(labels, published)], fontsize=8)
    ax.set_ylabel("deviation from NAFEMS FV52 [%]")
    ax.set_title(f"NAFEMS FV52 thick plate, hex20 {'20 x 20 x 4' if mesh == 'full' else '8 x 8 x 2'}: "
                 "flexmbs = CalculiX to 1e-6")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    save_figure(fig, path)


if __name__ == "__main__":
    main()
