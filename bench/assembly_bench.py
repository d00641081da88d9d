#!/usr/bin/python3
"""Assembly speed and peak memory: flexmbs against FEniCS (DOLFINx 0.5) on the same meshes.

For each size it meshes a unit steel cube with gmsh (tet10, Mesh.SecondOrderIncomplete=1,
unstructured, one .msh file read by both programs), then in separate processes, each under
/usr/bin/time -v for its peak resident set size:
  flexmbs mesh BODY.yaml --json   -> seconds.assembly (sparsity pattern + K + M, serial)
  bench/dolfinx_assemble.py MSH   -> the same forms on the same mesh (P2 vector Lagrange on
                                     the P2 geometry), pattern + K + M, serial PETSc AIJ
and prints a table with the ratio dolfinx / flexmbs (> 1: flexmbs is faster).

Usage (from anywhere; Debian's python with gmsh, dolfinx):
  /usr/bin/python3 bench/assembly_bench.py [--max-dof 1e6] [--repeat 3] [--json-out FILE]

See bench/README.md.
"""
import argparse
import json
import os

from bench_common import (DEFAULT_FLEXMBS, E, HERE, NU, PYTHON, RHO, TIME, make_box_msh, mesh_size_for,
                          require_executables, single_thread_env, timed_run, write_body_yaml)

