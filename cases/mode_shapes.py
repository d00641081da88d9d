#!/usr/bin/python3
"""Mode-shape pictures of a reduced body, read from its .sid.h5 alone (docs/sid.md): the visual
surface's polygons (`visual_surface`) on the FE nodes (`mesh/node_positions`), displaced by each
mode (`modes/phi`, u = Phi q, row 3k + a node k along axis a) scaled so that its largest nodal
displacement is `--scale` of the body's largest extent, coloured by the displacement's magnitude
(relative to that largest one), the undeformed outline in grey. Used by cases 01, 05 and 07.

Usage: /usr/bin/python3 mode_shapes.py BODY.sid.h5 OUT.png [--modes N] [--scale s] [--view ELEV AZIM]
"""
import argparse

import h5py
import numpy as np


def read_body(path):
    """Nodes (N, 3) [m], polygons (lists of node indices), Phi (3N, n), mode names and frequencies [Hz]."""
    with h5py.File(path, "r") as f:
        nodes = f["mesh/node_positions"][:]
        phi = f["modes/phi"][:]
        sizes = f["visual_surface/face_sizes"][:]
        face_nodes = f["visual_surface/face_nodes"][:]
        names = [n.decode() for n in f["refmod/mode_names"][:]]
        frequencies = f["refmod/frequency_hz"][:]
    faces = np.split(face_nodes, np.cumsum(sizes)[:-1])
    return nodes, faces, phi, names, frequencies


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("body")
    p.add_argument("png")
    p.add_argument("--modes", type=int, default=6, help="the first N modes (default 6)")
    p.add_argument("--scale", type=float, default=0.15, help="largest displacement / largest extent")
    p.add_argument("--view", type=float, nargs=2, default=(25.0, -60.0), metavar=("ELEV", "AZIM"))
    p.add_argument("--title", default=None)
    a = p.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    nodes, faces, phi, names, frequencies = read_body(a.body)
    extent = np.ptp(nodes, axis=0)
    count = min(a.modes, phi.shape[1])
    columns = min(3, count)
    rows = (count + columns - 1) // columns
    fig = plt.figure(figsize=(4.2 * columns, 3.6 * rows))
    colours = plt.get_cmap("viridis")
    for k in range(count):
        u = phi[:, k].reshape(-1, 3)
        magnitude = np.linalg.norm(u, axis=1)
        largest = magnitude.max()
        moved = nodes + u * (a.scale * extent.max() / largest)
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d")
        ax.add_collection3d(Line3DCollection([nodes[np.append(f, f[0])] for f in faces],
                                             colors=[(0.5, 0.5, 0.5, 0.3)], linewidths=0.2))
        shade = [colours(magnitude[f].mean() / largest) for f in faces]
        ax.add_collection3d(Poly3DCollection([moved[f] for f in faces], facecolors=shade, edgecolors="k",
                                             linewidths=0.1))
        # True proportions, but no axis drawn shorter than a fifth of the longest (slender bodies).
        both = np.vstack([nodes, moved])
        centre = 0.5 * (both.max(axis=0) + both.min(axis=0))
        half = np.maximum(0.5 * np.ptp(both, axis=0), 0.1 * np.ptp(both, axis=0).max())
        for setter, c, h in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, half):
            setter(c - h, c + h)
        ax.set_box_aspect(half)
        ax.view_init(*a.view)
        ax.set_axis_off()
        ax.set_title(f"{names[k]}: {frequencies[k]:.5g} Hz", fontsize=9)
    mappable = plt.cm.ScalarMappable(cmap=colours, norm=plt.Normalize(0, 1))
    fig.colorbar(mappable, ax=fig.axes, shrink=0.6, label="|u| / largest |u| of the mode")
    fig.suptitle(a.title or f"{a.body.split('/')[-1]}: mode shapes (displacement x{a.scale:g} of the extent)")
    fig.savefig(a.png, dpi=110)
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
