#!/usr/bin/env python3
"""Writes the generated fixtures of tests/data/io (binary PLY and STL, ASCII STL): a unit cube in
each, the same cube as the hand-written cube_mixed.obj, cube.off and cube_ascii.ply.
Run from anywhere: python3 make_fixtures.py. Deterministic: same bytes every time."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
TRIS = [t for q in QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def normal(t):
    a, b, c = (V[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


# Little-endian PLY: float coordinates, a uchar and a float list per vertex to skip, uint counts
# with int indices for quads, an extra int face property, and an extra element after the faces.
head = ("ply\nformat binary_little_endian 1.0\ncomment unit cube for the meshquilt io tests (make_fixtures.py)\n"
        "element vertex 8\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
        "property list uchar float uv\n"
        "element face 6\nproperty list uint int vertex_indices\nproperty int flags\n"
        "element material 2\nproperty double shininess\nproperty list ushort uchar name\nend_header\n")
body = b""
for i, v in enumerate(V):
    body += struct.pack("<fffB", *v, 200)
    body += struct.pack("<B", 2) + struct.pack("<ff", 0.25, 0.75) if i % 2 else struct.pack("<B", 0)
for q in QUADS:
    body += struct.pack("<I4ii", 4, *q, 7)
for m in (b"steel", b"gold"):
    body += struct.pack("<dH", 0.5, len(m)) + m
write("cube_binary_le.ply", head.encode() + body)

# Big-endian PLY: double coordinates named float64, the face list as uint8/uint16, triangles.
head = ("ply\nformat binary_big_endian 1.0\ncomment unit cube for the meshquilt io tests (make_fixtures.py)\n"
        "element vertex 8\nproperty float64 x\nproperty float64 y\nproperty float64 z\n"
        "element face 12\nproperty list uint8 uint16 vertex_indices\nend_header\n")
body = b"".join(struct.pack(">ddd", *v) for v in V)
body += b"".join(struct.pack(">BHHH", 3, *t) for t in TRIS)
write("cube_binary_be.ply", head.encode() + body)

# ASCII STL: upper- and lower-case keywords, as exporters write both.
lines = ["solid cube"]
for n, t in enumerate(TRIS):
    up = str.upper if n == 0 else str
    lines.append(up("  facet normal") + " %g %g %g" % normal(t))
    lines.append(up("    outer loop"))
    for i in t:
        lines.append(up("      vertex") + " %g %g %g" % V[i])
    lines.append(up("    endloop"))
    lines.append(up("  endfacet"))
lines.append("endsolid cube")
write("cube_ascii.stl", ("\n".join(lines) + "\n").encode())

# Binary STL whose 80-byte header starts with "solid", as some exporters write it.
data = b"solid cube, but binary".ljust(80, b" ") + struct.pack("<I", len(TRIS))
for t in TRIS:
    data += struct.pack("<3f", *normal(t))
    for i in t:
        data += struct.pack("<3f", *V[i])
    data += struct.pack("<H", 0)
write("cube_binary_solid.stl", data)
