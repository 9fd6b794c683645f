#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Deterministic generator of the meshquilt example swatches.

Standard library only (Python >= 3.8), so anyone can rerun it:

    python3 swatches/generate.py                 # rewrite every swatch next to this script
    python3 swatches/generate.py --only weave    # just one
    python3 swatches/generate.py --out /tmp/sw   # somewhere else

Every swatch is a thin slab: footprint x in [0, Lx], y in [0, Ly], thickness z in [0, h]
with h much smaller than the footprint. Every element (connected component) is a closed,
edge-manifold, outward-oriented triangle mesh, and no two elements touch. The script checks
the topological part of that itself (edges, orientation, volume, degenerate faces, duplicate
vertices) before writing; swatches/check_swatches.py checks the geometry (intersections, gaps,
chain-mail linking numbers) independently.

Output is byte-identical on every run: all randomness comes from random.Random(seed) with a
fixed seed per swatch, iteration orders are fixed, and floats are written with '%.6f'.

The generated OBJ files are dedicated to the public domain (CC0-1.0); this script is part of
meshquilt and licensed AGPL-3.0-or-later.
"""

import argparse
import math
import os
import random
import sys

FLOAT_FORMAT = '%.6f'
DATA_LICENCE = ('CC0-1.0 (this generated data is dedicated to the public domain; '
                'the generator script is AGPL-3.0-or-later like the rest of meshquilt)')
TAU = 2.0 * math.pi


# ----------------------------------------------------------------------------------------------
# small vector helpers (tuples of 3 floats)

def v_add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def v_sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def v_mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def v_dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def v_cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def v_len(a):
    return math.sqrt(v_dot(a, a))


def v_unit(a):
    n = v_len(a)
    return (a[0] / n, a[1] / n, a[2] / n)


# ----------------------------------------------------------------------------------------------
# meshes

class Part:
    """One element: a closed triangle mesh with 0-based faces."""

    def __init__(self):
        self.v = []
        self.f = []

    def vert(self, p):
        self.v.append((float(p[0]), float(p[1]), float(p[2])))
        return len(self.v) - 1

    def tri(self, a, b, c):
        self.f.append((a, b, c))

    def quad(self, a, b, c, d):
        """Quad a-b-c-d (counter-clockwise seen from outside) as two triangles."""
        self.f.append((a, b, c))
        self.f.append((a, c, d))

    def translate(self, t):
        self.v = [(p[0] + t[0], p[1] + t[1], p[2] + t[2]) for p in self.v]

    def signed_volume(self):
        vol = 0.0
        for a, b, c in self.f:
            vol += v_dot(self.v[a], v_cross(self.v[b], self.v[c]))
        return vol / 6.0

    def flip(self):
        self.f = [(a, c, b) for a, b, c in self.f]


def check_part(part, name):
    """Topological self-check of one element; raises on any problem."""
    nv = len(part.v)
    used = [False] * nv
    directed = {}
    for fi, (a, b, c) in enumerate(part.f):
        if len({a, b, c}) != 3:
            raise ValueError('%s: face %d repeats a vertex' % (name, fi))
        for x, y in ((a, b), (b, c), (c, a)):
            if (x, y) in directed:
                raise ValueError('%s: directed edge %d-%d used twice (non-manifold or '
                                 'inconsistent winding)' % (name, x, y))
            directed[(x, y)] = fi
        used[a] = used[b] = used[c] = True
        pa, pb, pc = part.v[a], part.v[b], part.v[c]
        area2 = v_len(v_cross(v_sub(pb, pa), v_sub(pc, pa)))
        longest = max(v_len(v_sub(pb, pa)), v_len(v_sub(pc, pb)), v_len(v_sub(pa, pc)))
        if area2 <= 1e-9 or area2 / (longest * longest) < 1e-4:
            raise ValueError('%s: degenerate face %d' % (name, fi))
    for (x, y) in directed:
        if (y, x) not in directed:
            raise ValueError('%s: boundary edge %d-%d (mesh not closed)' % (name, x, y))
    if not all(used):
        raise ValueError('%s: unused vertex' % name)
    # vertex manifoldness: the faces around each vertex form a single fan
    nxt = {}
    for a, b, c in part.f:
        for x, y, z in ((a, b, c), (b, c, a), (c, a, b)):
            nxt.setdefault(x, {})[y] = z
    for x, ring in nxt.items():
        start = next(iter(ring))
        y, steps = start, 0
        while True:
            y = ring[y]
            steps += 1
            if y == start:
                break
        if steps != len(ring):
            raise ValueError('%s: vertex %d is not manifold' % (name, x))
    if part.signed_volume() <= 0.0:
        raise ValueError('%s: volume not positive (faces oriented inward)' % name)


def fmt(x):
    s = FLOAT_FORMAT % x
    if s.startswith('-') and float(s) == 0.0:
        s = s[1:]
    return s


def write_obj(path, header, parts):
    """Write parts (list of Part) to an OBJ file; returns (n_vertices, n_faces)."""
    lines = ['# ' + h if h else '#' for h in header]
    seen = set()
    offset = 1
    vlines = []
    flines = []
    for pi, part in enumerate(parts):
        for p in part.v:
            s = 'v %s %s %s' % (fmt(p[0]), fmt(p[1]), fmt(p[2]))
            if s in seen:
                raise ValueError('%s: duplicate vertex %s (element %d)' % (path, s, pi))
            seen.add(s)
            vlines.append(s)
        for a, b, c in part.f:
            flines.append('f %d %d %d' % (a + offset, b + offset, c + offset))
        offset += len(part.v)
    text = '\n'.join(lines + vlines + flines) + '\n'
    with open(path, 'w', newline='\n', encoding='ascii') as fh:
        fh.write(text)
    return len(vlines), len(flines)


def normalise_placement(parts, xy=True):
    """Translate all parts together so that min z = 0 (and min x = min y = 0 if xy)."""
    mins = [min(p.v[i][k] for p in parts for i in range(len(p.v))) for k in range(3)]
    t = (-mins[0] if xy else 0.0, -mins[1] if xy else 0.0, -mins[2])
    for p in parts:
        p.translate(t)


def extent(parts):
    lo = [min(p.v[i][k] for p in parts for i in range(len(p.v))) for k in range(3)]
    hi = [max(p.v[i][k] for p in parts for i in range(len(p.v))) for k in range(3)]
    return lo, hi


# ----------------------------------------------------------------------------------------------
# 1. weave: long interlaced threads (non-tileable)

class Thread:
    """A yarn running along one axis; t is the coordinate along that axis, in [0, L]."""

    def __init__(self, along_x, base, half_w, half_h, wav, radvar):
        self.along_x = along_x      # True: warp (runs along x), False: weft (runs along y)
        self.base = base            # nominal cross coordinate (y for warp, x for weft)
        self.half_w = half_w        # half width of the elliptic cross-section
        self.half_h = half_h        # half height of the elliptic cross-section
        self.wav = wav              # [(amplitude, wavelength, phase)] in-plane waviness
        self.radvar = radvar        # (relative amplitude, wavelength, phase) of radius variation
        self.knots = []             # [(t, sign)] over (+1) / under (-1) at each crossing

    def offset(self, t):
        return sum(a * math.sin(TAU * t / lam + ph) for a, lam, ph in self.wav)

    def d_offset(self, t):
        return sum(a * TAU / lam * math.cos(TAU * t / lam + ph) for a, lam, ph in self.wav)

    def cross_coord(self, t):
        return self.base + self.offset(t)

    def radius_scale(self, t):
        e, lam, ph = self.radvar
        return 1.0 + e * math.sin(TAU * t / lam + ph)

    def profile(self, t):
        """Smooth over/under profile s(t) in [-1, 1] and ds/dt: a half cosine between crossings."""
        k = self.knots
        if t <= k[0][0]:
            t0, s0, d = k[0][0], k[0][1], k[1][0] - k[0][0]
        elif t >= k[-1][0]:
            t0, s0, d = k[-1][0], k[-1][1], k[-1][0] - k[-2][0]
        else:
            j = 0
            while k[j + 1][0] < t:
                j += 1
            t0, s0, d = k[j][0], k[j][1], k[j + 1][0] - k[j][0]
        w = math.pi / d
        return s0 * math.cos(w * (t - t0)), -s0 * w * math.sin(w * (t - t0))


def thread_part(th, length, z_mid, amp, sides, segs):
    part = Part()
    rings = []
    for k in range(segs + 1):
        t = length * k / segs
        s, ds = th.profile(t)
        off, doff = th.offset(t), th.d_offset(t)
        if th.along_x:
            c = (t, th.base + off, z_mid + amp * s)
            tan = v_unit((1.0, doff, amp * ds))
        else:
            c = (th.base + off, t, z_mid + amp * s)
            tan = v_unit((doff, 1.0, amp * ds))
        side = v_unit((-tan[1], tan[0], 0.0))
        up = v_cross(tan, side)
        sc = th.radius_scale(t)
        a, b = th.half_w * sc, th.half_h * sc
        ring = []
        for m in range(sides):
            th_m = TAU * (m + 0.5) / sides      # flat top and bottom: a flattened yarn
            p = v_add(c, v_add(v_mul(side, a * math.cos(th_m)), v_mul(up, b * math.sin(th_m))))
            if k in (0, segs):
                # cut the end exactly in the plane t = 0 or t = length (slide along the tangent)
                ax = 0 if th.along_x else 1
                p = v_add(p, v_mul(tan, (t - p[ax]) / tan[ax]))
            ring.append(part.vert(p))
        rings.append((c, ring))
    for k in range(segs):
        r0, r1 = rings[k][1], rings[k + 1][1]
        for m in range(sides):
            m1 = (m + 1) % sides
            part.quad(r0[m], r0[m1], r1[m1], r1[m])
    for k, rev in ((0, False), (segs, True)):
        c, ring = rings[k]
        ci = part.vert(c)
        for m in range(sides):
            a, b = ring[m], ring[(m + 1) % sides]
            if rev:
                part.tri(ci, a, b)
            else:
                part.tri(ci, b, a)
    if part.signed_volume() < 0:
        part.flip()
    return part


def gen_weave():
    seed = 4
    rng = random.Random(seed)
    P = dict(L=10.0, n_warp=7, n_weft=7, sides=8, segments=66, half_width=0.44,
             half_height=0.17, amplitude=0.25, spacing_jitter=0.08, width_jitter=0.08,
             waviness=0.045, radius_variation=0.06)
    L = P['L']

    def make(along_x, n):
        d = L / n
        out = []
        for i in range(n):
            base = (i + 0.5) * d + rng.uniform(-1.0, 1.0) * P['spacing_jitter'] * d
            sw = 1.0 + rng.uniform(-1.0, 1.0) * P['width_jitter']
            wav = [(rng.uniform(0.4, 1.0) * P['waviness'], rng.uniform(4.0, 12.0),
                    rng.uniform(0.0, TAU)) for _ in range(2)]
            radvar = (rng.uniform(0.5, 1.0) * P['radius_variation'], rng.uniform(3.0, 8.0),
                      rng.uniform(0.0, TAU))
            out.append(Thread(along_x, base, P['half_width'] * sw, P['half_height'] * sw,
                              wav, radvar))
        return out

    warps = make(True, P['n_warp'])
    wefts = make(False, P['n_weft'])
    for i, w in enumerate(warps):
        w.knots = [(f.cross_coord(w.base), 1 if (i + j) % 2 == 0 else -1)
                   for j, f in enumerate(wefts)]
    for j, f in enumerate(wefts):
        f.knots = [(w.cross_coord(f.base), -1 if (i + j) % 2 == 0 else 1)
                   for i, w in enumerate(warps)]
    z_mid = 1.0
    parts = [thread_part(th, L, z_mid, P['amplitude'], P['sides'], P['segments'])
             for th in warps + wefts]
    normalise_placement(parts, xy=False)
    desc = ['Non-tileable plain weave: %d warp threads along x and %d weft threads along y,'
            % (P['n_warp'], P['n_weft']),
            'each a closed tube (elliptic %d-gon cross-section, flat end caps at the swatch border)'
            % P['sides'],
            'running the whole swatch and going over/under alternately (half-cosine profile',
            'between crossings); random spacing jitter, in-plane waviness, radius variation.',
            'Elements 1-%d are the warp threads (ordered by y), elements %d-%d the weft threads'
            % (P['n_warp'], P['n_warp'] + 1, P['n_warp'] + P['n_weft']),
            '(ordered by x); warp i is over weft j where i + j is even (0-based).']
    return parts, seed, P, desc


# ----------------------------------------------------------------------------------------------
# 2. chain mail: European 4-in-1

CHAINMAIL = dict(R=1.0, r=0.18, tilt_deg=35.0, px=1.25, py=1.25, rows=6, cols=6,
                 major_segments=24, minor_segments=8, origin_x=1.0, origin_y=1.2)


def torus_part(c, n, R, r, nu, nv):
    a = (0.0, 1.0, 0.0)             # n never has a y component here
    b = v_cross(n, a)               # (a, b, n) right-handed
    part = Part()
    idx = []
    for i in range(nu):
        u = TAU * i / nu
        e = v_add(v_mul(a, math.cos(u)), v_mul(b, math.sin(u)))
        row = []
        for j in range(nv):
            w = TAU * (j + 0.5) / nv
            p = v_add(c, v_add(v_mul(e, R + r * math.cos(w)), v_mul(n, r * math.sin(w))))
            row.append(part.vert(p))
        idx.append(row)
    for i in range(nu):
        i1 = (i + 1) % nu
        for j in range(nv):
            j1 = (j + 1) % nv
            part.quad(idx[i][j], idx[i1][j], idx[i1][j1], idx[i][j1])
    if part.signed_volume() < 0:
        part.flip()
    return part


def chainmail_rings(P=CHAINMAIL):
    """Ring centres and normals: row k, ring i; rows run along x, alternate rows lean opposite."""
    s, c = math.sin(math.radians(P['tilt_deg'])), math.cos(math.radians(P['tilt_deg']))
    rings = []
    for k in range(P['rows']):
        sign = 1.0 if k % 2 == 0 else -1.0
        for i in range(P['cols']):
            centre = (i * P['px'] + (k % 2) * 0.5 * P['px'], k * P['py'], 0.0)
            rings.append(((k, i), centre, (sign * s, 0.0, c)))
    return rings


def gen_chainmail():
    P = dict(CHAINMAIL)
    parts = [torus_part(c, n, P['R'], P['r'], P['major_segments'], P['minor_segments'])
             for _, c, n in chainmail_rings(P)]
    # ring (0, 0) at a round (x, y) position, lowest point of the mail at z = 0
    lo, _ = extent(parts)
    t = (P['origin_x'], P['origin_y'], -lo[2])
    for p in parts:
        p.translate(t)
    desc = ['European 4-in-1 chain mail: %d rows x %d tori (core radius R, tube radius r).'
            % (P['rows'], P['cols']),
            'Row k, ring i has its core circle centred at',
            '  (origin_x + i*px + (k%%2)*px/2, origin_y + k*py, %s)' % fmt(t[2]),
            'with unit normal ((-1)^k*sin(tilt), 0, cos(tilt)). Every ring links the two rings',
            'diagonally above and the two diagonally below it (linking number +-1) and no other',
            'ring. Translation lattice: (px, 0) and (0, 2*py) (rows alternate tilt).',
            'Elements are in row-major order: element k*cols + i + 1 is row k, ring i.']
    return parts, None, P, desc


# ----------------------------------------------------------------------------------------------
# 3. pebbles: one layer of smooth random blobs

_PHI = (1.0 + math.sqrt(5.0)) / 2.0
_ICO_V = [(-1, _PHI, 0), (1, _PHI, 0), (-1, -_PHI, 0), (1, -_PHI, 0),
          (0, -1, _PHI), (0, 1, _PHI), (0, -1, -_PHI), (0, 1, -_PHI),
          (_PHI, 0, -1), (_PHI, 0, 1), (-_PHI, 0, -1), (-_PHI, 0, 1)]
_ICO_F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
          (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
          (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
          (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]


def geodesic_sphere(freq):
    """Class-I geodesic sphere: each icosahedron face split into freq^2 triangles (unit radius)."""
    base = [v_unit(p) for p in _ICO_V]
    faces = []
    for a, b, c in _ICO_F:
        pa, pb, pc = base[a], base[b], base[c]
        if v_dot(v_cross(v_sub(pb, pa), v_sub(pc, pa)), pa) < 0:
            b, c = c, b
        faces.append((a, b, c))
    verts, key_index, tris = [], {}, []
    for a, b, c in faces:
        grid = {}
        for i in range(freq + 1):
            for j in range(freq + 1 - i):
                w = {a: freq - i - j, b: i, c: j}
                key = tuple(sorted((vid, wt) for vid, wt in w.items() if wt > 0))
                if key not in key_index:
                    p = (0.0, 0.0, 0.0)
                    for vid, wt in key:
                        p = v_add(p, v_mul(base[vid], wt))
                    key_index[key] = len(verts)
                    verts.append(v_unit(p))
                grid[(i, j)] = key_index[key]
        for i in range(freq):
            for j in range(freq - i):
                tris.append((grid[(i, j)], grid[(i + 1, j)], grid[(i, j + 1)]))
                if i + j + 2 <= freq:
                    tris.append((grid[(i + 1, j)], grid[(i + 1, j + 1)], grid[(i, j + 1)]))
    return verts, tris


def gen_pebbles():
    seed = 3
    rng = random.Random(seed)
    P = dict(L=10.0, target=25, darts=2000, shrink_tries=6, shrink=0.92, size_min=0.50,
             size_max=1.00,
             gap=0.10, noise_terms=4, noise_amp=0.06, base_squash=0.8)
    L = P['L']
    spheres = {f: geodesic_sphere(f) for f in (3, 4, 5)}
    # stratified sizes: exactly a factor size_max / size_min between the smallest and largest
    ratio = P['size_max'] / P['size_min']
    sizes = sorted((P['size_min'] * ratio ** ((k + rng.random()) / P['target'])
                    for k in range(P['target'])), reverse=True)
    placed = []                     # (cx, cy, bounding radius, Part)
    for size in sizes:
        for attempt in range(P['shrink_tries']):
            freq = 3 if size < 0.62 else (4 if size < 0.9 else 5)
            sv, sf = spheres[freq]
            sx = size
            sy = size * rng.uniform(0.68, 0.95)
            sz = size * rng.uniform(0.50, 0.72)
            yaw = rng.uniform(0.0, TAU)
            terms = []
            for _ in range(P['noise_terms']):
                d = v_unit((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)))
                terms.append((d, rng.uniform(1.0, 2.4), rng.uniform(0.0, TAU),
                              P['noise_amp'] * rng.uniform(0.5, 1.0)))
            cy_, sy_ = math.cos(yaw), math.sin(yaw)
            pts = []
            for u in sv:
                rad = 1.0 + sum(a * math.sin(f * v_dot(d, u) + ph) for d, f, ph, a in terms)
                x, y, z = u[0] * rad * sx, u[1] * rad * sy, u[2] * rad * sz
                if z < 0.0:
                    z *= P['base_squash']
                pts.append((cy_ * x - sy_ * y, sy_ * x + cy_ * y, z))
            brad = max(math.hypot(p[0], p[1]) for p in pts)
            zmin = min(p[2] for p in pts)
            spot = None
            for _ in range(P['darts']):
                cx = rng.uniform(brad, L - brad)
                cy = rng.uniform(brad, L - brad)
                if all(math.hypot(cx - ox, cy - oy) >= brad + orad + P['gap']
                       for ox, oy, orad, _ in placed):
                    spot = (cx, cy)
                    break
            if spot is not None:
                part = Part()
                for p in pts:
                    part.vert((p[0] + spot[0], p[1] + spot[1], p[2] - zmin))
                part.f = list(sf)
                placed.append((spot[0], spot[1], brad, part))
                break
            size *= P['shrink']         # no room: try a slightly smaller pebble
    # order elements by position (rows of y, then x) for a readable file
    placed.sort(key=lambda e: (round(e[1] / 2.0), e[0]))
    parts = [e[3] for e in placed]
    desc = ['One layer of %d smooth pebbles: geodesic spheres (frequency 3-5 by size) with'
            % len(parts),
            'low-frequency radial noise, scaled to random ellipsoids (sizes vary by a factor 2),',
            'flattened underneath, resting on z = 0, placed by Poisson-disk dart throwing on',
            'their bounding radii with a gap.']
    return parts, seed, P, desc


# ----------------------------------------------------------------------------------------------
# 4. rivets: domed heads on a jittered hexagonal lattice

def rivet_part(cx, cy, rho, hc, hd, sides, phase, arc_steps):
    rs = (rho * rho + hd * hd) / (2.0 * hd)         # sphere radius of the cap
    zc = hc + hd - rs                               # sphere centre height
    phi0 = math.asin(rho / rs)
    profile = [(rho, 0.0), (rho, hc)]
    for k in range(1, arc_steps):
        phi = phi0 * (1.0 - k / arc_steps)
        profile.append((rs * math.sin(phi), zc + rs * math.cos(phi)))
    part = Part()
    rings = []
    for rad, z in profile:
        ring = []
        for m in range(sides):
            a = phase + TAU * m / sides
            ring.append(part.vert((cx + rad * math.cos(a), cy + rad * math.sin(a), z)))
        rings.append(ring)
    bottom = part.vert((cx, cy, 0.0))
    top = part.vert((cx, cy, hc + hd))
    for m in range(sides):
        m1 = (m + 1) % sides
        part.tri(bottom, rings[0][m1], rings[0][m])
        part.tri(top, rings[-1][m], rings[-1][m1])
        for k in range(len(rings) - 1):
            part.quad(rings[k][m], rings[k][m1], rings[k + 1][m1], rings[k + 1][m])
    return part


def gen_rivets():
    seed = 7
    rng = random.Random(seed)
    P = dict(L=10.0, rows=7, per_row=6, spacing=1.55, jitter=0.06, radius=0.58,
             radius_variation=0.18, min_gap=0.12, sides=18, arc_steps=4)
    L, s = P['L'], P['spacing']
    dy = s * math.sqrt(3.0) / 2.0
    x0 = (L - (P['per_row'] - 0.5) * s) / 2.0
    y0 = (L - (P['rows'] - 1) * dy) / 2.0
    heads = []
    for k in range(P['rows']):
        for i in range(P['per_row']):
            cx = x0 + i * s + (0.5 * s if k % 2 else 0.0) + rng.uniform(-1, 1) * P['jitter']
            cy = y0 + k * dy + rng.uniform(-1, 1) * P['jitter']
            rho = P['radius'] * (1.0 + rng.uniform(-1, 1) * P['radius_variation'])
            # never closer than min_gap to a neighbour (shrink if the jitter made it tight)
            for ox, oy, orho, _, _, _ in heads:
                room = math.hypot(cx - ox, cy - oy) - orho - P['min_gap']
                rho = min(rho, room)
            hc = rho * rng.uniform(0.12, 0.22)
            hd = rho * rng.uniform(0.38, 0.60)
            phase = rng.uniform(0.0, TAU / P['sides'])
            heads.append((cx, cy, rho, hc, hd, phase))
    parts = [rivet_part(cx, cy, rho, hc, hd, P['sides'], ph, P['arc_steps'])
             for cx, cy, rho, hc, hd, ph in heads]
    desc = ['%d domed rivet heads (short cylinder + spherical cap, closed underneath) on a'
            % len(parts),
            'jittered hexagonal lattice with random radius, shank and dome heights.']
    return parts, seed, P, desc


# ----------------------------------------------------------------------------------------------
# 5. cobbles: shrunk, rounded Voronoi cells extruded to random heights

def clip_halfplane(poly, nx, ny, c):
    """Keep the part of convex polygon poly (list of (x, y)) with nx*x + ny*y <= c."""
    out = []
    n = len(poly)
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        dp = nx * p[0] + ny * p[1] - c
        dq = nx * q[0] + ny * q[1] - c
        if dp <= 0.0:
            out.append(p)
        if (dp < 0.0 < dq) or (dq < 0.0 < dp):
            t = dp / (dp - dq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def inset_cell(seeds, i, box, inset):
    """Voronoi cell of seed i inside box, with every edge moved inwards by inset."""
    (x0, y0, x1, y1) = box
    poly = [(x0 + inset, y0 + inset), (x1 - inset, y0 + inset),
            (x1 - inset, y1 - inset), (x0 + inset, y1 - inset)]
    sx, sy = seeds[i]
    for j, (tx, ty) in enumerate(seeds):
        if j == i or not poly:
            continue
        dx, dy = tx - sx, ty - sy
        d = math.hypot(dx, dy)
        nx, ny = dx / d, dy / d
        mx, my = (sx + tx) / 2.0, (sy + ty) / 2.0
        poly = clip_halfplane(poly, nx, ny, nx * mx + ny * my - inset)
    return poly


def clean_polygon(poly, min_edge):
    """Merge vertices closer than min_edge (convex polygon, counter-clockwise)."""
    changed = True
    while changed and len(poly) > 3:
        changed = False
        for i in range(len(poly)):
            p, q = poly[i], poly[(i + 1) % len(poly)]
            if math.hypot(q[0] - p[0], q[1] - p[1]) < min_edge:
                m = ((p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0)
                j = (i + 1) % len(poly)
                poly = [m if k == i else poly[k] for k in range(len(poly)) if k != j]
                changed = True
                break
    return poly


def rounded_directions(core, max_step_deg, miter_deg):
    """Directions for offsetting the convex core polygon: (vertex, unit dir, length factor).

    The rounded shape is core (+) disk(r): each corner gets an arc of directions from the
    normal of the incoming edge to the normal of the outgoing edge. Nearly straight corners
    get one mitred direction instead."""
    n = len(core)
    normals = []
    for i in range(n):
        p, q = core[i], core[(i + 1) % n]
        ex, ey = q[0] - p[0], q[1] - p[1]
        d = math.hypot(ex, ey)
        normals.append((ey / d, -ex / d))           # outward for a counter-clockwise polygon
    out = []
    for i in range(n):
        n_in, n_out = normals[i - 1], normals[i]
        a0 = math.atan2(n_in[1], n_in[0])
        turn = math.atan2(n_out[1], n_out[0]) - a0
        while turn < 0.0:
            turn += TAU
        while turn >= TAU:
            turn -= TAU
        if turn < math.radians(miter_deg):
            am = a0 + turn / 2.0
            out.append((core[i], (math.cos(am), math.sin(am)), 1.0 / math.cos(turn / 2.0)))
        else:
            steps = max(1, int(math.ceil(turn / math.radians(max_step_deg))))
            for k in range(steps + 1):
                a = a0 + turn * k / steps
                out.append((core[i], (math.cos(a), math.sin(a)), 1.0))
    return out


def polygon_area(poly):
    return 0.5 * sum(poly[i][0] * poly[(i + 1) % len(poly)][1]
                     - poly[(i + 1) % len(poly)][0] * poly[i][1] for i in range(len(poly)))


def cobble_part(core, rnd, height, bevel, dome, bevel_deg, inner_scales, max_step_deg, miter_deg):
    dirs = rounded_directions(core, max_step_deg, miter_deg)
    m = len(dirs)
    ccx = sum(p[0] for p in core) / len(core)
    ccy = sum(p[1] for p in core) / len(core)
    # vertical profile (offset from the core polygon, height): vertical side, quarter-round bevel
    profile = [(rnd, 0.0), (rnd, height - bevel)]
    for deg in bevel_deg:
        a = math.radians(deg)
        profile.append((rnd - bevel + bevel * math.cos(a), height - bevel + bevel * math.sin(a)))
    part = Part()
    rings = []
    for off, z in profile:
        rings.append([part.vert((p[0] + off * f * d[0], p[1] + off * f * d[1], z))
                      for p, d, f in dirs])
    # slightly domed top: rings scaled towards the centre on a paraboloid, then a fan
    top = [part.v[vi] for vi in rings[-1]]
    for s in inner_scales:
        rings.append([part.vert((ccx + s * (x - ccx), ccy + s * (y - ccy),
                                 height + dome * (1.0 - s * s))) for x, y, _ in top])
    apex = part.vert((ccx, ccy, height + dome))
    base = part.vert((ccx, ccy, 0.0))
    for k in range(m):
        k1 = (k + 1) % m
        part.tri(base, rings[0][k1], rings[0][k])
        for r in range(len(rings) - 1):
            part.quad(rings[r][k], rings[r][k1], rings[r + 1][k1], rings[r + 1][k])
        part.tri(apex, rings[-1][k], rings[-1][k1])
    return part


def gen_cobbles():
    seed = 11
    rng = random.Random(seed)
    P = dict(L=10.0, nx=6, ny=6, jitter=0.40, gap=0.14, rounding=0.17, bevel=0.12,
             bevel_deg=[45.0, 90.0], height_min=0.30, height_max=0.62, dome_min=0.03,
             dome_max=0.10, inner_scales=[0.72, 0.4], arc_step_deg=40.0, miter_deg=8.0,
             min_edge=0.02)
    L = P['L']
    cw, ch = L / P['nx'], L / P['ny']
    seeds = []
    for j in range(P['ny']):
        for i in range(P['nx']):
            seeds.append(((i + 0.5 + rng.uniform(-1, 1) * P['jitter']) * cw,
                          (j + 0.5 + rng.uniform(-1, 1) * P['jitter']) * ch))
    parts = []
    for i in range(len(seeds)):
        core = inset_cell(seeds, i, (0.0, 0.0, L, L), P['gap'] / 2.0 + P['rounding'])
        core = clean_polygon(core, P['min_edge'])
        if len(core) < 3 or polygon_area(core) < 0.05:
            continue
        height = rng.uniform(P['height_min'], P['height_max'])
        dome = rng.uniform(P['dome_min'], P['dome_max'])
        parts.append(cobble_part(core, P['rounding'], height, P['bevel'], dome, P['bevel_deg'],
                                 P['inner_scales'], P['arc_step_deg'], P['miter_deg']))
    desc = ['%d cobble stones: cells of a jittered %d x %d Voronoi diagram (half-plane clipping),'
            % (len(parts), P['nx'], P['ny']),
            'shrunk inwards to leave a gap, corners rounded (Minkowski sum with a disk), top edge',
            'bevelled with a quarter round, slightly domed top, extruded to a random height.']
    return parts, seed, P, desc


# ----------------------------------------------------------------------------------------------
# 6. scales: overlapping shingles, each laid partly over the row below

def scale_part(cx, yb, width, length, thick, slope, top, dome, around, rings):
    """A tilted plate: a half disc at its tip (y = yb) and straight sides up to yb + length. Its top
    falls by `slope` per unit of y from `top` at the tip and is domed across by `dome`; it is
    `thick` thick (straight down). `around` points round the outline, `rings` rings inwards."""
    r = 0.5 * width
    outline = []
    for i in range(around):
        u = i / around
        if u < 0.5:       # the tip: a half circle
            th = math.pi + u / 0.5 * math.pi
            outline.append((cx + r * math.cos(th), yb + r + r * math.sin(th)))
        elif u < 0.65:    # right side, upwards
            outline.append((cx + r, yb + r + (u - 0.5) / 0.15 * (length - r)))
        elif u < 0.85:    # top edge (hidden under the next row)
            outline.append((cx + r - 2.0 * r * (u - 0.65) / 0.2, yb + length))
        else:             # left side, downwards
            outline.append((cx - r, yb + length - (u - 0.85) / 0.15 * (length - r)))
    centre = (cx, yb + 0.55 * length)

    def z_top(x, y):
        d = (x - cx) / r
        return top - slope * (y - yb) + dome * (1.0 - d * d)

    part = Part()
    idx = {}
    for side in (0, 1):   # 0: top surface, 1: bottom surface
        idx[(side, 0, 0)] = part.vert((centre[0], centre[1], z_top(*centre) - side * thick))
        for k in range(1, rings + 1):
            f = k / rings
            for i in range(around):
                x = centre[0] + f * (outline[i][0] - centre[0])
                y = centre[1] + f * (outline[i][1] - centre[1])
                idx[(side, k, i)] = part.vert((x, y, z_top(x, y) - side * thick))
    for side in (0, 1):
        for i in range(around):
            j = (i + 1) % around
            if side == 0:
                part.tri(idx[(0, 0, 0)], idx[(0, 1, i)], idx[(0, 1, j)])
            else:
                part.tri(idx[(1, 0, 0)], idx[(1, 1, j)], idx[(1, 1, i)])
            for k in range(1, rings):
                a, b, c, d = idx[(side, k, i)], idx[(side, k + 1, i)], idx[(side, k + 1, j)], idx[(side, k, j)]
                if side == 0:
                    part.quad(a, b, c, d)
                else:
                    part.quad(a, d, c, b)
    for i in range(around):
        j = (i + 1) % around
        part.quad(idx[(0, rings, i)], idx[(1, rings, i)], idx[(1, rings, j)], idx[(0, rings, j)])
    return part


def gen_scales():
    seed = 11
    rng = random.Random(seed)
    P = dict(rows=8, cols=8, pitch_x=1.25, pitch_y=1.25, width=1.15, length=2.0, thick=0.1,
             slope=0.3, dome=0.075, size_variation=0.03, around=24, rings=3)
    parts = []
    for row in range(P['rows']):
        for col in range(P['cols']):
            cx = (col + (0.5 if row % 2 else 0.0) + 0.5) * P['pitch_x']
            grow = 1.0 + rng.uniform(-1, 1) * P['size_variation']
            parts.append(scale_part(cx, row * P['pitch_y'], P['width'] * grow, P['length'] * grow,
                                    P['thick'], P['slope'], 0.75, P['dome'], P['around'], P['rings']))
    normalise_placement(parts)
    desc = ['%d overlapping scales (shingles) in %d rows of %d, each row shifted by half a pitch.'
            % (len(parts), P['rows'], P['cols']),
            'Each scale is a tilted plate with a rounded tip, domed across; its top half lies under',
            'the tips of the next row, %.2f above it, so the elements overlap in projection but never'
            % (P['slope'] * P['pitch_y'] - P['thick']),
            'touch.']
    return parts, seed, P, desc


# ----------------------------------------------------------------------------------------------
# 7. knots: Truchet knot work (winding strands with over/under gaps)

def strand_part(points, half_w, half_h, sides):
    """A strand along a polyline of (x, y, z of its centre line): a flat-topped elliptic tube that
    keeps its width through bends, its ends capped flat across the line."""
    part = Part()
    n = len(points)
    rings = []
    for k in range(n):
        p = points[k]
        a, b = points[max(k - 1, 0)], points[min(k + 1, n - 1)]
        t = v_unit((b[0] - a[0], b[1] - a[1], 0.0))
        side = (-t[1], t[0], 0.0)
        miter = 1.0
        if 0 < k < n - 1:   # the side grows by 1 / cos(half the turn)
            t0 = v_unit((p[0] - a[0], p[1] - a[1], 0.0))
            miter = 1.0 / max(0.5, v_dot((-t0[1], t0[0], 0.0), side))
        ring = []
        for m in range(sides):
            th_m = TAU * (m + 0.5) / sides
            q = v_add(p, v_add(v_mul(side, half_w * miter * math.cos(th_m)), (0.0, 0.0, half_h * math.sin(th_m))))
            ring.append(part.vert(q))
        rings.append(ring)
    for k in range(n - 1):
        r0, r1 = rings[k], rings[k + 1]
        for m in range(sides):
            m1 = (m + 1) % sides
            part.quad(r0[m], r1[m], r1[m1], r0[m1])
    for k in (0, n - 1):
        ci = part.vert(points[k])
        ring = rings[k]
        for m in range(sides):
            a, b = ring[m], ring[(m + 1) % sides]
            part.tri(ci, a, b) if k == 0 else part.tri(ci, b, a)
    if part.signed_volume() < 0:
        part.flip()
    return part


def polyline_length(pts):
    return sum(v_len(v_sub(pts[k + 1], pts[k])) for k in range(len(pts) - 1))


def cut_polyline(pts, s0, s1, near):
    """The part of polyline pts between arc lengths s0 < s1; a vertex nearer than `near` to a cut
    point is left out (a short last segment would turn the end ring against its neighbour)."""
    out = []
    acc = 0.0
    for k in range(len(pts) - 1):
        a, b = pts[k], pts[k + 1]
        seg = v_len(v_sub(b, a))
        if not out and s0 < acc + seg:
            out.append(v_add(a, v_mul(v_sub(b, a), (s0 - acc) / seg)))
        if s1 <= acc + seg:
            out.append(v_add(a, v_mul(v_sub(b, a), (s1 - acc) / seg)))
            return out
        if out and acc + seg - s0 > near and s1 - (acc + seg) > near:
            out.append(b)
        acc += seg
    return out


def gen_knots():
    seed = 7
    rng = random.Random(seed)
    P = dict(tiles=8, pitch=1.25, half_width=0.16, half_height=0.11, gap=0.2, crossing=0.5,
             bump=0.07, arc_segments=6, sides=8)
    n, pitch, hw, hh, gap = P['tiles'], P['pitch'], P['half_width'], P['half_height'], P['gap']
    half = 0.5 * pitch
    # Tile (i, j): 'A' holds quarter arcs round its lower-left and upper-right corners joining the
    # midpoints of its edges, 'B' round the other two corners; 'X' (never on the border) two
    # straight lines, one passing over the other (rising by `bump`), the other stopping `gap`
    # short of it on both sides. Pieces meet at the edge midpoints (nodes) and join into strands.
    pieces = []   # (node, node, points from the first node to the second)

    def node(i, j, side):
        return {'W': ('v', i, j), 'E': ('v', i + 1, j), 'S': ('h', i, j), 'N': ('h', i, j + 1)}[side]

    def arc(cx, cy, a0, a1):
        m = P['arc_segments']
        return [(cx + half * math.cos(a0 + (a1 - a0) * k / m), cy + half * math.sin(a0 + (a1 - a0) * k / m), hh)
                for k in range(m + 1)]

    for j in range(n):
        for i in range(n):
            x0, y0 = i * pitch, j * pitch
            inner = 0 < i < n - 1 and 0 < j < n - 1
            if inner and rng.random() < P['crossing']:
                x_over = rng.random() < 0.5
                steps = 2 * P['arc_segments']
                rise = [P['bump'] * math.cos(math.pi * (k / steps - 0.5)) ** 2 for k in range(steps + 1)]
                xs = [(x0 + pitch * k / steps, y0 + half, hh + rise[k]) for k in range(steps + 1)]
                ys = [(x0 + half, y0 + pitch * k / steps, hh + rise[k]) for k in range(steps + 1)]
                over, under = (xs, ys) if x_over else (ys, xs)
                a, b = ('W', 'E') if x_over else ('S', 'N')
                c, d = ('S', 'N') if x_over else ('W', 'E')
                pieces.append((node(i, j, a), node(i, j, b), over))
                stop = half - hw - gap
                u0, u1 = (under[0][0], under[0][1], hh), (under[-1][0], under[-1][1], hh)
                dirn = v_unit(v_sub(u1, u0))
                pieces.append((node(i, j, c), ('end', i, j, 0), [u0, v_add(u0, v_mul(dirn, stop))]))
                pieces.append((node(i, j, d), ('end', i, j, 1), [u1, v_sub(u1, v_mul(dirn, stop))]))
            elif rng.random() < 0.5:   # A
                pieces.append((node(i, j, 'S'), node(i, j, 'W'), arc(x0, y0, 0.0, 0.5 * math.pi)))
                pieces.append((node(i, j, 'N'), node(i, j, 'E'), arc(x0 + pitch, y0 + pitch, math.pi, 1.5 * math.pi)))
            else:   # B
                pieces.append((node(i, j, 'S'), node(i, j, 'E'), arc(x0 + pitch, y0, math.pi, 0.5 * math.pi)))
                pieces.append((node(i, j, 'W'), node(i, j, 'N'), arc(x0, y0 + pitch, 1.5 * math.pi, 2.0 * math.pi)))
    at = {}
    for k, (e0, e1, _) in enumerate(pieces):
        at.setdefault(e0, []).append(k)
        at.setdefault(e1, []).append(k)
    used = [False] * len(pieces)

    def walk(k, start):
        """The strand's points from node `start` through piece k onwards, to an end or back to
        `start` (a loop)."""
        pts, frm = [], start
        while True:
            used[k] = True
            e0, e1, p = pieces[k]
            seq, nxt = (p, e1) if e0 == frm else (list(reversed(p)), e0)
            pts.extend(seq if not pts else seq[1:])
            others = [q for q in at[nxt] if q != k]
            if not others or used[others[0]]:
                return pts
            k, frm = others[0], nxt

    strands = []
    for k, (e0, e1, _) in enumerate(pieces):   # open strands: from the border or a stub's end
        for e in (e0, e1):
            if not used[k] and len(at[e]) == 1:
                strands.append(walk(k, e))
    loops = 0
    for k in range(len(pieces)):   # closed loops are broken by a gap, at a random point
        if used[k]:
            continue
        pts = walk(k, pieces[k][0])
        total = polyline_length(pts)
        s = rng.uniform(0.2, 0.8) * total
        # rotate the loop so that the gap lies at its two ends
        near = 0.5 * half * 0.5 * math.pi / P['arc_segments']   # half an arc segment
        tail, head = cut_polyline(pts, s + 0.5 * gap, total, near), cut_polyline(pts, 0.0, s - 0.5 * gap, near)
        strands.append(tail + head[1:])
        loops += 1
    parts = [strand_part(pts, hw, hh, P['sides']) for pts in strands]
    normalise_placement(parts)
    desc = ['Truchet knot work: %d x %d tiles %g wide; a tile holds two quarter arcs round opposite'
            % (n, n, pitch),
            'corners (either pair) or, off the border, a crossing whose under line stops %g short'
            % gap,
            'of the over line, which rises by %g. The arcs join into %d winding strands (flat-topped'
            % (P['bump'], len(parts)),
            'tubes %g wide, %g high, ends capped flat); %d closed loops were broken by a gap of %g.'
            % (2 * hw, 2 * hh, loops, gap)]
    return parts, seed, P, desc

# ----------------------------------------------------------------------------------------------

SWATCHES = [
    ('weave', gen_weave),
    ('chainmail', gen_chainmail),
    ('pebbles', gen_pebbles),
    ('rivets', gen_rivets),
    ('cobbles', gen_cobbles),
    ('scales', gen_scales),
    ('knots', gen_knots),
]


def param_string(P):
    out = []
    for k, v in P.items():
        out.append('%s=%s' % (k, repr(v) if not isinstance(v, float) else ('%g' % v)))
    return ' '.join(out)


def build(name, fn, out_dir):
    parts, seed, P, desc = fn()
    for i, part in enumerate(parts):
        check_part(part, '%s element %d' % (name, i))
    lo, hi = extent(parts)
    size = [hi[k] - lo[k] for k in range(3)]
    if lo[2] < -1e-9 or size[2] > 0.5 * min(size[0], size[1]):
        raise ValueError('%s: not a thin slab in z (extent %r)' % (name, size))
    nf = sum(len(p.f) for p in parts)
    nv = sum(len(p.v) for p in parts)
    header = ['meshquilt example swatch: %s' % name,
              'generator: swatches/generate.py (python3 swatches/generate.py --only %s)' % name,
              'licence: ' + DATA_LICENCE,
              'seed: %s' % ('none (no randomness)' if seed is None else
                            'random.Random(%d)' % seed),
              'parameters: ' + param_string(P),
              'elements: %d closed triangle meshes; vertices: %d; faces: %d' % (len(parts), nv, nf),
              'extent: x [%s, %s] y [%s, %s] z [%s, %s] (z is the thin axis)'
              % (fmt(lo[0]), fmt(hi[0]), fmt(lo[1]), fmt(hi[1]), fmt(lo[2]), fmt(hi[2])),
              ''] + desc
    path = os.path.join(out_dir, name + '.obj')
    write_obj(path, header, parts)
    return path, len(parts), nv, nf, size


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--out', default=os.path.dirname(os.path.abspath(__file__)),
                    help='output directory (default: the directory of this script)')
    ap.add_argument('--only', choices=[n for n, _ in SWATCHES], help='generate one swatch')
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for name, fn in SWATCHES:
        if args.only and name != args.only:
            continue
        path, ne, nv, nf, size = build(name, fn, args.out)
        print('%-10s %3d elements %7d vertices %7d faces  extent %.3f x %.3f x %.3f  -> %s'
              % (name, ne, nv, nf, size[0], size[1], size[2], path))
    return 0


if __name__ == '__main__':
    sys.exit(main())
