#!/usr/bin/python3
"""Writes a large closed test mesh: an icosphere subdivided `--level` times (20 * 4^level
triangles; level 8 gives 1,310,720) with a smooth deterministic radial bump, as binary PLY with
per-vertex normals. The figure of README.md's performance table (a million-triangle mesh at
L = 16 through `tessim sim`) uses the default.

    /usr/bin/python3 scripts/make_big_mesh.py [-o sphere.ply] [--level 8]
"""
import argparse
import sys

import numpy as np


def icosphere(level):
    t = (1.0 + 5.0 ** 0.5) / 2.0
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
                  [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], dtype=np.float64)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
                  [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
                  [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]], dtype=np.int64)
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    for _ in range(level):
        # One midpoint per undirected edge, shared by its two faces.
        edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        key = np.sort(edges, axis=1)
        uniq, inverse = np.unique(key[:, 0] * len(v) + key[:, 1], return_inverse=True)
        a, b = uniq // len(v), uniq % len(v)
        mid = v[a] + v[b]
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = inverse.reshape(3, -1).T + len(v)  # midpoints of edges 01, 12, 20 per face
        v = np.concatenate([v, mid])
        f = np.concatenate([np.stack([f[:, 0], m[:, 0], m[:, 2]], 1), np.stack([f[:, 1], m[:, 1], m[:, 0]], 1),
                            np.stack([f[:, 2], m[:, 2], m[:, 1]], 1), m])
    return v, f


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--output", default="big_sphere.ply")
    ap.add_argument("--level", type=int, default=8, help="subdivisions (20 * 4^level triangles)")
    args = ap.parse_args()
    if not 0 <= args.level <= 10:
        sys.exit("make_big_mesh: --level must be 0..10")
    v, f = icosphere(args.level)
    # A smooth bump of +-4 % of the radius: the surface is curved everywhere but never folds.
    bump = 1.0 + 0.04 * np.sin(5 * v[:, 0]) * np.sin(4 * v[:, 1] + 1.0) * np.cos(3 * v[:, 2])
    p = v * bump[:, None]
    # Vertex normals: area-weighted face normals.
    fn = np.cross(p[f[:, 1]] - p[f[:, 0]], p[f[:, 2]] - p[f[:, 0]])
    n = np.zeros_like(p)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    vert = np.empty(len(p), dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4")])
    for i, name in enumerate("xyz"):
        vert[name] = p[:, i]
        vert["n" + name] = n[:, i]
    face = np.empty(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    face["n"] = 3
    face["i"] = f
    header = ("ply\nformat binary_little_endian 1.0\ncomment tessim scripts/make_big_mesh.py level %d\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (args.level, len(p), len(f))
    with open(args.output, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(vert.tobytes())
        out.write(face.tobytes())
    print("%s: %d vertices, %d triangles" % (args.output, len(p), len(f)))


if __name__ == "__main__":
    main()
