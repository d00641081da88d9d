#!/usr/bin/python3
"""The FE-pair reference of the elastic-teeth model (issue 18; docs/contact.md, "Elastic teeth").

The z 20/40 steel pair of bench_gear_pair_fe (m 4 mm, b 40 mm, basic rack, a = a_0) as a
plane-strain slice (one layer of C3D20R, every node held in z) of both wheels' rims with the
teeth near the mesh, meshed by gmsh from flexmbs' own tooth outline (involute and rack-cut
fillet, contact/gears/tooth_profile.h, printed by bench_gear_pair_fe) and solved by CalculiX with
surface-to-surface penalty contact on the driving flanks: wheel 2's bore and cut faces clamped,
wheel 1's turned rigidly about its centre (prescribed displacements: a torque-loaded rigid hub
did not converge from the unloaded touching state), by the elastic-teeth estimate and then by
the secant to the turn whose reaction torque is T (two solves per roll angle). Each wheel is held
as the FE tooth of gear_tooth_fe is (bore 3.5 m below the root circle, radial cuts 1.5 pitches
beyond the outer teeth), so that the two models differ by what the pair adds: neighbouring teeth and the rim
between them, the contact itself (flattening, contact off the line of action), and the load
sharing the teeth find. At `--angles` wheel-1 angles over one mesh cycle, under T, the static
transmission error r_b1 * (wheel 1's turn) and each tooth pair's share of the load are compared
with flexmbs' elastic teeth (FE tables) and ISO 6336-1's c'; printed with the seconds per roll
angle of both.

  /usr/bin/python3 bench/gear_pair_calculix.py [--angles 8] [--only 0,2] [--contact-size 2e-4]
      [--size 1e-3] [--torque 400] [--keep DIR]   (needs build/bin/bench_gear_pair_fe, gmsh, ccx)
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

SLICE = 2e-4  # slab thickness [m]; plane strain makes it arbitrary (loads scale with it)
RIM_DEPTH = 3.5  # bore below the root circle / m (gear_tooth_fe's default)
CUT_PITCHES = 1.5  # cuts beyond the outer teeth' centre lines (gear_tooth_fe's segment)
PENALTY = 1e16  # contact pressure per overclosure [Pa/m]


def rotate(points, angle):
    c, s = math.cos(angle), math.sin(angle)
    p = np.asarray(points, dtype=float)
    return np.column_stack((c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]))


def tooth_outline(wheel):
    """One tooth's boundary in its tooth frame (centre line +y), counter-clockwise about the
    wheel's centre: the right flank (x > 0) up from the root circle, the tip, the left flank
    down. Returns (right, left) polylines, each from the root circle to the tip."""
    right = np.vstack((np.array(wheel["fillet"]), np.array(wheel["involute"])[1:]))
    left = right.copy()
    left[:, 0] *= -1.0
    return right, left


def wheel_geo(wheel, centre, phi, teeth, size, contact_points, contact_size):
    """A gmsh .geo of the wheel's sector with the given tooth indices (tooth k's centre line at
    phi + 2 pi k / z from the pair frame's x axis), its centre at `centre`."""
    z = wheel["teeth"]
    pitch = 2.0 * math.pi / z
    r_f = wheel["root_radius"]
    r_i = r_f - RIM_DEPTH * wheel["module"]
    right, left = tooth_outline(wheel)
    lines = ["SetFactory(\"Built-in\");"]
    count = {"p": 0, "c": 0}

    def point(p, lc=size):
        count["p"] += 1
        lines.append(f"Point({count['p']}) = {{{p[0] + centre[0]:.17g}, {p[1] + centre[1]:.17g}, 0, {lc:.17g}}};")
        return count["p"]

    def curve(kind, tags):
        count["c"] += 1
        lines.append(f"{kind}({count['c']}) = {{{', '.join(map(str, tags))}}};")
        return count["c"]

    centre_tag = point((0.0, 0.0))
    ks = sorted(teeth)
    start = phi + pitch * ks[0] - CUT_PITCHES * pitch
    end = phi + pitch * ks[-1] + CUT_PITCHES * pitch
    loop = []
    # Bore from `end` back to `start` is closed last; start at the bore's start.
    bore_start = point((r_i * math.cos(start), r_i * math.sin(start)))
    root_start = point((r_f * math.cos(start), r_f * math.sin(start)))
    loop.append(curve("Line", [bore_start, root_start]))
    last = root_start
    for k in ks:
        angle = phi + pitch * k - math.pi / 2.0  # tooth frame +y to the centre line
        r = rotate(right, angle)
        l = rotate(left, angle)
        # Counter-clockwise: the right flank (x > 0 in the tooth frame) comes first.
        first = point(r[0])
        loop.append(curve("Circle", [last, centre_tag, first]))
        tip_r = point(r[-1])
        loop.append(curve("Spline", [first] + [point(p) for p in r[1:-1]] + [tip_r]))
        tip_l = point(l[-1])
        loop.append(curve("Circle", [tip_r, centre_tag, tip_l]))
        foot = point(l[0])
        loop.append(curve("Spline", [tip_l] + [point(p) for p in l[-2:0:-1]] + [foot]))
        last = foot
    root_end = point((r_f * math.cos(end), r_f * math.sin(end)))
    loop.append(curve("Circle", [last, centre_tag, root_end]))
    bore_end = point((r_i * math.cos(end), r_i * math.sin(end)))
    loop.append(curve("Line", [root_end, bore_end]))
    # The bore back to its start (arcs under pi each).
    mid_angle = 0.5 * (start + end)
    bore_mid = point((r_i * math.cos(mid_angle), r_i * math.sin(mid_angle)))
    loop.append(curve("Circle", [bore_end, centre_tag, bore_mid]))
    loop.append(curve("Circle", [bore_mid, centre_tag, bore_start]))
    lines.append(f"Curve Loop(1) = {{{', '.join(map(str, loop))}}};")
    lines.append("Plane Surface(1) = {1};")
    field_points = [point(np.asarray(c) - centre, contact_size) for c in contact_points]
    lines += [
        "Field[1] = Distance;",
        f"Field[1].PointsList = {{{', '.join(map(str, field_points))}}};",
        "Field[2] = Threshold;",
        "Field[2].InField = 1;",
        f"Field[2].SizeMin = {contact_size:.17g};",
        f"Field[2].SizeMax = {size:.17g};",
        f"Field[2].DistMin = {8 * contact_size:.17g};",
        f"Field[2].DistMax = {max(3e-3, 10 * contact_size):.17g};",  # above DistMin
        "Background Field = 2;",
        "Mesh.MeshSizeFromPoints = 0;",
        "Mesh.MeshSizeExtendFromBoundary = 0;",
        "Mesh.MeshSizeFromCurvature = 0;",
        "Mesh.RecombineAll = 1;",
        "Mesh.Algorithm = 6;",
        "Mesh.SubdivisionAlgorithm = 1;",
        "Mesh.RecombinationAlgorithm = 1;",
        "Mesh.ElementOrder = 2;",
        "Mesh.SecondOrderIncomplete = 1;",
        "Mesh.MshFileVersion = 2.2;",
        "Physical Surface(1) = {1};",
    ]
    return "\n".join(lines) + "\n", r_i, start, end


