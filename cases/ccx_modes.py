#!/usr/bin/python3
"""The natural frequencies of a body held by supports by component, computed by CalculiX (ccx).

The peer of cases 05_nafems_fv52 and 07_bracket_modes: meshes a geometry with gmsh exactly as
flexmbs does (Mesh.MeshSizeMax, Mesh.ElementOrder, Mesh.SecondOrderIncomplete = 1), writes a
CalculiX deck (C3D20, one linear isotropic material, each --hold node set's nodes held in its
components by *BOUNDARY, *FREQUENCY), runs ccx and prints JSON:

  {"peer": "CalculiX", "element": "C3D20", "nodes": ..., "elements": ...,
   "held_dofs": ..., "frequencies_hz": [...], "seconds": ...}

Usage: /usr/bin/python3 ccx_modes.py GEOMETRY --order 2 --youngs-modulus 2e11 --poisson-ratio 0.3
           --density 8000 --modes 6 --hold bottom_edges:z --hold mid_x:x [--keep DIR] [--ccx ccx]
(a case's run.sh passes what its body files say.) Needs python3-gmsh and calculix-ccx (Debian).

CalculiX integrates C3D20 stiffness and mass with 3 x 3 x 3 Gauss points, as flexmbs does
for hex20 (docs/elements.md), so on an undistorted structured mesh both matrices are the same
up to round-off.
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

# gmsh element type -> (CalculiX type, ccx node k = gmsh node perm[k]); the case's hex20 only
# (tests/peers/ccx_modal.py drives tet4 and tet10).
# hex20: gmsh's edges 8..19 are (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7) (4,5) (4,7)
# (5,6) (6,7); CalculiX (Abaqus) orders them (0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4)
# (0,4) (1,5) (2,6) (3,7).
ELEMENTS = {
    17: ("C3D20", [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15]),
}
AXES = {"x": 1, "y": 2, "z": 3}
NO_SIZE_LIMIT = 1e22  # flexmbs' Mesh.MeshSizeMax without a mesh_size (fem/gmsh_import.cc)


def fail(message):
    print(f"ccx_modes.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_hold(text):
    """'set:xz' -> ('set', [1, 3])."""
    name, _, axes = text.partition(":")
    if not name or not axes or any(c not in AXES for c in axes):
        raise argparse.ArgumentTypeError(f"'{text}': give NODE_SET:COMPONENTS, components among x, y, z")
    return name, [AXES[c] for c in axes]


def mesh(body):
    """Nodes (tag -> xyz) of the volume elements, element blocks, and each support's node tags."""
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(body["geometry"])
        gmsh.option.setNumber("Mesh.MeshSizeMax", body["mesh_size"])
        gmsh.option.setNumber("Mesh.ElementOrder", body["order"])
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.generate(3)
        blocks, used = [], set()
        for t, tags, nodes in zip(*gmsh.model.mesh.getElements(3)):
            if t not in ELEMENTS:
                fail(f"gmsh element type {t} is not supported")
            n = len(nodes) // len(tags)
            blocks.append((t, [int(x) for x in tags], [[int(x) for x in nodes[i * n:(i + 1) * n]] for i in range(len(tags))]))
            used.update(int(x) for x in nodes)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        xyz = {int(tag): coords[3 * i:3 * i + 3] for i, tag in enumerate(tags) if int(tag) in used}
        groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        held = []
        for name, components in body["supports"]:
            if name not in groups:
                fail(f"no physical group '{name}'")
            group_tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(*groups[name])
            held.append((name, sorted({int(t) for t in group_tags} & used), components))
        return xyz, blocks, held
    finally:
        gmsh.finalize()


