#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""What the Python module adds to a run: meshquilt.decorate() against the library's own time.

    python3 bench/bench_python.py [BASE] [SWATCH] [--scale 0.12] [--repeat 3]

Default: spot (tests/data/surface/spot.obj) with rivets at scale 0.12, the README's main job.
For each run it prints the wall time of decorate() as seen from Python, the library's own time
(report["seconds"]["total"]: validation, quilting, embedding), the difference (array conversion in
and out, the JSON report, the GIL), the output size and the peak RSS of the process. Needs the
module (pip install . or PYTHONPATH=<build>/python). Not run in CI: timings are measured on an idle
machine and recorded in docs/benchmarks.md.
"""
import argparse
import os
import resource
import time

import meshquilt

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("base", nargs="?", default=os.path.join(ROOT, "tests", "data", "surface", "spot.obj"))
    ap.add_argument("swatch", nargs="?", default=os.path.join(ROOT, "swatches", "rivets.obj"))
    ap.add_argument("--scale", type=float, default=0.12)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    base = meshquilt.read_mesh(args.base)
    swatch = meshquilt.read_mesh(args.swatch)
    calls = [0]

    def progress(stage, fraction):
        calls[0] += 1
        return True

    print(f"meshquilt {meshquilt.__version__}: {os.path.basename(args.base)} ({len(base[1])} faces) + "
          f"{os.path.basename(args.swatch)} ({len(swatch[1])} faces), scale {args.scale}, seed {args.seed}")
    for run in range(args.repeat):
        calls[0] = 0
        t0 = time.perf_counter()
        r = meshquilt.decorate(*base, *swatch, scale=args.scale, seed=args.seed, progress=progress)
        wall = time.perf_counter() - t0
        inside = r.report["seconds"]["total"]
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"run {run + 1}: decorate() {wall:.2f} s, library {inside:.2f} s, binding {wall - inside:.3f} s "
              f"({100 * (wall - inside) / wall:.1f}%); {r.num_elements} elements, {len(r.faces)} faces; "
              f"{calls[0]} progress calls; peak RSS {rss:.0f} MB")


if __name__ == "__main__":
    main()
