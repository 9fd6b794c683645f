#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Render a meshquilt output (or a swatch) to an image, headless, with Blender's Cycles on the CPU.

Every element (connected component) gets its own colour; the camera looks obliquely at the whole
mesh and is pulled back until it fits the frame. The mesh is taken to be z-up, as meshquilt writes it.

Needs Blender as a Python module (Python 3.11):
    python3.11 -m venv /tmp/bpyenv && /tmp/bpyenv/bin/pip install "numpy<2" "bpy==4.5.*"

Usage:
    /tmp/bpyenv/bin/python scripts/render.py IN.obj OUT.jpg [--size 900 500] [--samples 32]
        [--azimuth -18] [--elevation 42] [--zoom 1.0] [--up z|y|x]
The OBJ group `base` (meshquilt --with-base) is drawn in one neutral colour.
OUT may end in .jpg (quality 88; about 50 KB for the README images) or .png (8-bit, maximum
compression; about 400 KB at 900 x 500).
Also runs inside Blender: blender -b -P scripts/render.py -- IN.obj OUT.jpg
"""
import argparse
import colorsys
import math
import os
import sys

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

# The add-on's muted earthy palette (one place for both), each element one entry with a small
# jitter in value and saturation. Importing the add-on only defines it; nothing is registered.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "blender"))
from meshquilt_addon import PALETTE  # noqa: E402


def read_obj(path):
    """Vertices (n x 3), triangles (m x 3, 0-based) and, per triangle, whether it is in the OBJ
    group `base` (meshquilt --with-base); polygons are fan-triangulated."""
    verts, tris, base = [], [], []
    in_base = False
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith(("o ", "g ")):
                in_base = line.split()[1:2] == ["base"]
            elif line.startswith("v "):
                verts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                idx = []
                for tok in line.split()[1:]:
                    i = int(tok.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
                    base.append(in_base)
    if not tris:
        sys.exit(f"render.py: {path}: no faces")
    return np.asarray(verts, dtype=np.float64), np.asarray(tris, dtype=np.int64), np.asarray(base, dtype=bool)


def components(n_verts, tris):
    """Connected component of every face (faces sharing a vertex belong together)."""
    parent = np.arange(n_verts)

    def find(a):
        root = a
        while parent[root] != root:
            root = parent[root]
        while parent[a] != root:
            parent[a], a = root, parent[a]
        return root

    for a, b, c in tris:
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    roots = np.array([find(t[0]) for t in tris])
    _, labels = np.unique(roots, return_inverse=True)
    return labels


def element_colours(count):
    rng = np.random.default_rng(7)
    out = np.empty((count, 4))
    for e in range(count):
        r, g, b = PALETTE[rng.integers(len(PALETTE))]
        h, s, v = colorsys.rgb_to_hsv(r, g, b)
        s = min(1.0, s * rng.uniform(0.85, 1.1))
        v = min(1.0, v * rng.uniform(0.85, 1.05))
        rgb = colorsys.hsv_to_rgb(h, s, v)
        out[e] = [c ** 2.2 for c in rgb] + [1.0]  # sRGB -> linear
    return out


def build_mesh(verts, tris, base):
    labels = components(len(verts), tris)
    mesh = bpy.data.meshes.new("quilt")
    mesh.vertices.add(len(verts))
    mesh.vertices.foreach_set("co", verts.astype(np.float32).ravel())
    mesh.loops.add(3 * len(tris))
    mesh.loops.foreach_set("vertex_index", tris.astype(np.int32).ravel())
    mesh.polygons.add(len(tris))
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * len(tris), 3, dtype=np.int32))
    mesh.update(calc_edges=True)
    mesh.validate()
    colours = element_colours(labels.max() + 1)[labels]
    colours[base] = [0.45 ** 2.2, 0.43 ** 2.2, 0.40 ** 2.2, 1.0]  # the base: neutral grey-brown
    attr = mesh.color_attributes.new("element", "FLOAT_COLOR", "FACE")
    attr.data.foreach_set("color", colours.astype(np.float32).ravel())
    # Smooth shading where the surface is smooth, flat across sharp edges (facets, bevels).
    mesh.shade_smooth()
    mesh.set_sharp_from_angle(angle=math.radians(35))
    obj = bpy.data.objects.new("quilt", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj, labels.max() + 1


def material_from_attribute():
    mat = bpy.data.materials.new("element")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.55
    col = nodes.new("ShaderNodeAttribute")
    col.attribute_name = "element"
    links.new(col.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def add_ground(centre, radius, z):
    bpy.ops.mesh.primitive_plane_add(size=radius * 40, location=(centre.x, centre.y, z))
    ground = bpy.context.active_object
    mat = bpy.data.materials.new("ground")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.50, 0.49, 0.47, 1)
    bsdf.inputs["Roughness"].default_value = 0.9
    ground.data.materials.append(mat)


def add_lights(scene):
    # A large, soft key light from the upper left and a weak fill from the right; sky fills the rest.
    for rot, energy, angle in (((45, 0, -40), 4.0, 8), ((65, 0, 140), 0.5, 30)):
        data = bpy.data.lights.new("sun", "SUN")
        data.energy = energy
        data.angle = math.radians(angle)
        light = bpy.data.objects.new("sun", data)
        light.rotation_euler = tuple(math.radians(a) for a in rot)
        scene.collection.objects.link(light)
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs[0].default_value = (0.80, 0.86, 0.95, 1)
    bg.inputs[1].default_value = 0.45


def place_camera(scene, corners, centre, azimuth, elevation, zoom):
    data = bpy.data.cameras.new("cam")
    data.lens = 70
    cam = bpy.data.objects.new("cam", data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    a, e = math.radians(azimuth), math.radians(elevation)
    direction = Vector((math.cos(e) * math.sin(a), -math.cos(e) * math.cos(a), math.sin(e)))
    cam.rotation_euler = (-direction).to_track_quat("-Z", "Y").to_euler()

    def project(dist):
        cam.location = centre + direction * dist
        bpy.context.view_layer.update()
        return [world_to_camera_view(scene, cam, p) for p in corners]

    def fits(dist):
        return all(d > 0 and 0.03 <= x <= 0.97 and 0.04 <= y <= 0.96 for x, y, d in project(dist))

    def fit_distance():
        lo, hi = 0.0, 1.0
        while not fits(hi):
            hi *= 2
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if fits(mid) else (mid, hi)
        return hi

    # Perspective makes the near edge larger than the far one: shift the lens until the projected
    # box is centred in the frame, then pull in as close as the frame allows.
    aspect = scene.render.resolution_x / scene.render.resolution_y
    for _ in range(4):
        dist = fit_distance()
        xs, ys = zip(*[(x, y) for x, y, _ in project(dist)])
        data.shift_x += (0.5 * (min(xs) + max(xs)) - 0.5) * (1.0 if aspect >= 1 else 1.0 / aspect)
        data.shift_y += (0.5 * (min(ys) + max(ys)) - 0.5) * (1.0 / aspect if aspect >= 1 else 1.0)
    cam.location = centre + direction * (fit_distance() / zoom)


def setup_render(scene, corners, centre, args):
    """Ground, lights, camera and Cycles settings for a model whose bounding box has these corners;
    `args` carries size, samples, azimuth, elevation, zoom and output (JPEG or PNG)."""
    lo = Vector([min(c[i] for c in corners) for i in range(3)])
    hi = Vector([max(c[i] for c in corners) for i in range(3)])
    add_ground(centre, float((hi - lo).length), float(lo.z))
    add_lights(scene)

    scene.render.resolution_x, scene.render.resolution_y = args.size
    scene.render.resolution_percentage = 100
    place_camera(scene, corners, centre, args.azimuth, args.elevation, args.zoom)

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    scene.cycles.use_denoising = True
    scene.view_settings.view_transform = "AgX"
    scene.view_settings.look = "AgX - Medium High Contrast"

    settings = scene.render.image_settings
    if args.output.lower().endswith((".jpg", ".jpeg")):
        settings.file_format = "JPEG"
        settings.quality = 88
    else:
        settings.file_format = "PNG"
        settings.color_mode = "RGB"
        settings.color_depth = "8"
        settings.compression = 100
    scene.render.filepath = args.output


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--size", type=int, nargs=2, default=(900, 500), metavar=("W", "H"))
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--azimuth", type=float, default=-18.0, help="degrees; 0 looks along +y")
    ap.add_argument("--elevation", type=float, default=42.0, help="degrees above the xy plane")
    ap.add_argument("--zoom", type=float, default=1.0, help="> 1 crops into the middle")
    ap.add_argument("--up", choices=("x", "y", "z"), default="z", help="the mesh's up axis (meshes from scans are often y-up)")
    args = ap.parse_args(argv)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    verts, tris, base = read_obj(args.input)
    if args.up == "y":  # y-up to z-up, a rotation (keeps orientation)
        verts = np.stack([verts[:, 0], -verts[:, 2], verts[:, 1]], axis=1)
    elif args.up == "x":
        verts = np.stack([verts[:, 1], verts[:, 2], verts[:, 0]], axis=1)
    obj, count = build_mesh(verts, tris, base)
    obj.data.materials.append(material_from_attribute())

    used = verts[np.unique(tris)]
    lo, hi = used.min(axis=0), used.max(axis=0)
    centre = Vector(((lo + hi) / 2).tolist())
    corners = [Vector((x, y, z)) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    setup_render(scene, corners, centre, args)
    bpy.ops.render.render(write_still=True)
    print(f"render.py: {len(tris)} faces, {count} elements -> {args.output}")


if __name__ == "__main__":
    main()
