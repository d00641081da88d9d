#!/usr/bin/python3
"""Reduction speed and peak memory: `flexmbs reduce` against SciPy and CalculiX, and the bound.

For each size a steel bar 1 m x 0.2 m x 0.2 m (tet10, gmsh, one .msh read by every program)
clamped on its face x = 0 (physical group 'clamp'): the lowest --modes fixed-interface modes.
Each program runs in its own process under /usr/bin/time -v (peak resident set size), one
core each (BLAS and OpenMP single-threaded):

  flexmbs reduce BODY.yaml --json   eigensolver spectra; slepc on 1 rank; slepc under
                                    `mpirun -n 2` (time: seconds.reduction = everything after
                                    assembly: held-body matrices, eigen-solve, basis, reduced
                                    matrices; the whole process's wall time is shown too)
  SciPy eigsh                       shift-invert (sigma = 0, which='LM', SuperLU inside) on the
                                    same K, M (`flexmbs mesh --matrix-market`), clamped DOFs
                                    removed; time: the eigsh call only (factorisation + ARPACK)
  CalculiX ccx *FREQUENCY           the same mesh as C3D10 (tests/peers/ccx_modal.py deck);
                                    time: the whole ccx run (and ccx's own "Total CalculiX
                                    Time"; ccx prints no solver split)
  lower bound                       bench_cholmod_bound: one CHOLMOD Cholesky of K on the free
                                    DOFs (ordering + numeric) and 2 x modes single-vector solves

plus a Craig-Bampton body at --cb-size: interfaces 'clamp' and 'tip' (both end faces, rigid
by default), 20 fixed-interface modes, per backend, checked against SciPy with both faces
clamped. Frequencies are checked: flexmbs backends against SciPy (--tol, 1e-6 relative),
CalculiX against SciPy (--ccx-tol: its C3D10 mass is the degree-2 one, tests/peers/README.md).

Usage (Debian's python: gmsh, scipy; after `cmake --build build --target flexmbs
bench_cholmod_bound bench_eigensolver_split`):
  /usr/bin/python3 bench/reduce_bench.py                  # 20k and 100k DOF + CB, ~10 min
  /usr/bin/python3 bench/reduce_bench.py --max-dof 6e5    # with 500k DOF, ~45 min

See bench/README.md.
"""
import argparse
import json
import math
import os
import re
import sys

import numpy as np

from bench_common import (DEFAULT_FLEXMBS, PYTHON, ROOT, TIME, E, NU, RHO, make_box_msh, mesh_size_for,
                          require_executables, run_measured, single_thread_env, timed_run, write_body_yaml)

WHAT = "reduce_bench.py"
PEERS = os.path.join(ROOT, "tests", "peers")
BIN = os.path.join(ROOT, "build", "bin")
BEAM = (1.0, 0.2, 0.2)  # m
BEAM_VOLUME = BEAM[0] * BEAM[1] * BEAM[2]
# DOF h^3 / volume of the tet10 bar meshed by gmsh at size h (measured).
BEAM_MEASURED = [(0.038, 28.75), (0.02, 22.36), (0.0115, 20.13)]
DEFAULT_SIZES = [2e4, 1e5, 5e5]
SOLVERS = ("spectra", "slepc", "slepc_np2")
LABEL = {"spectra": "flexmbs spectra", "slepc": "flexmbs slepc 1 rank", "slepc_np2": "flexmbs slepc np 2",
         "scipy": "SciPy eigsh", "ccx": "CalculiX ccx", "bound": "lower bound"}


# ---- SciPy worker (runs in its own process: python reduce_bench.py --scipy-worker ...) -------

def read_matrix_market(path):
    """A symmetric Matrix Market file (lower triangle) as a full scipy CSC matrix (np.loadtxt:
    about 3x faster than scipy.io.mmread of SciPy 1.10)."""
    import scipy.sparse as sp
    with open(path) as f:
        skip = 0
        for line in f:
            skip += 1
            if not line.startswith("%"):
                n = int(line.split()[0])
                break
    d = np.loadtxt(path, skiprows=skip, ndmin=2)
    i, j, v = d[:, 0].astype(np.int64) - 1, d[:, 1].astype(np.int64) - 1, d[:, 2]
    off = i != j
    return sp.coo_matrix((np.concatenate([v, v[off]]), (np.concatenate([i, j[off]]), np.concatenate([j, i[off]]))),
                         shape=(n, n)).tocsc()