def read_msh(path):
    """Nodes {tag: xy} and the 8-node quadrilaterals (gmsh's order: corners, then the mid-edge
    nodes of edges 01, 12, 23, 30, as CalculiX's) of a version 2.2 file."""
    nodes, quads = {}, []
    with open(path) as f:
        text = f.read().split("\n")
    i = 0
    while i < len(text):
        if text[i] == "$Nodes":
            n = int(text[i + 1])
            for line in text[i + 2:i + 2 + n]:
                v = line.split()
                nodes[int(v[0])] = np.array([float(v[1]), float(v[2])])
            i += n + 2
        elif text[i] == "$Elements":
            n = int(text[i + 1])
            for line in text[i + 2:i + 2 + n]:
                v = [int(x) for x in line.split()]
                if v[1] == 16:
                    quads.append(v[3 + v[2]:])
                elif v[1] not in (8, 15):  # 3-node lines and points of the boundary
                    raise RuntimeError(f"{path}: element type {v[1]} (only quad8 expected)")
            i += n + 2
        else:
            i += 1
    return nodes, quads


def slab(nodes, quads, first):
    """The one-layer slab of thickness SLICE over the quad8 mesh: C3D20R elements (CalculiX's
    order: bottom corners, top corners, bottom and top mid-edge nodes, vertical mid-edge nodes),
    counter-clockwise in the plane. Node numbers from `first`; returns ({number: xyz}, elements,
    the quads as corner lists in the same order)."""
    corners = sorted({q[i] for q in quads for i in range(4)})
    tags = sorted(nodes)
    bottom = {t: first + i for i, t in enumerate(tags)}
    top = {t: first + len(tags) + i for i, t in enumerate(tags)}
    middle = {t: first + 2 * len(tags) + i for i, t in enumerate(corners)}
    xyz = {}
    for t in tags:
        xyz[bottom[t]] = np.array([*nodes[t], 0.0])
        xyz[top[t]] = np.array([*nodes[t], SLICE])
    for t in corners:
        xyz[middle[t]] = np.array([*nodes[t], 0.5 * SLICE])
    elements, planar = [], []
    for q in quads:
        p = [nodes[q[i]] for i in range(4)]
        area = (p[2][0] - p[0][0]) * (p[3][1] - p[1][1]) - (p[2][1] - p[0][1]) * (p[3][0] - p[1][0])
        if area < 0:
            q = [q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4]]
        c, m = q[:4], q[4:]
        elements.append([bottom[t] for t in c] + [top[t] for t in c] + [bottom[t] for t in m] +
                        [top[t] for t in m] + [middle[t] for t in c])
        planar.append(c)
    return xyz, elements, planar