WHAT = "assembly_bench.py"
DEFAULT_TARGETS = [1e4, 3e4, 1e5, 3e5, 1e6]
# DOF * h^3 of a tet10 unit cube meshed by gmsh at size h, nearly linear in h (boundary
# layer): measured 27.3 at h = 0.126, 18.8 at h = 0.028. Refitted from the meshes made.
MEASURED_DOF_TIMES_H3 = [(0.126, 27.3), (0.028, 18.8)]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--max-dof", type=float, default=1.2e6, help="skip sizes whose target DOF exceeds this")
    p.add_argument("--sizes", help="comma-separated target DOF counts (default 1e4,3e4,1e5,3e5,1e6)")
    p.add_argument("--repeat", type=int, default=3,
                   help="runs per size, fastest kept (only one run once a flexmbs assembly takes > 5 s)")
    p.add_argument("--stiffness-degree", type=int, default=3,
                   help="DOLFINx quadrature degree for K (flexmbs tet10: degree 3, 8 points)")
    p.add_argument("--mass-degree", type=int, default=4,
                   help="DOLFINx quadrature degree for M (basix degree 4: 14 points; flexmbs: 14 points, degree 5)")
    p.add_argument("--flexmbs", default=DEFAULT_FLEXMBS)
    p.add_argument("--workdir", default="/tmp/flexmbs_assembly_bench", help="meshes are kept here and reused")
    p.add_argument("--json-out", help="also write the results as JSON")
    a = p.parse_args()

    require_executables((a.flexmbs, TIME, PYTHON), WHAT)
    os.makedirs(a.workdir, exist_ok=True)
    targets = [float(s) for s in a.sizes.split(",")] if a.sizes else DEFAULT_TARGETS
    targets = [t for t in targets if t <= a.max_dof]
    env = single_thread_env()

    # DOLFINx's fixed cost (interpreter, dolfinx, PETSc, gmsh) for reading its peak RSS.
    _, dfx_base_mb, _ = timed_run([PYTHON, "-c", "import gmsh, dolfinx.fem.petsc, dolfinx.io.gmshio"], env, what=WHAT)
    _, fx_base_mb, _ = timed_run([a.flexmbs, "--version"], env, what=WHAT)

    print(f"# flexmbs {a.flexmbs}; DOLFINx: K degree {a.stiffness_degree}, M degree {a.mass_degree}; "
          f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores", flush=True)
    print(f"# baseline peak RSS: flexmbs --version {fx_base_mb:.0f} MB, python+dolfinx imports {dfx_base_mb:.0f} MB",
          flush=True)
    header = (f"{'DOF':>9} {'tet10':>8} {'flexmbs s':>10} {'dolfinx s':>10} {'ratio':>6} "
              f"{'flexmbs MB':>11} {'dolfinx MB':>11}  {'dolfinx pattern/K/M s':>22} {'load':>5}  check")
    print(header)
    print("-" * len(header), flush=True)

    rows = []
    for target in targets:
        h = mesh_size_for(target, MEASURED_DOF_TIMES_H3)
        msh = os.path.join(a.workdir, f"box_h{h:.5f}.msh")
        if not os.path.exists(msh):
            make_box_msh(msh, h)
        body = os.path.join(a.workdir, f"box_h{h:.5f}.yaml")
        write_body_yaml(body, msh, "bench_box")

        # Interleaved runs (flexmbs, DOLFINx, flexmbs, ...), fastest of each kept, so that a
        # burst of load from other work on the machine hits both sides alike.
        fx_best, fx_rss, dfx, dfx_rss = None, 0.0, None, 0.0
        for r in range(max(1, a.repeat)):
            out, rss, _ = timed_run([a.flexmbs, "mesh", body, "--json"], env, what=WHAT)
            j = json.loads(out)
            fx_rss = max(fx_rss, rss)
            if fx_best is None or j["seconds"]["assembly"] < fx_best["seconds"]["assembly"]:
                fx_best = j
            out, rss, _ = timed_run(
                [PYTHON, os.path.join(HERE, "dolfinx_assemble.py"), msh,
                 "--youngs-modulus", repr(E), "--poisson-ratio", repr(NU), "--density", repr(RHO),
                 "--stiffness-degree", str(a.stiffness_degree), "--mass-degree", str(a.mass_degree)], env, what=WHAT)
            d = json.loads(out)
            dfx_rss = max(dfx_rss, rss)
            if dfx is None or d["seconds"]["assembly"] < dfx["seconds"]["assembly"]:
                dfx = d
            if j["seconds"]["assembly"] > 5.0:
                break

        dofs = fx_best["dofs"]
        MEASURED_DOF_TIMES_H3.append((h, dofs * h ** 3))
        fx_s = fx_best["seconds"]["assembly"]
        dfx_s = dfx["seconds"]["assembly"]
        same = (dfx["dofs"] == dofs and dfx["stiffness_nonzeros"] == fx_best["stiffness_nonzeros"]
                and abs(dfx["mass_kg"] / fx_best["mass_kg"] - 1) < 1e-10)
        row = {
            "dofs": dofs, "tet10": fx_best["elements"].get("tet10", 0), "mesh_size_m": h, "msh": msh,
            "flexmbs": {"assembly_s": fx_s, "mesh_s": fx_best["seconds"]["mesh"], "peak_rss_mb": fx_rss,
                        "stiffness_nonzeros": fx_best["stiffness_nonzeros"], "mass_kg": fx_best["mass_kg"]},
            "dolfinx": {"assembly_s": dfx_s, "pattern_s": dfx["seconds"]["pattern"],
                        "stiffness_s": dfx["seconds"]["stiffness"], "mass_s": dfx["seconds"]["mass"],
                        "read_mesh_s": dfx["seconds"]["read_mesh"], "peak_rss_mb": dfx_rss,
                        "stiffness_nonzeros": dfx["stiffness_nonzeros"], "mass_kg": dfx["mass_kg"],
                        "quadrature_points": dfx["quadrature_points"]},
            "ratio_dolfinx_over_flexmbs": dfx_s / fx_s,
            "same_pattern_and_mass": same,
        }
        load = os.getloadavg()[0]
        row["load_average"] = load
        rows.append(row)
        split = f"{dfx['seconds']['pattern']:.2f}/{dfx['seconds']['stiffness']:.2f}/{dfx['seconds']['mass']:.2f}"
        print(f"{dofs:>9} {row['tet10']:>8} {fx_s:>10.3f} {dfx_s:>10.3f} {dfx_s / fx_s:>6.2f} "
              f"{fx_rss:>11.0f} {dfx_rss:>11.0f}  {split:>22} {load:>5.1f}  {'ok' if same else 'MISMATCH'}", flush=True)

    print("\nratio = dolfinx s / flexmbs s (> 1: flexmbs faster); load = 1-minute load average "
          "after the size (other work on the machine); check: same DOF count, same nonzeros in K, "
          "same total mass (1e-10).")
    if a.json_out:
        with open(a.json_out, "w") as f:
            json.dump({"baseline_rss_mb": {"flexmbs": fx_base_mb, "dolfinx": dfx_base_mb},
                       "load_average": os.getloadavg()[0], "rows": rows}, f, indent=2)


if __name__ == "__main__":
    main()
