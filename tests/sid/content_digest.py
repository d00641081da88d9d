"""The content digest of a `.sid.h5` body, computed from the file with h5py as docs/sid.md
("Content digest") describes it, independently of flexmbs's reader and hasher.

    python3 content_digest.py BODY.sid.h5

prints two lines: the digest with the hash the file's schema names (4: SHA-256 by hashlib,
5: XXH3-128 by python3-xxhash), then the digest the file stores.
"""
import hashlib
import struct
import sys

import h5py
import numpy as np
import xxhash

INVARIANTS = ["mdCM", "J", "Ct", "Cr", "Me", "Gr", "Ge", "Oe", "Ke", "De", "ksigma"]
NODE_FIELDS = ["origin", "phi", "psi", "AP"]


class Body:
    def __init__(self, hasher):
        self.h = hasher

    def integer(self, value):
        self.h.update(struct.pack("<q", value))

    def text(self, value):
        raw = value if isinstance(value, bytes) else value.encode()
        self.integer(len(raw))
        self.h.update(raw)

    def matrix(self, m):
        """A matrix as the math sees it: dims, then its doubles column by column."""
        m = np.asarray(m, dtype="<f8")
        if m.ndim == 1:
            m = m.reshape(-1, 1)
        self.integer(m.shape[0])
        self.integer(m.shape[1])
        self.h.update(m.tobytes(order="F"))

    def indices(self, values):
        values = np.asarray(values, dtype="<i8")
        self.integer(len(values))
        self.h.update(values.tobytes())

    def taylor(self, name, g):
        self.text(name)
        m0 = g["m0"][()]
        self.matrix(m0)
        order, modes = int(g.attrs["order"]), int(g.attrs["modes"])
        for k, count in ((1, modes), (2, modes * modes)):
            if order < k:
                self.integer(0)
                continue
            blocks = g[f"m{k}"][()].reshape(count, *m0.shape)
            self.integer(count)
            for block in blocks:
                self.matrix(block)


def digest(f, hasher):
    b = Body(hasher)
    b.text(f.attrs["name"])
    refmod = f["refmod"]
    b.matrix(np.array([[refmod["mass"][()]]]))
    b.matrix(refmod["center_of_mass"][()])
    b.matrix(refmod["inertia_about_center_of_mass"][()])
    for key in ("mode_names", "mode_kinds"):
        names = refmod[key][()]
        b.integer(len(names))
        for name in names:
            b.text(name)
    b.matrix(refmod["frequency_hz"][()])
    b.matrix(refmod["relative_residuals"][()])
    b.text(refmod.attrs["damping"])
    for name in INVARIANTS:
        b.taylor(name, f["invariants"][name])
    b.integer(1 if "stiffening" in f else 0)
    if "stiffening" in f:
        s = f["stiffening"]
        for name in ([f"K0t_{a}" for a in "xyz"] + [f"K0r_{a}" for a in "xyz"] +
                     [f"K0omega_{p}" for p in ("xx", "yy", "zz", "xy", "yz", "zx")]):
            b.matrix(s[name][()])
    b.matrix(f["mesh/node_positions"][()].T)  # stored one row per node; the body holds 3 x N
    sets = f["mesh/node_sets"]
    b.integer(len(sets))
    for name in sorted(sets):
        b.text(name)
        b.indices(sets[name][()])
    b.matrix(f["modes/phi"][()])
    nodes = f["nodes"]
    b.integer(len(nodes))
    for name in sorted(nodes):
        g = nodes[name]
        b.text(name)
        b.indices(g["fe_nodes"][()])
        b.text(g.attrs["coupling"])
        for field in NODE_FIELDS:
            b.taylor(field, g[field])
    surfaces = f["surfaces"]
    b.integer(len(surfaces))
    for name in sorted(surfaces):
        g = surfaces[name]
        b.text(name)
        b.indices(g["fe_nodes"][()])
        b.matrix(g["vertices"][()])
        b.indices(g["face_sizes"][()])
        b.indices(g["face_vertices"][()])
        b.matrix(g["face_normals"][()])
        b.matrix(g["phi"][()])
    visual = f["visual_surface"] if "visual_surface" in f else {}
    b.indices(visual["face_sizes"][()] if visual else [])
    b.indices(visual["face_nodes"][()] if visual else [])
    return hasher.hexdigest()


def main(path):
    with h5py.File(path, "r") as f:
        schema = int(f.attrs["schema_version"])
        hasher, attribute = ((hashlib.sha256(), "content_sha256") if schema == 4 else
                             (xxhash.xxh3_128(), "content_xxh3_128"))
        print(digest(f, hasher))
        stored = f.attrs[attribute]
        print(stored.decode() if isinstance(stored, bytes) else stored)


if __name__ == "__main__":
    main(sys.argv[1])