def scipy_worker(a):
    import time
    import scipy.sparse.linalg as sla
    start = time.perf_counter()
    K = read_matrix_market(a.scipy_worker + "_K.mtx")
    M = read_matrix_market(a.scipy_worker + "_M.mtx")
    nodes = np.loadtxt(a.fixed_nodes, dtype=np.int64, ndmin=1)
    fixed = (3 * nodes[:, None] + np.arange(3)[None, :]).ravel()
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    Kf = K[free][:, free].tocsc()
    Mf = M[free][:, free].tocsc()
    del K, M
    prepare = time.perf_counter() - start
    start = time.perf_counter()
    lam, X = sla.eigsh(Kf, k=a.modes, M=Mf, sigma=0.0, which="LM")  # SuperLU of Kf, ARPACK mode 3
    seconds = time.perf_counter() - start
    order = np.argsort(lam)
    lam, X = lam[order], X[:, order]
    KX, MX = Kf @ X, Mf @ X
    residual = np.linalg.norm(KX - MX * lam, axis=0) / np.linalg.norm(KX, axis=0)
    print(json.dumps({"free_dofs": int(free.size), "eigsh_seconds": seconds, "prepare_seconds": prepare,
                      "frequencies_hz": (np.sqrt(lam) / (2 * np.pi)).tolist(),
                      "max_relative_residual": float(residual.max())}))


# ---- the benchmark --------------------------------------------------------------------------

def fixed_node_indices(msh, groups):
    """0-based flexmbs node indices of the nodes of physical groups `groups` (union)."""
    sys.path.insert(0, PEERS)
    from scipy_modal import flexmbs_node_indices
    return np.unique(np.concatenate([flexmbs_node_indices(msh, g)[0] for g in groups]))


def reduction_yaml(method, solver, modes, coupling):
    if method == "fixed_interface":
        held = "  supports: [clamp]\n"
    else:
        held = (f"  interfaces:\n    - {{node_set: clamp, coupling: {coupling}}}\n"
                f"    - {{node_set: tip, coupling: {coupling}}}\n")
    return f"reduction:\n  method: {method}\n  modes: {modes}\n  eigensolver: {solver}\n{held}"


