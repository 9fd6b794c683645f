# SPDX-License-Identifier: AGPL-3.0-or-later
"""The whole job through the Python module: decorate BASE with SWATCH and write the result.

    python3 examples/decorate.py BASE SWATCH OUT.obj [SCALE] [SEED]

Needs the module: `pip install .` in the repository (docs/library.md).
"""
import sys

import numpy as np

import meshquilt


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    base_path, swatch_path, out_path = sys.argv[1:4]
    scale = float(sys.argv[4]) if len(sys.argv) > 4 else 0.08
    seed = int(sys.argv[5]) if len(sys.argv) > 5 else 1

    base_vertices, base_faces = meshquilt.read_mesh(base_path)
    swatch_vertices, swatch_faces = meshquilt.read_mesh(swatch_path)

    def progress(stage, fraction):
        print(f"\r{stage:<10} {100 * fraction:3.0f}%", end="", file=sys.stderr, flush=True)
        return True  # False would cancel: decorate() then raises meshquilt.CancelledError

    try:
        r = meshquilt.decorate(base_vertices, base_faces, swatch_vertices, swatch_faces,
                               scale=scale, seed=seed, progress=progress)
    except ValueError as e:  # meshquilt.InvalidInputError: bad mesh or option, with the reason
        sys.exit(f"\nerror: {e}")
    print(file=sys.stderr)
    for w in r.warnings:
        print("warning:", w, file=sys.stderr)
    meshquilt.write_mesh(out_path, r.vertices, r.faces, element_ids=r.element_ids)
    sizes = np.bincount(r.element_ids)
    print(f"{r.num_elements} elements, {len(r.faces)} faces ({sizes.min()}..{sizes.max()} per element), "
          f"{r.report['seconds']['total']:.1f} s -> {out_path}")


if __name__ == "__main__":
    main()
