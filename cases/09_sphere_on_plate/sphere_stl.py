#!/usr/bin/python3
"""The lower cap of an icosphere as a binary STL file, the rigid sphere of cases/09_sphere_on_plate.

The icosahedron's faces split into four `level` times, the new vertices pushed out onto the
sphere of radius R about the origin; kept are the faces with a vertex lower than the cap's rim
z = -R cos(asin(rim / R)) (an open patch, counter-clockwise seen from outside). Coordinates in
the sphere's own frame [m]; the scene places it by its marker.

Usage: /usr/bin/python3 sphere_stl.py LEVEL RADIUS RIM OUT.stl   (prints the triangle count)
"""
import sys

import numpy as np


def icosphere(level):
    """Unit icosphere: vertices (n x 3) and counter-clockwise faces (m x 3)."""
    g = (1.0 + 5.0 ** 0.5) / 2.0
    v = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
         (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(level):
        middle = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                p = vertices[i] + vertices[j]
                vertices.append(p / np.linalg.norm(p))
                middle[key] = len(vertices) - 1
            return middle[key]

        finer = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = finer
    return np.array(vertices), np.array(f)


def main():
    level, radius, rim, path = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
    vertices, faces = icosphere(level)
    vertices *= radius
    below = vertices[:, 2] < -np.sqrt(radius ** 2 - rim ** 2)
    faces = faces[below[faces].any(axis=1)]
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    rows = np.zeros(len(faces), record)
    rows["n"], rows["v"] = normals, corners
    with open(path, "wb") as out:
        out.write(b"flexmbs cases/09_sphere_on_plate sphere cap".ljust(80, b" "))
        out.write(np.uint32(len(faces)).tobytes())
        out.write(rows.tobytes())
    print(len(faces))


if __name__ == "__main__":
    main()