def petsc_log(path):
    """Seconds and counts of a few events of a PETSc -log_view file (max over ranks)."""
    out = {}
    if not os.path.exists(path):
        return out
    for line in open(path):
        m = re.match(r"^(EPSSolve|EPSSetUp|MatCholFctrSym|MatCholFctrNum|MatSolve|BVOrthogonalizeV|SubstrFactor|"
                     r"SubstrSolve)\s+(\d+)\s+\S+\s+(\S+)",
                     line)
        if m:
            out[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return out


def run_flexmbs(a, body, solver, out_dir, tag):
    """One `flexmbs reduce` run; returns a result dict."""
    env = single_thread_env()
    log = os.path.join(out_dir, f"{tag}_{solver}.petsc_log")
    if os.path.exists(log):
        os.remove(log)
    if solver.startswith("slepc"):
        env.update(PETSC_OPTIONS=f"-log_view :{log}", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
        if a.mpi_yield:
            env.update(OMPI_MCA_mpi_yield_when_idle="1")
    cmd = [a.flexmbs, "reduce", body, "-o", os.path.join(out_dir, f"{tag}_{solver}.sid.h5"), "--json"]
    rank_rss = None
    if solver == "slepc_np2":
        # Every rank under its own GNU time, so that the peak RSS of each is known (summed below).
        prefix = os.path.join(out_dir, f"{tag}_rank_rss")
        cmd = ["mpirun", "-n", "2", "--bind-to", "none", "sh", "-c",
               f'f=$1; shift; exec {TIME} -f %M -o "$f.$OMPI_COMM_WORLD_RANK" "$@"', "sh", prefix] + cmd
    r = run_measured(cmd, env=env, timeout=a.flexmbs_timeout)
    if r["status"] != "ok":
        sys.exit(f"{WHAT}: flexmbs {solver} failed ({r['status']}): {' '.join(cmd)}\n{r['stdout'][-1000:]}"
                 f"\n{r['stderr'][-2000:]}")
    if solver == "slepc_np2":
        ranks = [float(open(f"{prefix}.{k}").read().split()[-1]) / 1024.0 for k in range(2)]
        rank_rss = ranks
    j = json.loads(r["stdout"])
    normal = [f for f, name in zip(j["frequency_hz"], j["mode_names"]) if name.startswith("normal")]
    return {"program": solver, "seconds": j["seconds"]["reduction"], "wall_s": r["wall_s"],
            "mesh_s": j["seconds"]["mesh"], "assembly_s": j["seconds"]["assembly"],
            "peak_rss_mb": sum(rank_rss) if rank_rss else r["peak_rss_mb"], "rank_rss_mb": rank_rss,
            "frequencies_hz": normal, "modes": j["modes"], "dofs": j["dofs"], "petsc": petsc_log(log),
            "mpi": j.get("mpi"), "eigensolver": j["seconds"].get("eigensolver")}


def run_scipy(a, prefix, fixed_file):
    r = run_measured([PYTHON, os.path.abspath(__file__), "--scipy-worker", prefix, "--fixed-nodes", fixed_file,
                      "--modes", str(a.modes)], env=single_thread_env(), timeout=a.peer_timeout,
                     memory_gb=a.peer_memory_gb)
    res = {"program": "scipy", "status": r["status"], "wall_s": r["wall_s"], "peak_rss_mb": r["peak_rss_mb"]}
    if r["status"] == "ok":
        j = json.loads(r["stdout"])
        res.update(seconds=j["eigsh_seconds"], frequencies_hz=j["frequencies_hz"],
                   residual=j["max_relative_residual"], prepare_s=j["prepare_seconds"])
    else:
        res["error"] = (r["stderr"].split("\tCommand being timed")[0].strip().splitlines() or [""])[-1][:200]
    return res


def run_ccx(a, msh, ccx_dir):
    sys.path.insert(0, PEERS)
    import ccx_modal
    os.makedirs(ccx_dir, exist_ok=True)
    deck = os.path.join(ccx_dir, "modal.inp")
    if not os.path.exists(deck):
        xyz, blocks, clamped = ccx_modal.read_mesh(msh, "clamp")
        with open(deck + ".tmp", "w") as f:
            ccx_modal.write_deck(f, xyz, blocks, clamped, E, NU, RHO, a.modes)
        os.replace(deck + ".tmp", deck)
    for ext in (".dat", ".frd", ".sta", ".cvg"):
        if os.path.exists(os.path.join(ccx_dir, "modal" + ext)):
            os.remove(os.path.join(ccx_dir, "modal" + ext))
    r = run_measured([a.ccx, "-i", "modal"], env=single_thread_env(), cwd=ccx_dir, timeout=a.peer_timeout,
                     memory_gb=a.peer_memory_gb)
    res = {"program": "ccx", "status": r["status"], "wall_s": r["wall_s"], "peak_rss_mb": r["peak_rss_mb"]}
    dat = os.path.join(ccx_dir, "modal.dat")
    freqs = ccx_modal.parse_frequencies(open(dat).read()) if os.path.exists(dat) else None
    if r["status"] == "ok" and freqs and len(freqs) >= a.modes:
        m = re.search(r"Total CalculiX Time:\s*(\S+)", r["stdout"])
        res.update(seconds=r["wall_s"], own_total_s=float(m.group(1)) if m else None, frequencies_hz=freqs[:a.modes])
    elif r["status"] == "ok":
        res["status"] = "no frequencies"
    return res


def run_bound(a, prefix, fixed_file):
    out, rss, wall = timed_run([a.bound, prefix + "_K.mtx", "--fixed-nodes", fixed_file, "--solves",
                                str(2 * a.modes)], env=single_thread_env(), what=WHAT)
    j = json.loads(out)
    j.update(program="bound", seconds=j["bound_seconds"], peak_rss_mb=rss)
    return j


def run_split(a, prefix, fixed_file):
    out, rss, wall = timed_run([a.split, prefix + "_K.mtx", prefix + "_M.mtx", "--fixed-nodes", fixed_file,
                                "--modes", str(a.modes)], env=single_thread_env(), what=WHAT)
    return json.loads(out)


def max_rel_diff(f, ref):
    if not f or not ref or len(f) != len(ref):
        return float("nan")
    return max(abs(x / y - 1.0) for x, y in zip(sorted(f), sorted(ref)))


def fmt_s(r):
    if r.get("seconds") is not None:
        return f"{r['seconds']:.2f}"
    return f">{r['wall_s']:.0f}" if r.get("status") == "timeout" else "failed"


def prepare_size(a, target, tag_prefix=""):
    """Mesh, body files, matrices and fixed-node files of one size (all cached in workdir)."""
    h = mesh_size_for(target, BEAM_MEASURED, BEAM_VOLUME)
    tag = f"bar_h{h:.5f}"
    msh = os.path.join(a.workdir, tag + ".msh")
    if not os.path.exists(msh):
        make_box_msh(msh + ".tmp.msh", h, BEAM, ("clamp", "tip"))
        os.replace(msh + ".tmp.msh", msh)
    prefix = os.path.join(a.workdir, tag)
    plain = os.path.join(a.workdir, tag + "_mesh.yaml")
    write_body_yaml(plain, msh, "bench_bar", ("clamp", "tip"))
    if not (os.path.exists(prefix + "_K.mtx") and os.path.exists(prefix + "_M.mtx")):
        timed_run([a.flexmbs, "mesh", plain, "--json", "--matrix-market", prefix], env=single_thread_env(), what=WHAT)
    return h, tag, msh, prefix


def fixed_file_for(a, tag, msh, groups):
    path = os.path.join(a.workdir, f"{tag}_fixed_{'_'.join(groups)}.txt")
    if not os.path.exists(path):
        np.savetxt(path, fixed_node_indices(msh, groups), fmt="%d")
    return path


def print_rows(rows, ref_key):
    """One line per program of one case, with ratios and the frequency check."""
    by = {r["program"]: r for r in rows}
    ref = by.get("scipy", {}).get("frequencies_hz")
    ref_name = "scipy"
    if not ref:  # SciPy did not finish or was skipped: check against the first flexmbs backend that ran
        ref_name = next((p for p in SOLVERS if by.get(p, {}).get("frequencies_hz")), None)
        ref = by[ref_name]["frequencies_hz"] if ref_name else None
    bound = by.get("bound", {}).get("seconds")
    for r in rows:
        p = r["program"]
        ratio_bound = f"{r['seconds'] / bound:.2f}" if bound and r.get("seconds") and p != "bound" else ""
        scipy_r = ccx_r = ""
        if p in SOLVERS:
            sp, cx = by.get("scipy"), by.get("ccx")
            if sp:
                scipy_r = (f"{sp['seconds'] / r['seconds']:.2f}" if sp.get("seconds") else
                           f">{sp['wall_s'] / r['seconds']:.1f}" if sp.get("status") == "timeout" else "-")
            if cx:
                ccx_r = (f"{cx['seconds'] / r['wall_s']:.2f}" if cx.get("seconds") else
                         f">{cx['wall_s'] / r['wall_s']:.1f}" if cx.get("status") == "timeout" else "-")
        diff, check = "", ""
        if ref and r.get("frequencies_hz") and p != ref_name:
            d = max_rel_diff(r["frequencies_hz"], ref)
            tol = a_tol["ccx"] if p == "ccx" else a_tol["flexmbs"]
            diff, check = f"{d:.1e}", ("ok" if d <= tol else "MISMATCH") + f" vs {ref_name}"
            r["max_rel_diff"], r["check"] = d, check
        elif p == ref_name:
            check = "reference"
        if p == "scipy" and r.get("status") != "ok":
            check = r["status"] + (f" ({r.get('error')})" if r.get("error") else "")
        if p == "ccx" and r.get("status") != "ok":
            check = r["status"]
        what = {"spectra": "reduction", "slepc": "reduction", "slepc_np2": "reduction", "scipy": "eigsh",
                "ccx": "whole run", "bound": "Chol+solves"}[p]
        wall = f"{r['wall_s']:.1f}" if p in SOLVERS else (f"{r['own_total_s']:.1f}" if r.get("own_total_s") else "")
        rss = f"{r['peak_rss_mb']:.0f}" if math.isfinite(r["peak_rss_mb"]) else "-"
        print(f"{ref_key:>8} {LABEL[p]:<21} {fmt_s(r):>8} {what:<11} {wall:>7} {rss:>8} "
              f"{ratio_bound:>6} {scipy_r:>7} {ccx_r:>7} {diff:>8}  {check}", flush=True)


a_tol = {}


def header():
    h = (f"{'DOF':>8} {'program':<21} {'seconds':>8} {'timed':<11} {'wall s':>7} {'peak MB':>8} "
         f"{'xbound':>6} {'scipy/':>7} {'ccx/':>7} {'max df/f':>8}  check")
    print(h)
    print("-" * (len(h) + 12), flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--max-dof", type=float, default=1.5e5, help="skip sizes whose target DOF exceeds this")
    p.add_argument("--sizes", help="comma-separated target DOF counts (default 2e4,1e5,5e5; '' for the "
                   "Craig-Bampton body alone)")
    p.add_argument("--modes", type=int, default=20)
    p.add_argument("--cb-size", type=float, default=1e5, help="target DOF of the Craig-Bampton body (0: none)")
    p.add_argument("--cb-coupling", default="rigid", choices=("rigid", "nodes"),
                   help="coupling of the two end-face interfaces of the Craig-Bampton body")
    p.add_argument("--skip", default="", help="comma-separated programs not to run: scipy,ccx,split,slepc_np2,...")
    p.add_argument("--tol", type=float, default=1e-6, help="relative frequency agreement, flexmbs vs SciPy")
    p.add_argument("--ccx-tol", type=float, default=3e-4,
                   help="relative frequency agreement, CalculiX vs SciPy (degree-2 C3D10 mass)")
    p.add_argument("--peer-timeout", type=float, default=600.0, help="s; a peer still running then is stopped")
    p.add_argument("--peer-memory-gb", type=float, default=16.0, help="address-space limit of each peer process")
    p.add_argument("--flexmbs-timeout", type=float, default=1800.0)
    p.add_argument("--mpi-yield", action="store_true",
                   help="let waiting MPI ranks yield their core (OMPI_MCA_mpi_yield_when_idle=1): on a machine "
                        "shared with other jobs a polling rank holds a core the other rank needs (bench/README.md)")
    p.add_argument("--flexmbs", default=DEFAULT_FLEXMBS)
    p.add_argument("--bound", default=os.path.join(BIN, "bench_cholmod_bound"))
    p.add_argument("--split", default=os.path.join(BIN, "bench_eigensolver_split"))
    p.add_argument("--ccx", default="/usr/bin/ccx")
    p.add_argument("--workdir", default="/tmp/flexmbs_reduce_bench", help="meshes and matrices are kept here")
    p.add_argument("--json-out", help="also write the results as JSON")
    p.add_argument("--scipy-worker", help=argparse.SUPPRESS)
    p.add_argument("--fixed-nodes", help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.scipy_worker:
        return scipy_worker(a)

    skip = set(s for s in a.skip.split(",") if s)
    a_tol.update(flexmbs=a.tol, ccx=a.ccx_tol)
    require_executables([a.flexmbs, a.bound, TIME, PYTHON] + ([a.split] if "split" not in skip else []) +
                        ([a.ccx] if "ccx" not in skip else []), WHAT)
    os.makedirs(a.workdir, exist_ok=True)
    targets = [float(s) for s in a.sizes.split(",") if s.strip()] if a.sizes is not None else DEFAULT_SIZES
    targets = [t for t in targets if t <= a.max_dof]
    solvers = [s for s in SOLVERS if s not in skip]

    print(f"# flexmbs {a.flexmbs}; bar {BEAM[0]} x {BEAM[1]} x {BEAM[2]} m, tet10, steel; lowest {a.modes} modes; "
          f"one thread per process; load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores", flush=True)
    header()
    results = {"cases": []}
    for target in targets:
        h, tag, msh, prefix = prepare_size(a, target)
        fixed = fixed_file_for(a, tag, msh, ["clamp"])
        rows = []
        for s in solvers:
            body = os.path.join(a.workdir, f"{tag}_{s}.yaml")
            write_body_yaml(body, msh, "bench_bar", ("clamp", "tip"),
                            reduction_yaml("fixed_interface", s.split("_")[0], a.modes, a.cb_coupling))
            rows.append(run_flexmbs(a, body, s, a.workdir, tag))
        rows.append(run_bound(a, prefix, fixed))
        if "scipy" not in skip:
            rows.append(run_scipy(a, prefix, fixed))
        if "ccx" not in skip:
            rows.append(run_ccx(a, msh, os.path.join(a.workdir, tag + "_ccx")))
        split = run_split(a, prefix, fixed) if "split" not in skip else None
        dofs = rows[0]["dofs"]
        print_rows(rows, dofs)
        case = {"case": "fixed_interface", "dofs": dofs, "mesh_size_m": h, "msh": msh, "rows": rows,
                "spectra_split": split, "load_average": os.getloadavg()[0]}
        results["cases"].append(case)
        print_details(case)

    if a.cb_size > 0 and a.cb_size <= a.max_dof:
        h, tag, msh, prefix = prepare_size(a, a.cb_size)
        fixed = fixed_file_for(a, tag, msh, ["clamp", "tip"])
        rows = []
        for s in solvers:
            body = os.path.join(a.workdir, f"{tag}_cb_{s}.yaml")
            write_body_yaml(body, msh, "bench_bar_cb", ("clamp", "tip"),
                            reduction_yaml("craig_bampton", s.split("_")[0], a.modes, a.cb_coupling))
            rows.append(run_flexmbs(a, body, s, a.workdir, tag + "_cb"))
        rows.append(run_bound(a, prefix, fixed))
        if "scipy" not in skip:
            rows.append(run_scipy(a, prefix, fixed))
        dofs = rows[0]["dofs"]
        print(f"-- Craig-Bampton: interfaces clamp and tip ({a.cb_coupling}), {rows[0]['modes']['constraint']} "
              f"constraint + {rows[0]['modes']['normal']} normal modes; bound and SciPy: both faces clamped")
        print_rows(rows, f"CB {dofs}")
        case = {"case": "craig_bampton", "coupling": a.cb_coupling, "dofs": dofs, "mesh_size_m": h, "msh": msh,
                "rows": rows, "load_average": os.getloadavg()[0]}
        results["cases"].append(case)
        print_details(case)

    print("\nseconds: flexmbs = seconds.reduction of its JSON (all after assembly; 'wall s' = the whole process, "
          "mpirun included); SciPy = the eigsh call (SuperLU factorisation + ARPACK), reading the matrices not "
          "included; CalculiX = the whole ccx run ('wall s' column: ccx's own Total CalculiX Time); bound = CHOLMOD "
          f"ordering + factorisation of K on the free DOFs + {2 * a.modes} single-vector solves. xbound = seconds / "
          "bound; scipy/ = SciPy seconds / flexmbs seconds; ccx/ = ccx whole run / flexmbs whole process "
          "(> 1: flexmbs faster; '>' where the peer hit --peer-timeout). peak MB: the process (np 2: sum over the "
          f"ranks). check: max relative frequency difference, flexmbs {a.tol:g}, CalculiX {a.ccx_tol:g}.")
    goals(results, a)
    if a.json_out:
        with open(a.json_out, "w") as f:
            json.dump(results, f, indent=2)


def print_details(case):
    """Where the time goes: SLEPc's PETSc log and the spectra backend's own accounting."""
    by = {r["program"]: r for r in case["rows"]}
    for s in ("slepc", "slepc_np2"):
        r = by.get(s)
        if r and r.get("petsc"):
            g = r["petsc"]
            # The eigen-solve's factorisation: MUMPS's, or on 2+ ranks the substructured one
            # (docs/reduction.md), whose solves are logged as SubstrSolve.
            substructured = (r.get("eigensolver") or {}).get("factorization") == "substructured"
            fac = sum(g.get(k, (0, 0.0))[1] for k in ("MatCholFctrSym", "MatCholFctrNum", "SubstrFactor"))
            solves, solve_s = (sum(g.get(k, (0, 0.0))[i] for k in ("MatSolve", "SubstrSolve")) for i in (0, 1))
            krylov = g.get("BVOrthogonalizeV", (0, 0.0))[0]  # one per Krylov-Schur step
            eps = g.get("EPSSolve", (0, 0.0))[1]
            kind = "substructured" if substructured else "MUMPS"
            print(f"   {LABEL[s]}: {kind} Cholesky {fac:.2f} s, {solves} solves ({krylov} Krylov-Schur steps, "
                  f"{solves - krylov} others: the SID step's static solves, purifications only for a singular M) "
                  f"{solve_s:.2f} s ({1e3 * solve_s / max(solves, 1):.0f} ms each), EPSSolve {eps:.2f} s, outside "
                  f"EPSSolve {r['seconds'] - eps:.2f} s (the Sturm count and the basis; the other solves, "
                  f"~{(solves - krylov) * solve_s / max(solves, 1):.2f} s, come after it in the SID step); mesh+assembly "
                  f"{r['mesh_s'] + r['assembly_s']:.2f} s")
        if r and r.get("mpi"):
            m, ranks = r["mpi"]["seconds"], r["mpi"]["ranks"]
            each = lambda key, fmt: "/".join(format(k[key], fmt) for k in ranks)
            print(f"   {LABEL[s]} distributed path (reduce --json 'mpi'): partition+scatter {m['partition_scatter']:.2f} s, "
                  f"assembly {m['assembly']:.2f} s, factorisation+solve {m['factorisation_solve']:.2f} s, gather "
                  f"{m['gather']:.2f} s, basis on rank 0 {m['basis_rank0']:.2f} s; per rank: rows {each('rows', 'd')}, "
                  f"K nonzeros {each('nonzeros', 'd')}, peak RSS after the solve {each('peak_rss_mb_after_solve', '.0f')} MB")
    sp = case.get("spectra_split")
    if sp:
        print(f"   flexmbs spectra (same solve, bench_eigensolver_split): {sp['seconds']:.2f} s = factorisation "
              f"{sp['factorization_seconds']:.2f} + Sturm {sp['sturm_seconds']:.2f} + Krylov "
              f"{sp['krylov_seconds']:.2f} (+ residuals, rest {sp['seconds'] - sp['factorization_seconds'] - sp['sturm_seconds'] - sp['krylov_seconds']:.2f}); "
              f"{sp['operator_applications']} solves, {sp['krylov_runs']} Lanczos runs, {sp['restarts']} restarts, "
              f"check {sp['missed_mode_check']}")
    b = by.get("bound")
    if b:
        print(f"   bound: ordering ({b['ordering']}) + symbolic {b['analyze_seconds']:.2f} s, numeric "
              f"{b['factorize_seconds']:.2f} s ({b['factor_flops'] / 1e9:.0f} Gflop, nnz(L) "
              f"{b['factor_nonzeros'] / 1e6:.0f} M), {b['solves']} solves {b['solve_seconds']:.2f} s "
              f"({1e3 * b['solve_seconds'] / b['solves']:.0f} ms each)", flush=True)


def goals(results, a):
    fixed = [c for c in results["cases"] if c["case"] == "fixed_interface"]
    if not fixed:
        return
    big = max(fixed, key=lambda c: c["dofs"])
    by = {r["program"]: r for r in big["rows"]}
    print(f"\nGoals at the largest body run ({big['dofs']} DOF):")

    def peer_ratio(peer, r, key):
        q = by.get(peer)
        if not q:
            return None, "not run"
        if q.get("seconds"):
            return q["seconds"] / r[key], f"{q['seconds'] / r[key]:.2f}x"
        if q.get("status") == "timeout":
            return q["wall_s"] / r[key], f">{q['wall_s'] / r[key]:.1f}x (peer stopped at {q['wall_s']:.0f} s)"
        return None, f"peer {q.get('status')}"

    for s in SOLVERS:
        r = by.get(s)
        if not r:
            continue
        rs, ts = peer_ratio("scipy", r, "seconds")
        rc, tc = peer_ratio("ccx", r, "wall_s")
        ok = rs is not None and rc is not None and rs >= 2 and rc >= 2
        xb = r["seconds"] / by["bound"]["seconds"]
        print(f"  {LABEL[s]:<21} >= 2x faster than both peers: {'MET' if ok else 'MISSED'} (SciPy {ts}, CalculiX "
              f"{tc}); within 2x of the bound: {'MET' if xb <= 2 else 'MISSED'} ({xb:.2f}x)")
    if "slepc" in by and "slepc_np2" in by:
        sp = by["slepc"]["seconds"] / by["slepc_np2"]["seconds"]
        print(f"  mpirun -n 2 >= 1.6x faster than 1 rank: {'MET' if sp >= 1.6 else 'MISSED'} ({sp:.2f}x on "
              f"seconds.reduction, {by['slepc']['wall_s'] / by['slepc_np2']['wall_s']:.2f}x on the whole process)")


if __name__ == "__main__":
    main()