def write_deck(f, xyz, blocks, held, material, modes):
    f.write("** written by flexmbs cases/ccx_modes.py\n*NODE, NSET=NALL\n")
    for tag in sorted(xyz):
        f.write(f"{tag}, " + ", ".join(f"{c:.17g}" for c in xyz[tag]) + "\n")
    for t, tags, conn in blocks:
        ccx_type, perm = ELEMENTS[t]
        f.write(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL\n")
        for tag, nodes in zip(tags, conn):
            ordered = [str(nodes[k]) for k in perm]
            # At most 16 entries on a data line: continue on the next.
            f.write(f"{tag}, " + ", ".join(ordered[:15]) + (",\n" + ", ".join(ordered[15:]) if len(ordered) > 15 else "") + "\n")
    for name, tags, _ in held:
        f.write(f"*NSET, NSET={name.upper()}\n")
        for i in range(0, len(tags), 8):
            f.write(", ".join(map(str, tags[i:i + 8])) + ",\n")
    f.write("*BOUNDARY\n")
    for name, _, components in held:
        for c in components:
            f.write(f"{name.upper()}, {c}, {c}\n")
    f.write(f"*MATERIAL, NAME=MAT\n*ELASTIC\n{material['youngs_modulus']:.17g}, {material['poisson_ratio']:.17g}\n")
    f.write(f"*DENSITY\n{material['density']:.17g}\n*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n")
    f.write(f"*STEP\n*FREQUENCY\n{modes}\n*END STEP\n")


def parse_frequencies(dat_text):
    """Frequencies [cycles/time] of the first 'E I G E N V A L U E   O U T P U T' table."""
    start = dat_text.find("E I G E N V A L U E   O U T P U T")
    if start < 0:
        return []
    row = re.compile(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$")
    freqs = []
    for line in dat_text[start:].splitlines()[1:]:
        m = row.match(line)
        if m:
            freqs.append(float(m.group(4)))
        elif freqs and line.strip():
            break
    return freqs


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("geometry", help=".geo, .step or .msh file")
    p.add_argument("--mesh-size", type=float, default=NO_SIZE_LIMIT, help="Mesh.MeshSizeMax [m]")
    p.add_argument("--order", type=int, choices=(1, 2), default=2)
    p.add_argument("--youngs-modulus", type=float, required=True, help="Pa")
    p.add_argument("--poisson-ratio", type=float, required=True)
    p.add_argument("--density", type=float, required=True, help="kg/m^3")
    p.add_argument("--modes", type=int, required=True)
    p.add_argument("--hold", type=read_hold, action="append", required=True, help="NODE_SET:COMPONENTS, e.g. edges:z")
    p.add_argument("--ccx", default="ccx", help="CalculiX executable (default: ccx on PATH)")
    p.add_argument("--keep", help="write the deck and ccx's output to this directory and keep it")
    a = p.parse_args()
    ccx = shutil.which(a.ccx)
    if ccx is None:
        fail(f"CalculiX executable '{a.ccx}' not found (Debian: apt-get install calculix-ccx)")
    start = time.perf_counter()
    body = {"geometry": a.geometry, "mesh_size": a.mesh_size, "order": a.order, "supports": a.hold, "modes": a.modes,
            "material": {"youngs_modulus": a.youngs_modulus, "poisson_ratio": a.poisson_ratio, "density": a.density}}
    xyz, blocks, held = mesh(body)
    workdir = a.keep or tempfile.mkdtemp(prefix="ccx_modes_")
    os.makedirs(workdir, exist_ok=True)
    with open(os.path.join(workdir, "modal.inp"), "w") as f:
        write_deck(f, xyz, blocks, held, body["material"], body["modes"])
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = subprocess.run([ccx, "-i", "modal"], cwd=workdir, capture_output=True, text=True, env=env)
    dat_path = os.path.join(workdir, "modal.dat")
    freqs = parse_frequencies(open(dat_path).read() if os.path.exists(dat_path) else "")
    if run.returncode != 0 or len(freqs) < body["modes"] or "*ERROR" in run.stdout:
        errors = [line for line in run.stdout.splitlines() if "ERROR" in line][:5]
        fail(f"ccx failed (exit {run.returncode}, {len(freqs)} frequencies); deck kept in {workdir}: "
             + (" | ".join(errors) or run.stdout[-500:]))
    if not a.keep:
        shutil.rmtree(workdir, ignore_errors=True)
    held_dofs = len({(tag, c) for _, tags, components in held for tag in tags for c in components})
    print(json.dumps({
        "peer": "CalculiX",
        "element": "+".join(sorted({ELEMENTS[t][0] for t, _, _ in blocks})),
        "nodes": len(xyz),
        "elements": sum(len(tags) for _, tags, _ in blocks),
        "held_dofs": held_dofs,
        "frequencies_hz": freqs[:body["modes"]],
        "seconds": time.perf_counter() - start,
    }, indent=2))


if __name__ == "__main__":
    main()
