#!/usr/bin/python3
"""Peer worker for bench/assembly_bench.py: FEniCS (DOLFINx 0.5) assembles the linear
elasticity stiffness and the consistent mass matrix of a tet10 gmsh mesh, and prints timings
as JSON. Run it in its own process so that its peak memory can be measured
(/usr/bin/time -v).

The forms are those flexmbs assembles: P2 vector Lagrange on the mesh's own P2 (tet10)
geometry,
  K: int 2 mu eps(u):eps(v) + lambda div u div v dx   (quadrature degree --stiffness-degree)
  M: int rho u.v dx                                    (quadrature degree --mass-degree)
Timed, as flexmbs' `seconds.assembly` is: building the sparsity pattern once (create_matrix
for K; M duplicates K's structure, as flexmbs copies its pattern) and assembling both
matrices (PETSc AIJ, serial). Not timed: reading the mesh and JIT-compiling the forms.

Usage:
  /usr/bin/python3 dolfinx_assemble.py MESH.msh [--youngs-modulus 2.1e11] [--poisson-ratio 0.3]
      [--density 7850] [--stiffness-degree 3] [--mass-degree 4] [--repeat 1]

Note: dolfinx.io.gmshio.read_from_msh is broken in DOLFINx 0.5.2 (NameError 'msh'); the mesh
is read with gmsh.open and converted with gmshio.model_to_mesh instead.
"""
import argparse
import json
import time


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("mesh")
    p.add_argument("--youngs-modulus", type=float, default=2.1e11)
    p.add_argument("--poisson-ratio", type=float, default=0.3)
    p.add_argument("--density", type=float, default=7850.0)
    p.add_argument("--stiffness-degree", type=int, default=3)
    p.add_argument("--mass-degree", type=int, default=4)
    p.add_argument("--repeat", type=int, default=1, help="assemble this many times; report the fastest")
    a = p.parse_args()

    start = time.perf_counter()
    import gmsh
    from mpi4py import MPI
    import basix
    import dolfinx
    import dolfinx.fem.petsc
    import dolfinx.io.gmshio
    import ufl
    seconds = {"import": time.perf_counter() - start}

    t = time.perf_counter()
    gmsh.initialize([], False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(a.mesh)
    mesh, _, _ = dolfinx.io.gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=3)
    gmsh.finalize()
    seconds["read_mesh"] = time.perf_counter() - t

    t = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 2))
    E, nu, rho = a.youngs_modulus, a.poisson_ratio, a.density
    mu = E / (2 * (1 + nu))
    lmbda = E * nu / ((1 + nu) * (1 - 2 * nu))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    eps = lambda w: ufl.sym(ufl.grad(w))
    dx_k = ufl.dx(metadata={"quadrature_degree": a.stiffness_degree})
    dx_m = ufl.dx(metadata={"quadrature_degree": a.mass_degree})
    a_K = dolfinx.fem.form((2 * mu * ufl.inner(eps(u), eps(v)) + lmbda * ufl.div(u) * ufl.div(v)) * dx_k)
    a_M = dolfinx.fem.form(rho * ufl.inner(u, v) * dx_m)
    seconds["function_space_and_jit"] = time.perf_counter() - t

    best = None
    for _ in range(max(1, a.repeat)):
        t0 = time.perf_counter()
        K = dolfinx.fem.petsc.create_matrix(a_K)
        M = K.duplicate()  # same structure (MAT_DO_NOT_COPY_VALUES)
        t1 = time.perf_counter()
        K.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(K, a_K)
        K.assemble()
        t2 = time.perf_counter()
        M.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(M, a_M)
        M.assemble()
        t3 = time.perf_counter()
        run = {"pattern": t1 - t0, "stiffness": t2 - t1, "mass": t3 - t2, "assembly": t3 - t0}
        if best is None or run["assembly"] < best["assembly"]:
            best = run
        info_K, info_M = K.getInfo(), M.getInfo()
        ones = K.createVecRight()
        ones.set(1.0)
        Mx = M.createVecLeft()
        M.mult(ones, Mx)
        mass_kg = Mx.sum() / 3.0
        dofs = K.getSize()[0]
        K.destroy()
        M.destroy()
    seconds.update(best)

    cells = mesh.topology.index_map(3).size_local
    print(json.dumps({
        "peer": "DOLFINx",
        "dolfinx_version": dolfinx.__version__,
        "geometry_degree": mesh.geometry.cmap.degree,
        "cells": cells,
        "dofs": dofs,
        "stiffness_nonzeros": int(info_K["nz_used"]),
        "mass_nonzeros": int(info_M["nz_used"]),
        "mass_kg": mass_kg,
        "quadrature_points": {
            "stiffness": len(basix.make_quadrature(basix.CellType.tetrahedron, a.stiffness_degree)[1]),
            "mass": len(basix.make_quadrature(basix.CellType.tetrahedron, a.mass_degree)[1])},
        "quadrature_degree": {"stiffness": a.stiffness_degree, "mass": a.mass_degree},
        "seconds": seconds,
    }, indent=2))


if __name__ == "__main__":
    main()