def boundary_faces(nodes, elements):
    """Lateral boundary faces of the slab's elements: (element index, face number 3..6, midpoint of
    the bottom edge)."""
    edges = {}
    for idx, e in enumerate(elements):
        for f, (a, b) in enumerate(((0, 1), (1, 2), (2, 3), (3, 0))):
            key = tuple(sorted((e[a], e[b])))
            edges.setdefault(key, []).append((idx, f + 3, (nodes[e[a]] + nodes[e[b]]) / 2.0))
    return [v[0] for v in edges.values() if len(v) == 1]


def classify(wheel, part, phi):
    """Hub nodes (bore and cut faces) and, per tooth, the faces of its driving flank (the positive
    one, counter-clockwise from the centre line; wheel 1 drives +z, positive flank on positive)
    above the root circle + m / 4 (the involute, the fillet's top and half the tip)."""
    pitch = 2.0 * math.pi / wheel["teeth"]
    tol = 1e-8
    hub = []
    for n, p in part["nodes"].items():
        d = p[:2] - part["centre"]
        r = math.hypot(*d)
        a = math.atan2(d[1], d[0])
        on_cut = any(abs(math.remainder(a - c, 2 * math.pi)) * r < tol for c in (part["start"], part["end"]))
        if r <= part["r_i"] + tol or on_cut:
            hub.append(n)
    flanks = {k: [] for k in part["teeth"]}
    r_min = wheel["root_radius"] + 0.25 * wheel["module"]
    for idx, face, mid in boundary_faces(part["nodes"], part["elements"]):
        d = mid[:2] - part["centre"]
        if math.hypot(*d) < r_min:
            continue
        a = math.atan2(d[1], d[0])
        for k in part["teeth"]:
            if 0.0 < math.remainder(a - (phi + pitch * k), 2 * math.pi) < 0.5 * pitch:
                flanks[k].append((idx, face))
    return hub, flanks


