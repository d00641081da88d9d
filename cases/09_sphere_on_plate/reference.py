#!/usr/bin/python3
"""The sphere pressed into the clamped plate as the full FE model's static contact, in SciPy.

The reference of cases/09_sphere_on_plate, with no flexmbs code: flexmbs' stiffness matrix K
(`flexmbs mesh plate.yaml --matrix-market PREFIX`: PREFIX_K.mtx, DOF 3 node + axis) and the
mesh's node positions and contact-patch nodes (the reduced body file's `mesh/` group, which is
the FE mesh), the side faces' nodes held. The contact is the elastic foundation of
docs/contact.md (pressure p = c delta, c = 1 / (h_a/E_a + h_b/E_b)) between the exact sphere
(not its facets) and the plate's deformed top face, bilinear on each hex8 face:
  delta(x, y) = t + w(x, y) - (z_c - sqrt(R^2 - r^2)),   r the distance from the sphere's axis,
integrated on each patch cell by the midpoint rule on SAMPLES^2 sub-cells, consistent nodal
z loads f_i = -sum c max(0, delta) N_i dA. The plate's response to loads on the patch nodes is
their compliance block G = [K^-1]_SS (49 sparse solves); w_S = G f(w_S) is solved by Newton
(Jacobian I - G df/dw, df_i/dw_j = -sum c [delta > 0] N_i N_j dA) to 1e-13 m. Depth along z,
not the deformed normal: the slope under the contact is below 1e-2 (cos 1 - 5e-5).

Prints JSON: the contact force [N], the plate's deflection under the sphere's centre (bottom
face) [m], the layer's deepest compression [m], the Newton steps, the wall time.

Usage: /usr/bin/python3 reference.py PREFIX PLATE.sid.h5 [SAMPLES]
"""
import json
import sys
import time

import h5py
import numpy as np
import scipy.io
import scipy.sparse.linalg as sla

SIDE, THICKNESS = 0.2, 0.003               # plate [m] (plate.geo)
RADIUS = 0.05                              # sphere [m]
CENTRE = np.array([0.1013, 0.1007, 0.05225])  # sphere centre in W = the plate's frame (scene.yaml)
C = 1.0 / (2 * 2e-3 / 5e7)                 # both layers E = 5e7 Pa, h = 2 mm [N/m^3]


def main():
    start = time.perf_counter()
    prefix, body = sys.argv[1], sys.argv[2]
    samples = int(sys.argv[3]) if len(sys.argv) > 3 else 64
    K = scipy.io.mmread(prefix + "_K.mtx").tocsc()
    with h5py.File(body, "r") as f:
        nodes = f["mesh/node_positions"][:]
        patch = np.sort(f["mesh/node_sets/patch"][:].astype(int))
    x, y = nodes[:, 0], nodes[:, 1]
    held = (np.abs(x) < 1e-9) | (np.abs(x - SIDE) < 1e-9) | (np.abs(y) < 1e-9) | (np.abs(y - SIDE) < 1e-9)
    free = np.flatnonzero(np.repeat(~held, 3))
    position = -np.ones(3 * len(nodes), int)
    position[free] = np.arange(len(free))

    top = patch[np.abs(nodes[patch, 2] - THICKNESS) < 1e-9]
    xs, ys = np.unique(np.round(nodes[top, 0], 9)), np.unique(np.round(nodes[top, 1], 9))
    grid = {(round(nodes[n, 0], 9), round(nodes[n, 1], 9)): i for i, n in enumerate(top)}
    corners = [[grid[(xs[i], ys[j])], grid[(xs[i + 1], ys[j])], grid[(xs[i + 1], ys[j + 1])], grid[(xs[i], ys[j + 1])]]
               for i in range(len(xs) - 1) for j in range(len(ys) - 1)]
    # Per cell the sample points and their bilinear weights on the cell's four corners.
    s = (np.arange(samples) + 0.5) / samples
    xi, eta = np.meshgrid(s, s, indexing="ij")
    xi, eta = xi.ravel(), eta.ravel()
    shape = np.stack([(1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta], axis=1)
    rows = []
    for cell in corners:
        p = nodes[top[cell]]
        px = p[0, 0] + xi * (p[1, 0] - p[0, 0])
        py = p[0, 1] + eta * (p[3, 1] - p[0, 1])
        area = (p[1, 0] - p[0, 0]) * (p[3, 1] - p[0, 1]) / samples ** 2
        r2 = (px - CENTRE[0]) ** 2 + (py - CENTRE[1]) ** 2
        lowest = CENTRE[2] - np.sqrt(np.maximum(RADIUS ** 2 - r2, 0.0))
        rows.append((np.array(cell), THICKNESS - lowest, area))
    # The compliance of the top patch nodes in z, and of the node under the centre on the bottom.
    bottom = np.argmin(np.linalg.norm(nodes - [CENTRE[0], CENTRE[1], 0.0], axis=1))
    lu = sla.splu(K[free][:, free])
    unit = np.zeros((len(free), len(top)))
    unit[position[3 * top + 2], np.arange(len(top))] = 1.0
    X = lu.solve(unit)
    G = X[position[3 * top + 2]]
    g_bottom = X[position[3 * bottom + 2]]

    def loads(w):
        f, df = np.zeros(len(top)), np.zeros((len(top), len(top)))
        for cell, depth0, area in rows:
            delta = depth0 + shape @ w[cell]
            on = delta > 0
            f[cell] -= C * area * (shape[on].T @ delta[on])
            df[np.ix_(cell, cell)] -= C * area * (shape[on].T @ shape[on])
        return f, df

    w = np.zeros(len(top))
    for step in range(1, 51):
        f, df = loads(w)
        dw = np.linalg.solve(np.eye(len(top)) - G @ df, G @ f - w)
        w += dw
        if np.max(np.abs(dw)) < 1e-13:
            break
    f, _ = loads(w)
    deepest = max(np.max(d0 + shape @ w[c]) for c, d0, _ in rows)
    print(json.dumps({"force_n": -f.sum(), "deflection_m": float(g_bottom @ f), "layer_depth_m": float(deepest),
                      "newton_steps": step, "samples": samples, "wall_seconds": time.perf_counter() - start}))


if __name__ == "__main__":
    main()
