#!/usr/bin/python3
"""Lowest natural frequencies of a clamped gmsh mesh, computed by CalculiX (ccx).

An independent peer for flexmbs' FE matrices: it reads a gmsh .msh file (tet4 or tet10
volume elements), writes a CalculiX input deck (C3D4 / C3D10, linear isotropic material,
the nodes of one physical group clamped in all three directions, *FREQUENCY), runs `ccx`
in a temporary directory and prints the eigenfrequencies as JSON on stdout:

  {"peer": "CalculiX", "ccx_version": "2.20", "element": "C3D10", "nodes": ...,
   "elements": ..., "clamped_nodes": ..., "frequencies_hz": [...], "seconds": ...}

Usage:
  /usr/bin/python3 ccx_modal.py MESH.msh --clamp GROUP --youngs-modulus 2.1e11 \
      --poisson-ratio 0.3 --density 7850 --modes 8 [--keep DIR] [--ccx ccx]

Needs python3-gmsh (Debian: seen by /usr/bin/python3) and CalculiX (`ccx`,
Debian package calculix-ccx).

Note on quadrature: CalculiX 2.20 integrates the C3D10 stiffness AND mass matrices with the
same 4-point (degree 2) rule, while the consistent tet10 mass integrand N_a N_b has degree
4. Its K equals flexmbs' to 1e-12, its M is the degree-2 mass (26 % away from the exact one
in Frobenius norm). Well-resolved modes do not see this (cantilever, 8 lowest modes: 2e-7);
modes with one or two tet10 per half-wave do (up to 2 %). See tests/peers/README.md.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import gmsh

# gmsh element type -> (CalculiX type, permutation: ccx node k = gmsh node perm[k]).
# gmsh tet10 edges:  4=(0,1) 5=(1,2) 6=(0,2) 7=(0,3) 8=(2,3) 9=(1,3)
# Abaqus/CalculiX C3D10 (0-based corners): 4=(0,1) 5=(1,2) 6=(2,0) 7=(0,3) 8=(1,3) 9=(2,3)
# so the last two mid-edge nodes swap.
ELEMENTS = {
    4: ("C3D4", [0, 1, 2, 3]),
    11: ("C3D10", [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
}


def fail(message):
    print(f"ccx_modal.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_mesh(path, clamp_group):
    """Nodes (tag -> xyz) used by volume elements, elements per gmsh type, clamped tags."""
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        types, element_tags, node_tags = gmsh.model.mesh.getElements(3)
        if len(types) == 0:
            fail(f"{path}: no volume (3-D) elements")
        blocks = []
        used = set()
        for t, et, nt in zip(types, element_tags, node_tags):
            if t not in ELEMENTS:
                name = gmsh.model.mesh.getElementProperties(t)[0]
                fail(f"{path}: element type {name} (gmsh type {t}) is not supported (tet4, tet10)")
            n = len(nt) // len(et)
            conn = [list(map(int, nt[i * n:(i + 1) * n])) for i in range(len(et))]
            blocks.append((int(t), list(map(int, et)), conn))
            used.update(int(x) for x in nt)
        tags, coords, _ = gmsh.model.mesh.getNodes(-1, -1, False, False)
        xyz = {}
        for i, tag in enumerate(tags):
            tag = int(tag)
            if tag in used:
                xyz[tag] = (coords[3 * i], coords[3 * i + 1], coords[3 * i + 2])
        groups = {}
        for dim, tag in gmsh.model.getPhysicalGroups():
            groups[gmsh.model.getPhysicalName(dim, tag)] = (dim, tag)
        if clamp_group not in groups:
            fail(f"{path}: no physical group '{clamp_group}' (the file has: {', '.join(sorted(groups)) or 'none'})")
        group_tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(*groups[clamp_group])
        clamped = sorted({int(t) for t in group_tags} & used)
        if not clamped:
            fail(f"{path}: physical group '{clamp_group}' has no nodes on the solid mesh")
        return xyz, blocks, clamped
    finally:
        gmsh.finalize()


def write_deck(f, xyz, blocks, clamped, E, nu, rho, modes):
    f.write("** written by flexmbs tests/peers/ccx_modal.py\n*NODE, NSET=NALL\n")
    for tag in sorted(xyz):
        x, y, z = xyz[tag]
        f.write(f"{tag}, {x:.17g}, {y:.17g}, {z:.17g}\n")
    for gmsh_type, element_tags, conn in blocks:
        ccx_type, perm = ELEMENTS[gmsh_type]
        f.write(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL\n")
        for tag, nodes in zip(element_tags, conn):
            f.write(f"{tag}, " + ", ".join(str(nodes[k]) for k in perm) + "\n")
    f.write("*NSET, NSET=NCLAMP\n")
    for i in range(0, len(clamped), 8):
        f.write(", ".join(map(str, clamped[i:i + 8])) + ",\n")
    f.write("*BOUNDARY\nNCLAMP, 1, 3\n")
    f.write(f"*MATERIAL, NAME=MAT\n*ELASTIC\n{E:.17g}, {nu:.17g}\n*DENSITY\n{rho:.17g}\n")
    f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n")
    f.write(f"*STEP\n*FREQUENCY\n{modes}\n*END STEP\n")


def parse_frequencies(dat_text):
    """Frequencies (cycles/time) from the first 'E I G E N V A L U E   O U T P U T' table."""
    start = dat_text.find("E I G E N V A L U E   O U T P U T")
    if start < 0:
        return None
    freqs = []
    row = re.compile(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$")
    started = False
    for line in dat_text[start:].splitlines()[1:]:
        m = row.match(line)
        if m:
            started = True
            freqs.append(float(m.group(4)))
        elif started and line.strip():
            break
    return freqs


def ccx_version(ccx):
    try:
        out = subprocess.run([ccx, "-v"], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else "unknown"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("mesh", help="gmsh .msh file with tet4/tet10 volume elements")
    p.add_argument("--clamp", required=True, help="physical group whose nodes are fixed (all 3 directions)")
    p.add_argument("--youngs-modulus", type=float, required=True, help="Pa")
    p.add_argument("--poisson-ratio", type=float, required=True)
    p.add_argument("--density", type=float, required=True, help="kg/m^3")
    p.add_argument("--modes", type=int, default=8, help="number of eigenfrequencies")
    p.add_argument("--ccx", default="ccx", help="CalculiX executable (default: ccx on PATH)")
    p.add_argument("--keep", help="write the deck and ccx output to this directory and keep it")
    a = p.parse_args()

    ccx = shutil.which(a.ccx)
    if ccx is None:
        fail(f"CalculiX executable '{a.ccx}' not found (Debian: apt-get install calculix-ccx)")
    if not os.path.isfile(a.mesh):
        fail(f"{a.mesh}: no such file")
    start = time.perf_counter()
    xyz, blocks, clamped = read_mesh(a.mesh, a.clamp)

    workdir = a.keep or tempfile.mkdtemp(prefix="ccx_modal_")
    os.makedirs(workdir, exist_ok=True)
    ok = False
    try:
        with open(os.path.join(workdir, "modal.inp"), "w") as f:
            write_deck(f, xyz, blocks, clamped, a.youngs_modulus, a.poisson_ratio, a.density, a.modes)
        env = dict(os.environ)
        env.setdefault("OMP_NUM_THREADS", "1")
        run = subprocess.run([ccx, "-i", "modal"], cwd=workdir, capture_output=True, text=True, env=env)
        dat_path = os.path.join(workdir, "modal.dat")
        dat = open(dat_path).read() if os.path.exists(dat_path) else ""
        freqs = parse_frequencies(dat)
        if run.returncode != 0 or not freqs or "*ERROR" in run.stdout:
            errors = [l for l in run.stdout.splitlines() if "ERROR" in l][:5]
            fail(f"ccx failed (exit {run.returncode}); deck and output kept in {workdir}: "
                 + (" | ".join(errors) or run.stdout[-500:]))
        if len(freqs) < a.modes:
            fail(f"ccx returned {len(freqs)} of {a.modes} requested eigenfrequencies (kept {workdir})")
        ok = True
    finally:
        if ok and not a.keep:
            shutil.rmtree(workdir, ignore_errors=True)

    result = {
        "peer": "CalculiX",
        "ccx_version": ccx_version(ccx),
        "element": "+".join(sorted({ELEMENTS[t][0] for t, _, _ in blocks})),
        "nodes": len(xyz),
        "elements": sum(len(et) for _, et, _ in blocks),
        "clamped_nodes": len(clamped),
        "frequencies_hz": freqs[:a.modes],
        "seconds": time.perf_counter() - start,
    }
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
