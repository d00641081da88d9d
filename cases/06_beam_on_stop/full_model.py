#!/usr/bin/python3
"""The beam on the stop as a full FE model, integrated with SciPy and no flexmbs code.

The reference of cases/06_beam_on_stop: flexmbs' own K and M (`flexmbs mesh beam.yaml
--matrix-market PREFIX`: PREFIX_K.mtx, PREFIX_M.mtx, DOF 3 node + axis) and the mesh's pad
nodes (gmsh, meshed as flexmbs meshes it; node index = rank of the gmsh tag among the volume
elements' nodes), every pad node a contact on its y displacement against the stop y = 0 (gap 0
at rest), all nodes at v_y = -1 m/s at t = 0, stepped by the theta method of Moreau-Jean
(docs/contact.md; Acary & Brogliato 2008, §10.1):
  A = M + h^2 theta^2 K,  v_free = v_k - A^-1 h K (x_k + h theta v_k),
  v_k+1 = v_free + A^-1 H^T P,  x_k+1 = x_k + h (theta v_k+1 + (1 - theta) v_k),
with the contact impulses P of one formulation:
  velocity: theta = 1/2, points with g(x_k) + h/2 H v_k <= 0, 0 <= P _|_ H v_k+1 >= 0 (e = 0);
  position: theta = 1, points with g(x_k) + h H v_free <= 0, 0 <= P _|_ g(x_k) + h H v_k+1 >= 0;
  penalty: theta = 1/2, a spring k per pad node at x_k+theta: 0 <= P _|_ g(x_k+theta) + P / (h k) >= 0.
Each is an LCP in P, solved by Murty's principal pivoting (least-index rule; finite for the
P-matrices here). Writes the per-step impulse (summed over the pad) as .npy, and prints JSON
(the totals and the wall time of the run, reading and meshing included).

Usage: /usr/bin/python3 full_model.py PREFIX GEOMETRY FORMULATION OUT.npy
"""
import json
import sys
import time

import gmsh
import numpy as np
import scipy.io
import scipy.sparse.linalg as sla

LENGTH, CELLS = 0.6, 30           # beam length [m], cells along it (meshes/beam_stop.geo)
SPEED, STEP, END = 1.0, 1e-6, 1e-3  # [m/s] along -y, step and end time [s] (the scenes')
PENALTY = 1e7                     # [N/m] per pad node (scene_penalty.yaml)
THETA = {"velocity": 0.5, "position": 1.0, "penalty": 0.5}


def pad_nodes(geometry):
    """flexmbs' indices of the nodes on y = 0 in the last cell (x >= L - L / 30)."""
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(geometry)
        gmsh.option.setNumber("Mesh.MeshSizeMax", 1e22)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.generate(3)
        used = np.unique(np.concatenate([np.asarray(n) for n in gmsh.model.mesh.getElements(3)[2]]))
        tags, coords, _ = gmsh.model.mesh.getNodes()
        xyz = dict(zip(tags.astype(int), coords.reshape(-1, 3)))
        x = np.array([xyz[t] for t in used])
    finally:
        gmsh.finalize()
    return np.nonzero((np.abs(x[:, 1]) < 1e-9) & (x[:, 0] >= LENGTH - LENGTH / CELLS - 1e-9))[0], len(x)


def solve_lcp(W, q):
    """z >= 0, w = W z + q >= 0, z'w = 0 by Murty's least-index principal pivoting."""
    n = len(q)
    if n == 0:
        return np.zeros(0)
    held = np.zeros(n, bool)
    tolerance = 1e-12 * np.abs(q).max()
    for _ in range(100 * (n + 1)):
        z = np.zeros(n)
        if held.any():
            z[held] = np.linalg.solve(W[np.ix_(held, held)], -q[held])
        w = W @ z + q
        bad = np.nonzero((held & (z < 0.0)) | (~held & (w < -tolerance)))[0]
        if len(bad) == 0:
            return z
        held[bad[0]] = not held[bad[0]]
    raise RuntimeError("principal pivoting did not finish")


def integrate(K, M, pad, formulation):
    theta, h = THETA[formulation], STEP
    n = K.shape[0]
    H = np.zeros((len(pad), n))
    H[np.arange(len(pad)), 3 * pad + 1] = 1.0
    lu = sla.splu((M + (h * theta) ** 2 * K).tocsc())
    A_inv_Ht = lu.solve(H.T.copy())
    W_all = H @ A_inv_Ht
    x, v = np.zeros(n), np.zeros(n)
    v[1::3] = -SPEED
    impulses = []
    for _ in range(int(round(END / h))):
        v_free = v - lu.solve(h * (K @ (x + h * theta * v)))
        g, P = H @ x, np.zeros(len(pad))
        if formulation == "velocity":
            active = np.nonzero(g + 0.5 * h * (H @ v) <= 0.0)[0]
            P[active] = solve_lcp(W_all[np.ix_(active, active)], H[active] @ v_free)
        elif formulation == "position":
            active = np.nonzero(g + h * (H @ v_free) <= 0.0)[0]
            P[active] = solve_lcp(h * W_all[np.ix_(active, active)], g[active] + h * (H[active] @ v_free))
        else:
            q = g + h * theta * (1.0 - theta) * (H @ v) + h * theta * theta * (H @ v_free)
            P = solve_lcp(h * theta * theta * W_all + np.eye(len(pad)) / (h * PENALTY), q)
        v_next = v_free + A_inv_Ht @ P
        x = x + h * (theta * v_next + (1.0 - theta) * v)
        v = v_next
        impulses.append(P.sum())
    return np.array(impulses)


def main():
    prefix, geometry, formulation, out = sys.argv[1:5]
    start = time.perf_counter()
    K = scipy.io.mmread(prefix + "_K.mtx").tocsc()
    M = scipy.io.mmread(prefix + "_M.mtx").tocsc()
    pad, nodes = pad_nodes(geometry)
    if 3 * nodes != K.shape[0]:
        sys.exit(f"full_model.py: the mesh has {nodes} nodes, K {K.shape[0]} DOF")
    impulses = integrate(K, M, pad, formulation)
    np.save(out, impulses)
    print(json.dumps({"formulation": formulation, "dofs": K.shape[0], "pad_nodes": len(pad),
                      "impulse": impulses.sum(), "wall_seconds": time.perf_counter() - start}))


if __name__ == "__main__":
    main()
