#!/usr/bin/python3
"""Lowest natural frequencies of a body held by supports, computed by CalculiX (ccx).

The one CalculiX driver of the repository, an independent peer for flexmbs' FE matrices: of
tests/peers/peer_frequency_test.cc (a tet mesh clamped on one group), of bench/reduce_bench.py
(its functions read_mesh, write_deck, parse_frequencies) and of cases 05_nafems_fv52 and
07_bracket_modes (hex20, supports by component). It reads a gmsh .msh as it is, or meshes a .geo
or .step exactly as flexmbs does (Mesh.MeshSizeMax, Mesh.ElementOrder, Mesh.SecondOrderIncomplete
= 1), writes a CalculiX deck (C3D4, C3D10 or C3D20, one linear isotropic material, each held node
set's nodes held in its components by *BOUNDARY, *FREQUENCY), runs `ccx` in a temporary
directory and prints JSON:

  {"peer": "CalculiX", "ccx_version": "2.20", "element": "C3D10", "nodes": ..., "elements": ...,
   "clamped_nodes": ..., "held_dofs": ..., "frequencies_hz": [...], "seconds": ...}

(`clamped_nodes`: the nodes of the --clamp group, 0 without one.)

Usage:
  /usr/bin/python3 ccx_modal.py MESH.msh --clamp GROUP --youngs-modulus 2.1e11 \
      --poisson-ratio 0.3 --density 7850 --modes 8 [--keep DIR] [--ccx ccx]
  /usr/bin/python3 ccx_modal.py GEOMETRY.geo --order 2 [--mesh-size h] --youngs-modulus 2e11 \
      --poisson-ratio 0.3 --density 8000 --modes 6 --hold bottom_edges:z --hold mid_x:x
(--clamp G is --hold G:xyz; both may be given, each more than once.) Needs python3-gmsh (Debian:
seen by /usr/bin/python3) and CalculiX (`ccx`, Debian package calculix-ccx).

Quadrature: CalculiX 2.20 integrates C3D20 stiffness and mass with 3 x 3 x 3 Gauss points, as
flexmbs does for hex20 (docs/elements.md), so on an undistorted structured mesh both matrices are
the same up to round-off. It integrates the C3D10 stiffness AND mass matrices with the same
4-point (degree 2) rule, while the consistent tet10 mass integrand N_a N_b has degree 4: its K
equals flexmbs' to 1e-12, its M is the degree-2 mass (26 % away from the exact one in Frobenius
norm). Well-resolved modes do not see this (cantilever, 8 lowest modes: 2e-7); modes with one or
two tet10 per half-wave do (up to 2 %). See tests/peers/README.md.
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
# tet10: gmsh's edges 4=(0,1) 5=(1,2) 6=(0,2) 7=(0,3) 8=(2,3) 9=(1,3); Abaqus/CalculiX C3D10
# (0-based corners) 4=(0,1) 5=(1,2) 6=(2,0) 7=(0,3) 8=(1,3) 9=(2,3): the last two swap.
# hex20: gmsh's edges 8..19 are (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7) (4,5) (4,7)
# (5,6) (6,7); CalculiX orders them (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5)
# (2,6) (3,7).
ELEMENTS = {
    4: ("C3D4", [0, 1, 2, 3]),
    11: ("C3D10", [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
    17: ("C3D20", [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15]),
}
AXES = {"x": 1, "y": 2, "z": 3}
NO_SIZE_LIMIT = 1e22  # flexmbs' Mesh.MeshSizeMax without a mesh_size (fem/gmsh_import.cc)


def fail(message):
    print(f"ccx_modal.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_hold(text):
    """'set:xz' -> ('set', [1, 3])."""
    name, _, axes = text.partition(":")
    if not name or not axes or any(c not in AXES for c in axes):
        raise argparse.ArgumentTypeError(f"'{text}': give NODE_SET:COMPONENTS, components among x, y, z")
    return name, [AXES[c] for c in axes]


def load_mesh(path, supports, mesh_size=NO_SIZE_LIMIT, order=2):
    """Nodes (tag -> xyz) used by the volume elements, element blocks (gmsh type, tags,
    connectivity) and per support (name, components) its (name, node tags, components). A .msh
    is read as it is; other geometry is meshed as flexmbs meshes it."""
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        if not path.endswith(".msh"):
            gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size)
            gmsh.option.setNumber("Mesh.ElementOrder", order)
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
            gmsh.model.mesh.generate(3)
        types, element_tags, node_tags = gmsh.model.mesh.getElements(3)
        if len(types) == 0:
            fail(f"{path}: no volume (3-D) elements")
        blocks, used = [], set()
        for t, tags, nodes in zip(types, element_tags, node_tags):
            if t not in ELEMENTS:
                name = gmsh.model.mesh.getElementProperties(t)[0]
                fail(f"{path}: element type {name} (gmsh type {t}) is not supported (tet4, tet10, hex20)")
            n = len(nodes) // len(tags)
            blocks.append((int(t), [int(x) for x in tags],
                           [[int(x) for x in nodes[i * n:(i + 1) * n]] for i in range(len(tags))]))
            used.update(int(x) for x in nodes)
        tags, coords, _ = gmsh.model.mesh.getNodes(-1, -1, False, False)
        xyz = {int(tag): tuple(coords[3 * i:3 * i + 3]) for i, tag in enumerate(tags) if int(tag) in used}
        groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        held = []
        for name, components in supports:
            if name not in groups:
                fail(f"{path}: no physical group '{name}' (the file has: {', '.join(sorted(groups)) or 'none'})")
            group_tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(*groups[name])
            nodes = sorted({int(t) for t in group_tags} & used)
            if not nodes:
                fail(f"{path}: physical group '{name}' has no nodes on the solid mesh")
            held.append((name, nodes, components))
        return xyz, blocks, held
    finally:
        gmsh.finalize()


def read_mesh(path, clamp_group):
    """A .msh clamped on one physical group: nodes, element blocks, the clamped node tags."""
    xyz, blocks, held = load_mesh(path, [(clamp_group, [1, 2, 3])])
    return xyz, blocks, held[0][1]


def write_held_deck(f, xyz, blocks, held, E, nu, rho, modes):
    """The CalculiX deck: nodes, elements, each support's node set held in its components."""
    f.write("** written by flexmbs tests/peers/ccx_modal.py\n*NODE, NSET=NALL\n")
    for tag in sorted(xyz):
        f.write(f"{tag}, " + ", ".join(f"{c:.17g}" for c in xyz[tag]) + "\n")
    for t, tags, conn in blocks:
        ccx_type, perm = ELEMENTS[t]
        f.write(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL\n")
        for tag, nodes in zip(tags, conn):
            ordered = [str(nodes[k]) for k in perm]
            # At most 16 entries on a data line: continue on the next.
            f.write(f"{tag}, " + ", ".join(ordered[:15]) + (",\n" + ", ".join(ordered[15:]) if len(ordered) > 15 else "")
                    + "\n")
    for k, (_, tags, _) in enumerate(held):
        f.write(f"*NSET, NSET=NHELD{k}\n")
        for i in range(0, len(tags), 8):
            f.write(", ".join(map(str, tags[i:i + 8])) + ",\n")
    f.write("*BOUNDARY\n")
    for k, (_, _, components) in enumerate(held):
        for c in components:
            f.write(f"NHELD{k}, {c}, {c}\n")
    f.write(f"*MATERIAL, NAME=MAT\n*ELASTIC\n{E:.17g}, {nu:.17g}\n*DENSITY\n{rho:.17g}\n")
    f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n")
    f.write(f"*STEP\n*FREQUENCY\n{modes}\n*END STEP\n")


def write_deck(f, xyz, blocks, clamped, E, nu, rho, modes):
    """The deck of a mesh clamped (all three components) at the node tags `clamped`."""
    write_held_deck(f, xyz, blocks, [("clamp", clamped, [1, 2, 3])], E, nu, rho, modes)


def parse_frequencies(dat_text):
    """Frequencies (cycles/time) from the first 'E I G E N V A L U E   O U T P U T' table, None without one."""
    start = dat_text.find("E I G E N V A L U E   O U T P U T")
    if start < 0:
        return None
    freqs = []
    row = re.compile(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$")
    for line in dat_text[start:].splitlines()[1:]:
        m = row.match(line)
        if m:
            freqs.append(float(m.group(4)))
        elif freqs and line.strip():
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
    p.add_argument("mesh", help="gmsh .msh (read as it is), or .geo / .step (meshed as flexmbs does)")
    p.add_argument("--clamp", action="append", default=[], help="physical group whose nodes are fixed (all 3 directions)")
    p.add_argument("--hold", type=read_hold, action="append", default=[], help="NODE_SET:COMPONENTS, e.g. edges:z")
    p.add_argument("--mesh-size", type=float, default=NO_SIZE_LIMIT, help="Mesh.MeshSizeMax [m] (not for .msh)")
    p.add_argument("--order", type=int, choices=(1, 2), default=2, help="element order (not for .msh)")
    p.add_argument("--youngs-modulus", type=float, required=True, help="Pa")
    p.add_argument("--poisson-ratio", type=float, required=True)
    p.add_argument("--density", type=float, required=True, help="kg/m^3")
    p.add_argument("--modes", type=int, default=8, help="number of eigenfrequencies")
    p.add_argument("--ccx", default="ccx", help="CalculiX executable (default: ccx on PATH)")
    p.add_argument("--keep", help="write the deck and ccx output to this directory and keep it")
    a = p.parse_args()
    supports = [(name, [1, 2, 3]) for name in a.clamp] + a.hold
    if not supports:
        fail("give --clamp GROUP or --hold NODE_SET:COMPONENTS")
    ccx = shutil.which(a.ccx)
    if ccx is None:
        fail(f"CalculiX executable '{a.ccx}' not found (Debian: apt-get install calculix-ccx)")
    if not os.path.isfile(a.mesh):
        fail(f"{a.mesh}: no such file")
    start = time.perf_counter()
    xyz, blocks, held = load_mesh(a.mesh, supports, a.mesh_size, a.order)

    workdir = a.keep or tempfile.mkdtemp(prefix="ccx_modal_")
    os.makedirs(workdir, exist_ok=True)
    ok = False
    try:
        with open(os.path.join(workdir, "modal.inp"), "w") as f:
            write_held_deck(f, xyz, blocks, held, a.youngs_modulus, a.poisson_ratio, a.density, a.modes)
        env = dict(os.environ)
        env.setdefault("OMP_NUM_THREADS", "1")
        run = subprocess.run([ccx, "-i", "modal"], cwd=workdir, capture_output=True, text=True, env=env)
        dat_path = os.path.join(workdir, "modal.dat")
        freqs = parse_frequencies(open(dat_path).read() if os.path.exists(dat_path) else "")
        if run.returncode != 0 or not freqs or "*ERROR" in run.stdout:
            errors = [line for line in run.stdout.splitlines() if "ERROR" in line][:5]
            fail(f"ccx failed (exit {run.returncode}); deck and output kept in {workdir}: "
                 + (" | ".join(errors) or run.stdout[-500:]))
        if len(freqs) < a.modes:
            fail(f"ccx returned {len(freqs)} of {a.modes} requested eigenfrequencies (kept {workdir})")
        ok = True
    finally:
        if ok and not a.keep:
            shutil.rmtree(workdir, ignore_errors=True)

    clamped = {tag for name, tags, _ in held if name in a.clamp for tag in tags}
    print(json.dumps({
        "peer": "CalculiX",
        "ccx_version": ccx_version(ccx),
        "element": "+".join(sorted({ELEMENTS[t][0] for t, _, _ in blocks})),
        "nodes": len(xyz),
        "elements": sum(len(tags) for _, tags, _ in blocks),
        "clamped_nodes": len(clamped),
        "held_dofs": len({(tag, c) for _, tags, components in held for tag in tags for c in components}),
        "frequencies_hz": freqs[:a.modes],
        "seconds": time.perf_counter() - start,
    }, indent=2))


if __name__ == "__main__":
    main()
