# Writes open_caps.obj: a 5 x 5 swatch of open caps (the upper halves of icospheres of radius 0.8,
# two subdivisions, 2 apart), each one sheet with its own rim, as a leaf or a shingle often is.
# trimesh from PyPI (5.2.0 wrote the copy here); `python open_caps.py` beside this file.
import numpy as np
import trimesh

parts = []
for i in range(5):
    for j in range(5):
        s = trimesh.creation.icosphere(2, 0.8)
        keep = s.triangles_center[:, 2] > 0.0
        c = s.submesh([np.nonzero(keep)[0]], append=True)
        c.apply_translation([2 * i + 1, 2 * j + 1, 0])
        parts.append(c)
trimesh.util.concatenate(parts).export("open_caps.obj")
