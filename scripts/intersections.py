#!/usr/bin/env python3
"""Checks a meshquilt OBJ output for element-element intersections with a library independent
of ours (manifold3d): every `o element_*` group (the `base` group is skipped) becomes a Manifold,
and every pair whose bounding boxes overlap is intersected; a pair whose common volume exceeds
1e-9 of the smaller element's box volume counts as intersecting. Elements that manifold3d cannot
take as a closed manifold solid are counted apart (open swatches give open elements).

    python3 scripts/intersections.py out.obj [more.obj ...]

Needs numpy and manifold3d (pip install numpy manifold3d). Prints one line per file; exits 1
when any file has an intersecting pair. Used for the surveys in docs/surface.md.
"""
import sys

import numpy as np

from size_spread import elements  # the same reader: `o element_*` groups, base skipped


def check(path):
    import manifold3d as m3d

    v, groups = elements(path)
    solids, boxes, open_count = [], [], 0
    for tris in groups.values():
        tris = np.array(tris)
        used, local = np.unique(tris, return_inverse=True)
        mesh = m3d.Mesh(vert_properties=v[used].astype(np.float32), tri_verts=local.reshape(-1, 3).astype(np.uint32))
        solid = m3d.Manifold(mesh)
        if solid.status() != m3d.Error.NoError or solid.is_empty():
            open_count += 1
            continue
        solids.append(solid)
        boxes.append((v[used].min(0), v[used].max(0)))
    lo = np.array([b[0] for b in boxes]).reshape(-1, 3)
    hi = np.array([b[1] for b in boxes]).reshape(-1, 3)
    order = np.argsort(lo[:, 0])
    pairs = intersecting = 0
    for a_pos, a in enumerate(order):
        for b in order[a_pos + 1:]:
            if lo[b, 0] > hi[a, 0]:
                break
            if np.any(lo[b] > hi[a]) or np.any(hi[b] < lo[a]):
                continue
            pairs += 1
            box = min(np.prod(hi[a] - lo[a]), np.prod(hi[b] - lo[b]))
            if (solids[a] ^ solids[b]).volume() > 1e-9 * box:
                intersecting += 1
    return len(groups), open_count, pairs, intersecting


if __name__ == "__main__":
    bad = False
    for path in sys.argv[1:]:
        n, open_count, pairs, hits = check(path)
        bad = bad or hits > 0
        print(f"{path}: {n} elements, {open_count} not closed manifolds, {pairs} pairs with overlapping boxes, {hits} intersecting")
    sys.exit(1 if bad else 0)
