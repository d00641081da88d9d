#!/usr/bin/python3
"""Mesh a .geo/.step file with gmsh and write a .msh, the way flexmbs meshes a body.

Same options as flexmbs' gmsh import (fem/gmsh_import.cc): Mesh.MeshSizeMax = mesh size,
Mesh.ElementOrder = order, Mesh.SecondOrderIncomplete = 1 (tet10, not serendipity
variants). Writing the mesh to a file lets flexmbs and a peer program read the very same
nodes and elements.

Usage:
  /usr/bin/python3 make_msh.py GEOMETRY OUT.msh [--mesh-size 0.005] [--order 2]

Needs python3-gmsh (Debian: seen by /usr/bin/python3). Prints one JSON line with the node
and element counts.
"""
import argparse
import json
import sys

import gmsh


def make_msh(geometry, out, mesh_size=None, order=2):
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(geometry)
        gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size if mesh_size else 1e22)
        gmsh.option.setNumber("Mesh.ElementOrder", order)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.generate(3)
        types, element_tags, _ = gmsh.model.mesh.getElements(3)
        counts = {gmsh.model.mesh.getElementProperties(t)[0]: len(e) for t, e in zip(types, element_tags)}
        nodes = len(gmsh.model.mesh.getNodes()[0])
        gmsh.write(out)
        return {"msh": out, "nodes": nodes, "volume_elements": counts}
    finally:
        gmsh.finalize()


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("geometry", help=".geo, .step or .stp file")
    p.add_argument("out", help="output .msh file")
    p.add_argument("--mesh-size", type=float, help="Mesh.MeshSizeMax in model units (m)")
    p.add_argument("--order", type=int, default=2, choices=(1, 2))
    a = p.parse_args()
    try:
        print(json.dumps(make_msh(a.geometry, a.out, a.mesh_size, a.order)))
    except Exception as e:  # gmsh raises plain Exception with its last error
        print(f"make_msh.py: {a.geometry}: {e}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