def sector_teeth(pairs, z):
    """The loaded teeth of one wheel and one neighbour on each side, as consecutive indices
    (tooth k + z is tooth k)."""
    ref = pairs[0]
    ks = {ref + (k + d - ref + z // 2) % z - z // 2 for k in pairs for d in (-1, 0, 1)}
    return sorted(ks)


def mesh_wheel(wheel, centre, phi, teeth, size, contact_points, contact_size, workdir, name, offset):
    geo, r_i, start, end = wheel_geo(wheel, centre, phi, teeth, size, contact_points, contact_size)
    geo_path = os.path.join(workdir, f"{name}.geo")
    msh_path = os.path.join(workdir, f"{name}.msh")
    with open(geo_path, "w") as f:
        f.write(geo)
    subprocess.run(["gmsh", geo_path, "-2", "-o", msh_path, "-v", "1"], check=True,
                   stdout=subprocess.DEVNULL)
    nodes, quads = read_msh(msh_path)
    xyz, elements, _ = slab(nodes, quads, offset + 1)
    return dict(nodes=xyz, elements=elements, r_i=r_i, start=start, end=end, centre=centre,
                teeth=teeth)


def write_inp(path, parts, hubs, flanks, data, turn):
    e_mod, nu = data["youngs_modulus"], data["poisson_ratio"]
    z1 = data["gear1"]["teeth"]
    out = ["*NODE"]
    for part in parts:
        for n, p in sorted(part["nodes"].items()):
            out.append(f"{n}, {p[0]:.13g}, {p[1]:.13g}, {p[2]:.13g}")  # CalculiX: <= 20 characters a field
    eid = 0
    elem_ids = []
    for w, part in enumerate(parts):
        out.append(f"*ELEMENT, TYPE=C3D20R, ELSET=WHEEL{w + 1}")
        ids = []
        for e in part["elements"]:
            eid += 1
            ids.append(eid)
            nodes = [str(n) for n in e]
            out.append(f"{eid}, " + ", ".join(nodes[:15]) + ",")
            out.append(", ".join(nodes[15:]))
        elem_ids.append(ids)
    for w in range(2):
        out.append(f"*NSET, NSET=HUB{w + 1}")
        out += [", ".join(map(str, hubs[w][i:i + 16])) for i in range(0, len(hubs[w]), 16)]
    every = sorted(parts[0]["nodes"]) + sorted(parts[1]["nodes"])
    out.append("*NSET, NSET=PLANE")
    out += [", ".join(map(str, every[i:i + 16])) for i in range(0, len(every), 16)]
    for k, faces in flanks[0].items():
        out.append(f"*SURFACE, NAME=S1T{k % z1}, TYPE=ELEMENT")
        out += [f"{elem_ids[0][idx]}, S{face}" for idx, face in faces]
    out.append("*SURFACE, NAME=M2, TYPE=ELEMENT")
    for k, faces in flanks[1].items():
        out += [f"{elem_ids[1][idx]}, S{face}" for idx, face in faces]
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{e_mod:.17g}, {nu:.17g}",
            "*SOLID SECTION, ELSET=WHEEL1, MATERIAL=STEEL",
            "*SOLID SECTION, ELSET=WHEEL2, MATERIAL=STEEL",
            "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{PENALTY:.13g}"]
    for k in flanks[0]:
        out += ["*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE", f"S1T{k % z1}, M2"]
    # Wheel 1's hub turned by `turn` about its centre (small rotation: u = turn (-y, x)).
    out += ["*BOUNDARY", "PLANE, 3, 3, 0", "HUB2, 1, 2, 0"]
    for n in hubs[0]:
        x, y = parts[0]["nodes"][n][:2]
        out += [f"{n}, 1, 1, {-turn * y:.13g}", f"{n}, 2, 2, {turn * x:.13g}"]
    out += ["*STEP, INC=200", "*STATIC", "0.25, 1.0, 1e-4, 0.25",
            "*NODE PRINT, NSET=HUB1", "RF"]
    for k in flanks[0]:
        out += [f"*CONTACT PRINT, SLAVE=S1T{k % z1}, MASTER=M2", "CF"]
    out += ["*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def read_dat(path, hub_nodes, slaves):
    """The reaction torque [N m] about wheel 1's centre on its hub and the contact force vector per
    contact pair (slave surface of wheel-1 tooth k) at the step's end."""
    text = open(path).read()
    block = text.split("forces (fx,fy,fz) for set HUB1")[-1].split("\n")[2:]
    torque = 0.0
    for line in block:
        v = line.split()
        if len(v) != 4:
            break
        n, fx, fy = int(v[0]), float(v[1]), float(v[2])
        x, y = hub_nodes[n][:2]
        torque += x * fy - y * fx
    forces = {}
    for k in slaves:
        found = re.findall(r"statistics for slave set S1T%d[ ,].*?\n(?:.*\n){0,3}?\s*([-+0-9.E]+)\s+([-+0-9.E]+)\s+([-+0-9.E]+)" % k, text)
        if found:
            forces[k] = np.array([float(v) for v in found[-1]])
    return torque, forces


def run_angle(data, sample, workdir, size, contact_size):
    wheels = (data["gear1"], data["gear2"])
    pairs = sample["fe_teeth"]["pairs"] + sample["iso"]["pairs"]
    contact_points = [np.array(p[5:7]) for p in pairs]
    centres = (np.zeros(2), np.array([data["centre_distance"], 0.0]))
    phis = (sample["phi1"], sample["phi2"])
    parts, hubs, flanks = [], [], []
    offset = 0
    for w in range(2):
        teeth = sector_teeth([p[w] for p in pairs], wheels[w]["teeth"])
        part = mesh_wheel(wheels[w], centres[w], phis[w], teeth, size, contact_points,
                          contact_size, workdir, f"wheel{w + 1}", offset)
        offset = max(part["nodes"])
        hub, flank = classify(wheels[w], part, phis[w])
        parts.append(part)
        hubs.append(hub)
        flanks.append(flank)
    torque_slice = data["torque"] * SLICE / data["face_width"]
    z1 = wheels[0]["teeth"]
    slaves = [k % z1 for k in flanks[0]]

    def solve(turn):
        write_inp(os.path.join(workdir, "pair.inp"), parts, hubs, flanks, data, turn)
        run = subprocess.run(["ccx", "-i", "pair"], cwd=workdir, capture_output=True, text=True,
                             env=dict(os.environ, OMP_NUM_THREADS="1"))
        if run.returncode != 0 or "*ERROR" in run.stdout:
            raise RuntimeError(f"ccx failed in {workdir}: " + run.stdout[-2000:])
        return read_dat(os.path.join(workdir, "pair.dat"), parts[0]["nodes"], slaves)

    start = time.perf_counter()
    # The turn of wheel 1 whose reaction torque is T: the elastic-teeth estimate, then the secant.
    turn1 = sample["fe_teeth"]["ste"] / wheels[0]["base_radius"]
    torque1, forces = solve(turn1)
    turn2 = turn1 * torque_slice / torque1
    torque2, forces = solve(turn2)
    rot = turn1 + (turn2 - turn1) * (torque_slice - torque1) / (torque2 - torque1)
    seconds = (time.perf_counter() - start) / 2.0
    forces = {k: f * torque_slice / torque2 for k, f in forces.items()}
    nodes = sum(len(p["nodes"]) for p in parts)
    return dict(rot=rot, forces=forces, seconds=seconds, nodes=nodes, teeth1=list(flanks[0]),
                torque_misfit=torque2 / torque_slice - 1.0)


def shares(pairs):
    """Each loaded wheel-1 tooth's share of the pairs' total normal force."""
    total = sum(p[4] for p in pairs)
    return {p[0]: p[4] / total for p in pairs if p[4] > 0}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--angles", type=int, default=8, help="wheel-1 angles over one mesh cycle")
    parser.add_argument("--torque", type=float, default=400.0, help="T on wheel 1 [N m]")
    parser.add_argument("--size", type=float, default=1e-3, help="element edge away from contact [m]")
    parser.add_argument("--contact-size", type=float, default=2e-4, help="element edge at the contacts [m]")
    parser.add_argument("--only", type=str, default="", help="comma-separated sample indices to run")
    parser.add_argument("--keep", type=str, default="", help="keep the CalculiX models in this folder")
    parser.add_argument("--flexmbs", type=str, default=os.path.join(HERE, "..", "build", "bin"),
                        help="the folder of bench_gear_pair_fe")
    args = parser.parse_args()
    exe = os.path.join(args.flexmbs, "bench_gear_pair_fe")
    data = json.loads(subprocess.run([exe, str(args.angles), str(args.torque)], check=True,
                                     capture_output=True, text=True).stdout)
    r_b1 = data["gear1"]["base_radius"]
    print(f"z 20/40, m 4 mm, b 40 mm, T = {args.torque:g} N m on wheel 1; epsilon_alpha "
          f"{data['contact_ratio']:.4f}; CalculiX plane-strain slice, C3D20R, edge {args.size:g} m, "
          f"{args.contact_size:g} m at the contacts; penalty {PENALTY:g} Pa/m")
    print(f"{'phi1/pitch':>10} {'nodes':>7} {'ccx s':>7} {'STE ccx um':>10} {'FE teeth':>9} "
          f"{'ISO c_th':>9} {'ISO c':>9} {'err FE':>8} {'err ISOth':>9} {'share ccx':>10} "
          f"{'share FE':>9} {'share ISO':>9} {'T2/T-1':>8} {'coupled':>9} {'err cpl':>8} "
          f"{'share cpl':>10}")
    root = args.keep or tempfile.mkdtemp(prefix="flexmbs_gear_pair_")
    rows = []
    only = {int(i) for i in args.only.split(",")} if args.only else None
    for i, sample in enumerate(data["samples"]):
        if only is not None and i not in only:
            continue
        sample = dict(sample, centre_distance=data["centre_distance"])
        workdir = os.path.join(root, f"angle{i}")
        os.makedirs(workdir, exist_ok=True)
        ccx = run_angle(data, sample, workdir, args.size, args.contact_size)
        ste = r_b1 * ccx["rot"]
        fe, iso, iso_th = (sample[k]["ste"] for k in ("fe_teeth", "iso", "iso_theoretical"))
        magnitude = {k: float(np.linalg.norm(f)) for k, f in ccx["forces"].items()}
        total = sum(magnitude.values())
        z1 = data["gear1"]["teeth"]
        share_ccx = {k % z1: m / total for k, m in magnitude.items() if m > 1e-6 * total}
        share_fe = shares(sample["fe_teeth"]["pairs"])
        share_iso = shares(sample["iso"]["pairs"])
        # The teeth coupled through their rims (three-tooth segments, bench_gear_pair_fe): the
        # same pairs as the FE teeth', in their order.
        coupled = sample["coupled"]["ste"]
        share_cpl = {int(k): v for k, v in sample["coupled"]["shares"]}
        row = dict(phi=sample["phi1"] / (2 * math.pi / z1), nodes=ccx["nodes"], seconds=ccx["seconds"],
                   ste=ste, fe=fe, iso=iso, iso_th=iso_th, share_ccx=share_ccx, share_fe=share_fe,
                   share_iso=share_iso, misfit=ccx["torque_misfit"], coupled=coupled,
                   share_cpl=share_cpl)
        rows.append(row)
        fmt_share = lambda s: "/".join(f"{s.get(k, 0.0):.3f}" for k in sorted(set(share_fe) | set(share_ccx)))
        print(f"{row['phi']:>10.3f} {row['nodes']:>7d} {row['seconds']:>7.1f} {ste * 1e6:>10.4f} "
              f"{fe * 1e6:>9.4f} {iso_th * 1e6:>9.4f} {iso * 1e6:>9.4f} {fe / ste - 1:>+8.4f} "
              f"{iso_th / ste - 1:>+9.4f} {fmt_share(share_ccx):>10} {fmt_share(share_fe):>9} "
              f"{fmt_share(share_iso):>9} {row['misfit']:>+8.1e} {coupled * 1e6:>9.4f} "
              f"{coupled / ste - 1:>+8.4f} {fmt_share(share_cpl):>10}", flush=True)
    if not rows:
        return 0
    ste_err = max(abs(r["fe"] / r["ste"] - 1) for r in rows)
    iso_err = max(abs(r["iso_th"] / r["ste"] - 1) for r in rows)
    share_err = max(abs(r["share_fe"].get(k, 0.0) - r["share_ccx"].get(k, 0.0))
                    for r in rows for k in set(r["share_fe"]) | set(r["share_ccx"]))
    share_iso_err = max(abs(r["share_iso"].get(k, 0.0) - r["share_ccx"].get(k, 0.0))
                        for r in rows for k in set(r["share_iso"]) | set(r["share_ccx"]))
    cpl_err = max(abs(r["coupled"] / r["ste"] - 1) for r in rows)
    share_cpl_err = max(abs(r["share_cpl"].get(k, 0.0) - r["share_ccx"].get(k, 0.0))
                        for r in rows for k in set(r["share_cpl"]) | set(r["share_ccx"]))
    ccx_seconds = sum(r["seconds"] for r in rows) / len(rows)
    print(f"largest STE error: FE teeth {ste_err:.3g}, coupled teeth {cpl_err:.3g}, ISO c'_th "
          f"{iso_err:.3g}; largest load-share error: FE teeth {share_err:.3g}, coupled "
          f"{share_cpl_err:.3g}, ISO {share_iso_err:.3g}")
    print(f"time per CalculiX solve (two per roll angle: the turn for T by a secant): {ccx_seconds:.3g} s; "
          f"flexmbs static transmission error "
          f"{data['ste_seconds']:.3g} s ({ccx_seconds / data['ste_seconds']:.3g}x), one mesh "
          f"evaluation {data['mesh_seconds']:.3g} s ({ccx_seconds / data['mesh_seconds']:.3g}x); "
          f"flexmbs' FE tables once {data['fe_table_seconds']:.3g} s")
    print("headline " + json.dumps(dict(ste_error_fe=ste_err, ste_error_coupled=cpl_err,
                                        ste_error_iso_th=iso_err,
                                        share_error_fe=share_err, share_error_iso=share_iso_err,
                                        ccx_seconds_per_angle=ccx_seconds,
                                        flexmbs_seconds_per_angle=data["ste_seconds"])))
    if not args.keep:
        shutil.rmtree(root, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
