#!/usr/bin/python3
"""Lowest natural frequencies from flexmbs' own K and M (Matrix Market), by SciPy.

Reads the matrices written by `flexmbs mesh BODY.yaml --matrix-market PREFIX`
(PREFIX_K.mtx, PREFIX_M.mtx; symmetric, lower triangle; DOF = 3*node + axis), removes the
DOFs of the clamped nodes, solves K x = lambda M x for the lowest eigenpairs with
scipy.sparse.linalg.eigsh in shift-invert mode, and prints JSON on stdout:

  {"solver": "scipy.sparse.linalg.eigsh", "dofs": ..., "free_dofs": ...,
   "frequencies_hz": [...], "max_relative_residual": ..., "max_m_orthonormality_error": ...}

The clamped nodes are either named by a physical group of the .msh the body was meshed
from (--mesh M.msh --clamp GROUP), using flexmbs' node numbering (node index = rank of the
gmsh node tag among the tags used by volume elements), or given directly as 0-based node
indices in flexmbs' numbering (--clamp-nodes 0,5,7 or --clamp-nodes-file FILE).

Usage:
  /usr/bin/python3 scipy_modal.py PREFIX --mesh beam.msh --clamp clamp --modes 8

Needs python3-scipy (and python3-gmsh for --mesh); Debian's are seen by /usr/bin/python3.
"""
import argparse
import json
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sla


def fail(message):
    print(f"scipy_modal.py: {message}", file=sys.stderr)
    sys.exit(1)


def flexmbs_node_indices(msh_path, group):
    """0-based flexmbs node indices of the nodes of physical group `group` in `msh_path`.

    flexmbs numbers the nodes used by volume elements (of the physical volumes, or of all
    volumes when there is none) in increasing gmsh node tag order.
    """
    import gmsh
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(msh_path)
        volume_groups = gmsh.model.getPhysicalGroups(3)
        if volume_groups:
            entities = sorted({e for d, t in volume_groups for e in gmsh.model.getEntitiesForPhysicalGroup(d, t)})
        else:
            entities = [t for _, t in gmsh.model.getEntities(3)]
        used = []
        for entity in entities:
            _, _, node_tags = gmsh.model.mesh.getElements(3, entity)
            used.extend(np.asarray(nt, dtype=np.int64) for nt in node_tags)
        if not used:
            fail(f"{msh_path}: no volume (3-D) elements")
        used_tags = np.unique(np.concatenate(used))  # sorted: position = flexmbs node index
        groups = {gmsh.model.getPhysicalName(d, t): (d, t) for d, t in gmsh.model.getPhysicalGroups()}
        if group not in groups:
            fail(f"{msh_path}: no physical group '{group}' (the file has: {', '.join(sorted(groups)) or 'none'})")
        group_tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(*groups[group])
        group_tags = np.unique(np.asarray(group_tags, dtype=np.int64))
        group_tags = group_tags[np.isin(group_tags, used_tags)]
        if group_tags.size == 0:
            fail(f"{msh_path}: physical group '{group}' has no nodes on the solid mesh")
        return np.searchsorted(used_tags, group_tags), used_tags.size
    finally:
        gmsh.finalize()


def read_symmetric(path):
    A = scipy.io.mmread(path)  # a 'symmetric' file comes back with both triangles
    return sp.csc_matrix(A)


def lowest_modes(K, M, fixed_dofs, modes, sigma=0.0):
    """Lowest eigenpairs of K x = lambda M x on the free DOFs; returns (lambda, X_free, free)."""
    n = K.shape[0]
    free = np.setdiff1d(np.arange(n), fixed_dofs)
    Kf = K[free][:, free].tocsc()
    Mf = M[free][:, free].tocsc()
    lam, X = sla.eigsh(Kf, k=modes, M=Mf, sigma=sigma, which="LM")
    order = np.argsort(lam)
    return lam[order], X[:, order], free, Kf, Mf


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("prefix", help="Matrix Market prefix: reads PREFIX_K.mtx and PREFIX_M.mtx")
    p.add_argument("--mesh", help=".msh file the body was meshed from (with --clamp)")
    p.add_argument("--clamp", help="physical group of --mesh whose nodes are fixed")
    p.add_argument("--clamp-nodes", help="comma-separated 0-based flexmbs node indices to fix")
    p.add_argument("--clamp-nodes-file", help="file of 0-based flexmbs node indices to fix")
    p.add_argument("--modes", type=int, default=8)
    p.add_argument("--sigma", type=float, default=0.0,
                   help="shift (rad^2/s^2); keep below the lowest eigenvalue (a free body needs < 0)")
    a = p.parse_args()

    start = time.perf_counter()
    K = read_symmetric(a.prefix + "_K.mtx")
    M = read_symmetric(a.prefix + "_M.mtx")
    if K.shape != M.shape or K.shape[0] != K.shape[1] or K.shape[0] % 3:
        fail(f"K {K.shape} and M {M.shape} must be square, equal and of size 3 * nodes")
    nodes = K.shape[0] // 3

    if a.mesh and a.clamp:
        clamped, mesh_nodes = flexmbs_node_indices(a.mesh, a.clamp)
        if mesh_nodes != nodes:
            fail(f"{a.mesh} has {mesh_nodes} nodes on volume elements but the matrices have {nodes}")
    elif a.clamp_nodes is not None:
        clamped = np.array([int(s) for s in a.clamp_nodes.split(",") if s.strip()], dtype=np.int64)
    elif a.clamp_nodes_file:
        clamped = np.loadtxt(a.clamp_nodes_file, dtype=np.int64, ndmin=1)
    else:
        clamped = np.array([], dtype=np.int64)
    if clamped.size and (clamped.min() < 0 or clamped.max() >= nodes):
        fail(f"clamped node index out of range 0..{nodes - 1}")
    fixed = np.unique((3 * clamped[:, None] + np.arange(3)[None, :]).ravel())

    lam, X, free, Kf, Mf = lowest_modes(K, M, fixed, a.modes, a.sigma)
    # Checks: relative residual ||K x - lam M x|| / ||K x|| and M-orthonormality.
    KX = Kf @ X
    MX = Mf @ X
    residual = np.linalg.norm(KX - MX * lam, axis=0) / np.maximum(np.linalg.norm(KX, axis=0), 1e-300)
    G = X.T @ MX
    scale = np.sqrt(np.diag(G))
    ortho = np.abs(G / np.outer(scale, scale) - np.eye(len(lam))).max()

    result = {
        "solver": "scipy.sparse.linalg.eigsh (shift-invert, sigma=%g)" % a.sigma,
        "dofs": int(K.shape[0]),
        "free_dofs": int(free.size),
        "clamped_nodes": int(clamped.size),
        "eigenvalues_rad2_s2": lam.tolist(),
        "frequencies_hz": (np.sqrt(np.maximum(lam, 0.0)) / (2 * np.pi)).tolist(),
        "max_relative_residual": float(residual.max()),
        "max_m_orthonormality_error": float(ortho),
        "seconds": time.perf_counter() - start,
    }
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
