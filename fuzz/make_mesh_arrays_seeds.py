#!/usr/bin/python3
"""Writes the seeds of fuzz_mesh_arrays (fuzz/corpus/mesh_arrays/) from what gmsh returns for the
meshes in tests/data, encoded as mesh_arrays_fuzz.cc reads them. Run with Debian's python3 (it
has the gmsh module): /usr/bin/python3 fuzz/make_mesh_arrays_seeds.py"""
import pathlib
import struct

import gmsh

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "fuzz" / "corpus" / "mesh_arrays"
MAX_ELEMENTS = 7  # the target reads at most 7 elements per block
MAX_NODES = 63    # and at most 63 nodes


def tag(value):
    """A tag: flag 0 and one byte below 128, or flag 128 and eight bytes."""
    return bytes([0, value]) if value < 128 else bytes([128]) + struct.pack("<Q", value)


def coordinate(value):
    """A coordinate: flag 0 and int16 millimetres if exact, else flag 128 and the double."""
    mm = round(value * 1000)
    if abs(mm) < 32768 and mm / 1000.0 == value:
        return bytes([0]) + struct.pack("<h", mm)
    return bytes([128]) + struct.pack("<d", value)


def encode(blocks, node_tags, coords, set_tags):
    """The bytes of one input: blocks (type, element tags, node tags), nodes, a node set."""
    out = bytes([len(blocks)])
    for gmsh_type, elements, nodes in blocks:
        out += bytes([gmsh_type, len(elements)]) + b"".join(map(tag, elements))
        out += bytes([0]) + b"".join(map(tag, nodes))  # 0: exactly the count the type needs
    out += bytes([len(node_tags)]) + b"".join(map(tag, node_tags))
    out += bytes([0]) + b"".join(map(coordinate, coords))
    return out + b"".join(map(tag, set_tags))


def seed_of(path):
    """What gmsh returns for the mesh file (its first elements and nodes), encoded."""
    gmsh.open(str(path))
    blocks = []
    for dim, entity in gmsh.model.getEntities(3):
        types, elements, nodes = gmsh.model.mesh.getElements(dim, entity)
        for t, e, n in zip(types, elements, nodes):
            per = len(n) // len(e)
            count = min(len(e), MAX_ELEMENTS)
            blocks.append((int(t), [int(x) for x in e[:count]], [int(x) for x in n[:count * per]]))
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    count = min(len(node_tags), MAX_NODES)
    groups = gmsh.model.getPhysicalGroups()
    set_tags = []
    if groups:
        set_tags = [int(x) for x in gmsh.model.mesh.getNodesForPhysicalGroup(*groups[0])[0]]
    return encode(blocks[:3], [int(x) for x in node_tags[:count]], list(coords[:3 * count]), set_tags)


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    OUT.mkdir(parents=True, exist_ok=True)
    for name in ["two_tets", "inverted_tet", "pyramid", "hex27"]:
        (OUT / name).write_bytes(seed_of(ROOT / "tests" / "data" / f"{name}.msh"))
    gmsh.finalize()


if __name__ == "__main__":
    main()
