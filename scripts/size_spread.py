#!/usr/bin/env python3
"""Element size spread of a meshquilt OBJ output: the 95th over the 5th percentile of element
diameter (double sweep: farthest vertex from the farthest vertex) and of the square root of element
area, over the `o element_*` groups (the `base` group is skipped).

    python3 scripts/size_spread.py out.obj [more.obj ...]

Needs numpy. Used for the shell-map survey in docs/shellmap.md.
"""
import sys

import numpy as np


def elements(path):
    vertices, faces, current = [], {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith(("o ", "g ")):
                current = line.split()[1]
            elif line.startswith("f ") and current != "base":
                faces.setdefault(current, []).append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return np.array(vertices), faces


def spread(path):
    v, faces = elements(path)
    diameters, sizes = [], []
    for tris in faces.values():
        tris = np.array(tris)
        p = v[np.unique(tris)]
        a = p[np.argmax(((p - p[0]) ** 2).sum(1))]
        b = p[np.argmax(((p - a) ** 2).sum(1))]
        diameters.append(np.linalg.norm(b - a))
        e1, e2 = v[tris[:, 1]] - v[tris[:, 0]], v[tris[:, 2]] - v[tris[:, 0]]
        sizes.append(np.sqrt(0.5 * np.linalg.norm(np.cross(e1, e2), axis=1).sum()))
    ratio = lambda x: np.sort(x)[int(len(x) * 0.95)] / np.sort(x)[int(len(x) * 0.05)]
    return ratio(np.array(diameters)), ratio(np.array(sizes)), len(faces)


if __name__ == "__main__":
    for path in sys.argv[1:]:
        d, s, n = spread(path)
        print(f"{path}: {n} elements, p95/p5 diameter {d:.3f}, sqrt(area) {s:.3f}")
