#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Render the Blender add-on's result for the docs (docs/images/blender_addon.jpg).

Registers python/blender/meshquilt_addon.py, imports a base and a swatch OBJ (Blender's default
OBJ axes: y-up files come in z-up), runs ``bpy.ops.object.meshquilt_decorate`` on the base and
renders the new object, coloured per element by the add-on's material (the colour attribute
``meshquilt_color``), over the base, with Cycles on the CPU. Camera, lights and ground are those of
scripts/render.py.

Needs Blender as a Python module (Python 3.11, see scripts/render.py) and meshquilt importable::

    PYTHONPATH=build-main/python /tmp/bpyenv/bin/python python/blender/render_addon_example.py \\
        [docs/images/blender_addon.jpg] [--base tests/data/surface/spot.obj] [--swatch swatches/pebbles.obj]
        [--scale 0.1] [--seed 1] [--size 900 500] [--samples 32] [--azimuth -120] [--elevation 20]

About 30 s for the decoration (spot + pebbles at scale 0.1: ~2,500 pebbles, 730k faces) and 25 s
for the render on 2 cores.
"""
import argparse
import os
import sys
import time

import bpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import meshquilt_addon  # noqa: E402
from render import setup_render  # noqa: E402  (scripts/render.py)


def import_obj(path):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path)
    (obj,) = set(bpy.data.objects) - before
    return obj


def base_material():
    mat = bpy.data.materials.new("base")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.45 ** 2.2, 0.43 ** 2.2, 0.40 ** 2.2, 1)
    bsdf.inputs["Roughness"].default_value = 0.8
    return mat


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("output", nargs="?", default=os.path.join(ROOT, "docs", "images", "blender_addon.jpg"))
    ap.add_argument("--base", default=os.path.join(ROOT, "tests", "data", "surface", "spot.obj"))
    ap.add_argument("--swatch", default=os.path.join(ROOT, "swatches", "pebbles.obj"))
    ap.add_argument("--scale", type=float, default=0.1)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--size", type=int, nargs=2, default=(900, 500), metavar=("W", "H"))
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--azimuth", type=float, default=-120.0)
    ap.add_argument("--elevation", type=float, default=20.0)
    ap.add_argument("--zoom", type=float, default=1.0)
    args = ap.parse_args(argv)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    meshquilt_addon.register()
    if meshquilt_addon.load_meshquilt() is None:
        sys.exit("render_addon_example: " + meshquilt_addon.install_hint())
    scene = bpy.context.scene
    base = import_obj(args.base)
    swatch = import_obj(args.swatch)
    swatch.hide_render = swatch.hide_viewport = True
    base.data.materials.append(base_material())
    base.data.shade_smooth()

    bpy.context.view_layer.objects.active = base
    t0 = time.perf_counter()
    bpy.ops.object.meshquilt_decorate(swatch=swatch.name, scale=args.scale, seed=args.seed)
    out = bpy.context.view_layer.objects.active
    print(f"render_addon_example: {out.name}: {out['meshquilt_elements']} elements, "
          f"{out['meshquilt_faces']} faces in {time.perf_counter() - t0:.1f} s")

    corners = [out.matrix_world @ Vector(c) for c in out.bound_box]
    centre = sum(corners, Vector()) / len(corners)
    setup_render(scene, corners, centre, args)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"render_addon_example: rendered {args.output} in {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
    if not bpy.app.binary_path:  # bpy as a Python module, which can hang at exit (see python/tests/blender_e2e.py)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0)
