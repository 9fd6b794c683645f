# Writes holed_plate.obj: a 20 x 20 x 8 plate with a round hole (radius 5, 48 sides) through it,
# made with manifold3d's boolean difference and refine(4) (each triangle split into 16, so every
# edge, the hole's rims included, into 4 collinear pieces; slivers all over).
# Run: python3 holed_plate.py holed_plate.obj  (pip install manifold3d trimesh numpy)
import sys

import manifold3d as m
import numpy as np
import trimesh

plate = m.Manifold.cube([20, 20, 8], center=True) - m.Manifold.cylinder(20, 5, 5, 48, center=True)
plate = plate.refine(4)
mesh = plate.to_mesh()
t = trimesh.Trimesh(np.array(mesh.vert_properties)[:, :3], np.array(mesh.tri_verts), process=False)
print(len(t.faces), "faces, watertight:", t.is_watertight, "volume:", t.volume)
t.export(sys.argv[1])
