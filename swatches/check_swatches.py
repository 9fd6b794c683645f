#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Independent validity checker for the meshquilt example swatches.

    pip install numpy scipy trimesh manifold3d rtree
    python3 swatches/check_swatches.py [--dir swatches] [--only NAME] [--regen]

It re-reads each OBJ from disk and shares no code with generate.py. For every swatch it checks:
  * triangles only, no duplicate or unused vertices, no degenerate faces;
  * every connected component (element) is closed and edge-manifold with consistent winding
    (each directed edge exactly once, its reverse exactly once), vertex-manifold, has positive
    signed volume (outward), and trimesh and manifold3d both accept it as a valid volume;
  * no element intersects itself (exact segment/triangle tests on non-adjacent faces);
  * no two elements intersect or touch: the exact minimum triangle-to-triangle distance between
    every pair of nearby elements is at least 2% of the smaller element size (smallest side of
    its bounding box); manifold3d's boolean intersection volume of every such pair is 0 and its
    min_gap agrees;
  * slab shape: all coordinates >= 0, min z = 0, z extent <= 0.5 * the smaller footprint side;
  * the per-swatch expectations (element and face counts, genus, threads spanning the swatch,
    pebbles resting on z = 0) and, for the chain mail, the core circles extracted from the mesh:
    Gauss linking number +-1 exactly for the diagonal neighbours in adjacent rows (4 per
    interior ring), 0 for every other pair, link graph connected, and core-circle clearance
    > 2r by at least 0.15 r.
--regen additionally reruns generate.py into a temporary directory and requires the output to
be byte-identical to the checked-in files. Exit status 0 only if every check passed.
"""

import argparse
import filecmp
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree

import manifold3d
import trimesh

HERE = os.path.dirname(os.path.abspath(__file__))
NAMES = ['weave', 'chainmail', 'pebbles', 'rivets', 'cobbles', 'scales', 'knots']

EXPECT = {
    'weave': dict(elements=(12, 16), faces=(13000, 17000), genus=0),
    'chainmail': dict(elements=(30, 48), faces=(8000, 15500), genus=1),
    'pebbles': dict(elements=(20, 30), faces=(3500, 8000), genus=0),
    'rivets': dict(elements=(30, 60), faces=(5000, 8000), genus=0),
    'cobbles': dict(elements=(30, 60), faces=(3000, 8000), genus=0),
    'scales': dict(elements=(40, 80), faces=(12000, 24000), genus=0),
    'knots': dict(elements=(15, 40), faces=(8000, 18000), genus=0),
}
GAP_FRACTION = 0.02          # required clearance between elements, relative to element size
SEARCH = 0.5                 # distances above this are reported as "> SEARCH"


class CheckFailed(Exception):
    pass


def require(cond, msg):
    if not cond:
        raise CheckFailed(msg)


# ----------------------------------------------------------------------------------------------
# loading

def load_obj(path):
    verts, faces, header = [], [], []
    with open(path, encoding='ascii') as fh:
        for line in fh:
            tok = line.split()
            if not tok:
                continue
            if tok[0] == '#':
                header.append(line.rstrip('\n'))
            elif tok[0] == 'v':
                require(len(tok) == 4, 'bad vertex line %r' % line)
                verts.append([float(t) for t in tok[1:]])
            elif tok[0] == 'f':
                require(len(tok) == 4, 'non-triangle face %r' % line)
                faces.append([int(t.split('/')[0]) for t in tok[1:]])
            elif tok[0].startswith('#'):
                header.append(line.rstrip('\n'))
            else:
                raise CheckFailed('unexpected OBJ line %r' % line)
    V = np.array(verts, dtype=np.float64)
    F = np.array(faces, dtype=np.int64)
    require(F.min() >= 1 and F.max() <= len(V), 'face index out of range (indices are 1-based)')
    return V, F - 1, header


# ----------------------------------------------------------------------------------------------
# exact geometric primitives (vectorised)

def _dot(a, b):
    return np.einsum('ij,ij->i', a, b)


def seg_seg_dist(p1, q1, p2, q2):
    """Distance between segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection 5.1.9)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = _dot(d1, d1), _dot(d2, d2), _dot(d2, r)
    c, b = _dot(d1, r), _dot(d1, d2)
    denom = a * e - b * b
    with np.errstate(divide='ignore', invalid='ignore'):
        s = np.where(denom > 1e-14 * a * e, np.clip((b * f - c * e) / denom, 0.0, 1.0), 0.0)
        t = (b * s + f) / e
        s = np.where(t < 0.0, np.clip(-c / a, 0.0, 1.0),
                     np.where(t > 1.0, np.clip((b - c) / a, 0.0, 1.0), s))
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p1 + d1 * s[:, None] - p2 - d2 * t[:, None], axis=1)


def point_seg_dist(p, a, b):
    ab = b - a
    t = np.clip(_dot(p - a, ab) / _dot(ab, ab), 0.0, 1.0)
    return np.linalg.norm(p - a - ab * t[:, None], axis=1)


def point_tri_dist(p, a, b, c):
    n = np.cross(b - a, c - a)
    nn = _dot(n, n)
    w = p - a
    h = _dot(w, n) / nn
    pp = p - n * h[:, None]
    lc = _dot(np.cross(b - a, pp - a), n) / nn
    lb = _dot(np.cross(pp - a, c - a), n) / nn
    inside = (lb >= 0) & (lc >= 0) & (lb + lc <= 1)
    edge = np.minimum(np.minimum(point_seg_dist(p, a, b), point_seg_dist(p, b, c)),
                      point_seg_dist(p, c, a))
    return np.where(inside, np.abs(h) * np.sqrt(nn), edge)


def seg_tri_hit(p, q, a, b, c):
    """True where segment pq meets triangle abc (Moller-Trumbore, endpoints included)."""
    e1, e2, d = b - a, c - a, q - p
    h = np.cross(d, e2)
    det = _dot(e1, h)
    ok = np.abs(det) > 1e-15
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = p - a
    u = inv * _dot(s, h)
    qv = np.cross(s, e1)
    v = inv * _dot(d, qv)
    t = inv * _dot(e2, qv)
    return ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0) & (t <= 1)


def tris_intersect(T1, T2):
    """T1, T2: (n, 3, 3). True where the (non-coplanar) triangles intersect."""
    hit = np.zeros(len(T1), dtype=bool)
    for i in range(3):
        j = (i + 1) % 3
        hit |= seg_tri_hit(T1[:, i], T1[:, j], T2[:, 0], T2[:, 1], T2[:, 2])
        hit |= seg_tri_hit(T2[:, i], T2[:, j], T1[:, 0], T1[:, 1], T1[:, 2])
    return hit


def tri_tri_dist(T1, T2):
    """Exact distance between triangles (0 if they intersect)."""
    d = np.full(len(T1), np.inf)
    for i in range(3):
        d = np.minimum(d, point_tri_dist(T1[:, i], T2[:, 0], T2[:, 1], T2[:, 2]))
        d = np.minimum(d, point_tri_dist(T2[:, i], T1[:, 0], T1[:, 1], T1[:, 2]))
        for j in range(3):
            d = np.minimum(d, seg_seg_dist(T1[:, i], T1[:, (i + 1) % 3],
                                           T2[:, j], T2[:, (j + 1) % 3]))
    return np.where(tris_intersect(T1, T2), 0.0, d)


# ----------------------------------------------------------------------------------------------
# per-element checks

class Element:
    def __init__(self, V, F):
        self.V, self.F = V, F
        self.T = V[F]
        self.lo, self.hi = V.min(axis=0), V.max(axis=0)
        self.size = float((self.hi - self.lo).min())
        self.cent = self.T.mean(axis=1)
        self.brad = np.linalg.norm(self.T - self.cent[:, None, :], axis=2).max()
        self.tree = cKDTree(self.cent)
        self._manifold = None

    def manifold(self):
        if self._manifold is None:
            mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(self.V),
                                     tri_verts=np.ascontiguousarray(self.F.astype(np.uint64)))
            self._manifold = manifold3d.Manifold(mesh)
        return self._manifold


def check_element(V, F, label):
    """Returns (Element, genus). V: this element's vertices, F: its faces (local indices)."""
    nv = len(V)
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    key = e[:, 0] * nv + e[:, 1]
    require(len(np.unique(key)) == len(key),
            '%s: a directed edge occurs twice (non-manifold edge or inconsistent winding)' % label)
    rkey = e[:, 1] * nv + e[:, 0]
    require(np.isin(rkey, key).all(), '%s: open boundary edge (element not closed)' % label)
    # vertex-manifold: the faces around each vertex form one fan
    nxt = {}
    for a, b, c in F.tolist():
        nxt.setdefault(a, {})[b] = c
        nxt.setdefault(b, {})[c] = a
        nxt.setdefault(c, {})[a] = b
    require(len(nxt) == nv, '%s: unused vertex' % label)
    for x, ring in nxt.items():
        start = next(iter(ring))
        y, steps = ring[start], 1
        while y != start:
            y, steps = ring[y], steps + 1
            require(steps <= len(ring), '%s: vertex %d not manifold' % (label, x))
        require(steps == len(ring), '%s: vertex %d not manifold (several fans)' % (label, x))
    T = V[F]
    cr = np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0])
    area = 0.5 * np.linalg.norm(cr, axis=1)
    longest = np.max([np.linalg.norm(T[:, i] - T[:, (i + 1) % 3], axis=1) for i in range(3)],
                     axis=0)
    require((area > 1e-10).all() and (area / longest ** 2 > 1e-4).all(),
            '%s: degenerate face (area %.3g)' % (label, area.min()))
    vol = np.einsum('ij,ij->i', T[:, 0], np.cross(T[:, 1], T[:, 2])).sum() / 6.0
    require(vol > 0, '%s: signed volume %.6g not positive (inward orientation)' % (label, vol))
    chi = nv - len(e) // 2 + len(F)
    require(chi % 2 == 0, '%s: odd Euler characteristic' % label)
    genus = (2 - chi) // 2
    # an independent library's opinion
    tm = trimesh.Trimesh(vertices=V, faces=F, process=False)
    require(tm.is_watertight and tm.is_winding_consistent and tm.is_volume,
            '%s: trimesh says not a closed consistent volume' % label)
    require(abs(tm.volume - vol) <= 1e-9 * max(1.0, abs(vol)), '%s: volume mismatch' % label)
    el = Element(V, F)
    m = el.manifold()
    require(m.status() == manifold3d.Error.NoError, '%s: manifold3d status %s' % (label, m.status()))
    require(m.genus() == genus, '%s: manifold3d genus %d != %d' % (label, m.genus(), genus))
    require(abs(m.volume() - vol) <= 1e-6 * max(1.0, vol), '%s: manifold3d volume differs' % label)
    # self-intersection: non-adjacent triangles whose bounding spheres overlap
    pairs = el.tree.query_pairs(2.0 * el.brad, output_type='ndarray')
    if len(pairs):
        Fa, Fb = F[pairs[:, 0]], F[pairs[:, 1]]
        share = (Fa[:, :, None] == Fb[:, None, :]).any(axis=(1, 2))
        pairs = pairs[~share]
        hit = tris_intersect(T[pairs[:, 0]], T[pairs[:, 1]])
        require(not hit.any(), '%s: self-intersection (%d face pairs)' % (label, hit.sum()))
    return el, genus, area.min()


def element_gap(A, B):
    """Exact minimum distance between two elements (SEARCH if larger than SEARCH)."""
    if (np.maximum(A.lo - B.hi, B.lo - A.hi) > SEARCH).any():
        return SEARCH
    cand = A.tree.query_ball_tree(B.tree, A.brad + B.brad + SEARCH)
    ia = np.repeat(np.arange(len(cand)), [len(c) for c in cand])
    if len(ia) == 0:
        return SEARCH
    ib = np.concatenate([np.asarray(c, dtype=np.int64) for c in cand if c])
    best = SEARCH
    for s in range(0, len(ia), 200000):
        d = tri_tri_dist(A.T[ia[s:s + 200000]], B.T[ib[s:s + 200000]])
        best = min(best, float(d.min()))
    return best


# ----------------------------------------------------------------------------------------------
# chain mail: core circles and linking numbers

def core_circle(V):
    c = V.mean(axis=0)
    w, vec = np.linalg.eigh(np.cov((V - c).T))
    n = vec[:, 0]
    d = V - c
    h = d @ n
    inplane = d - np.outer(h, n)
    rad = np.linalg.norm(inplane, axis=1)
    R = rad.mean()
    r = np.sqrt(h ** 2 + (rad - R) ** 2).mean()
    return c, n, R, r


def circle_points(c, n, R, m):
    a = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(n, a)
    t = np.linspace(0.0, 2 * np.pi, m, endpoint=False)[:, None]
    return c + R * (np.cos(t) * a + np.sin(t) * b), (a, b)


def gauss_linking_number(P, Q):
    """Gauss linking integral of closed polygons P, Q, evaluated exactly per segment pair
    (solid-angle formula of Klenin & Langowski 2000)."""
    p1, p2 = P, np.roll(P, -1, axis=0)
    q1, q2 = Q, np.roll(Q, -1, axis=0)
    A1, A2 = np.repeat(p1, len(Q), 0), np.repeat(p2, len(Q), 0)
    B1, B2 = np.tile(q1, (len(P), 1)), np.tile(q2, (len(P), 1))
    r13, r14, r23, r24 = B1 - A1, B2 - A1, B1 - A2, B2 - A2

    def unit(x):
        return x / np.linalg.norm(x, axis=1)[:, None]
    n1, n2 = unit(np.cross(r13, r14)), unit(np.cross(r14, r24))
    n3, n4 = unit(np.cross(r24, r23)), unit(np.cross(r23, r13))
    om = (np.arcsin(np.clip(_dot(n1, n2), -1, 1)) + np.arcsin(np.clip(_dot(n2, n3), -1, 1))
          + np.arcsin(np.clip(_dot(n3, n4), -1, 1)) + np.arcsin(np.clip(_dot(n4, n1), -1, 1)))
    sign = np.sign(_dot(np.cross(B2 - B1, A2 - A1), r13))
    return float((om * sign).sum() / (4 * np.pi))


def disk_crossings(c, n, R, Q):
    """Signed number of crossings of closed polygon Q through the disk (c, n, R)."""
    q2 = np.roll(Q, -1, axis=0)
    s1, s2 = (Q - c) @ n, (q2 - c) @ n
    idx = np.nonzero((s1 < 0) != (s2 < 0))[0]
    tot = 0
    for i in idx:
        x = Q[i] + s1[i] / (s1[i] - s2[i]) * (q2[i] - Q[i])
        if np.linalg.norm(x - c) < R:
            tot += 1 if s2[i] > s1[i] else -1
    return tot


def circle_circle_dist(c1, n1, R1, c2, n2, R2):
    def dist_to_1(p):
        d = p - c1
        h = d @ n1
        rad = np.linalg.norm(d - np.outer(h, n1), axis=1)
        return np.sqrt(h ** 2 + (rad - R1) ** 2)
    _, (a, b) = circle_points(c2, n2, R2, 4)

    def f(t):
        return dist_to_1((c2 + R2 * (np.cos(t) * a + np.sin(t) * b))[None, :])[0]
    ts = np.linspace(0.0, 2 * np.pi, 2048, endpoint=False)
    P = c2 + R2 * (np.cos(ts)[:, None] * a + np.sin(ts)[:, None] * b)
    d = dist_to_1(P)
    best = d.min()
    for i in np.argsort(d)[:8]:
        res = minimize_scalar(f, bounds=(ts[i] - 0.01, ts[i] + 0.01), method='bounded',
                              options=dict(xatol=1e-12))
        best = min(best, res.fun)
    return best


def check_chainmail(elements, log):
    cores = [core_circle(el.V) for el in elements]
    R = np.mean([c[2] for c in cores])
    r = np.mean([c[3] for c in cores])
    # rows: cluster centres by y
    order = np.argsort([c[0][1] for c in cores])
    rows, cur = [], [order[0]]
    for i in order[1:]:
        if cores[i][0][1] - cores[cur[-1]][0][1] > 0.3 * R:
            rows.append(cur)
            cur = []
        cur.append(i)
    rows.append(cur)
    rows = [sorted(row, key=lambda i: cores[i][0][0]) for row in rows]
    where = {}
    for k, row in enumerate(rows):
        for j, i in enumerate(row):
            where[i] = (k, j)
    px = np.median([cores[row[j + 1]][0][0] - cores[row[j]][0][0]
                    for row in rows for j in range(len(row) - 1)])
    py = np.median([cores[rows[k + 1][0]][0][1] - cores[rows[k][0]][0][1]
                    for k in range(len(rows) - 1)])
    polys = [circle_points(c, n, Rc, 160)[0] for c, n, Rc, _ in cores]
    n = len(cores)
    links = np.zeros((n, n), dtype=int)
    min_clear = np.inf
    pairs = 0
    for i in range(n):
        for j in range(i + 1, n):
            ci, cj = cores[i], cores[j]
            if np.linalg.norm(ci[0] - cj[0]) > ci[2] + cj[2] + 2 * r + 1e-9:
                continue            # bounding spheres of the tori apart: unlinked, disjoint
            pairs += 1
            lk = gauss_linking_number(polys[i], polys[j])
            lk_int = int(round(lk))
            require(abs(lk - lk_int) < 1e-6, 'rings %d,%d: Gauss integral %.6f not integral'
                    % (i, j, lk))
            require(lk_int == disk_crossings(ci[0], ci[1], ci[2], polys[j]),
                    'rings %d,%d: Gauss integral disagrees with disk crossings' % (i, j))
            links[i, j] = links[j, i] = lk_int
            d = circle_circle_dist(ci[0], ci[1], ci[2], cj[0], cj[1], cj[2])
            min_clear = min(min_clear, d - 2 * r)
    for i in range(n):
        ki, ji = where[i]
        for j in range(n):
            if i == j:
                continue
            kj = where[j][0]
            dx = abs(cores[j][0][0] - cores[i][0][0])
            neighbour = abs(ki - kj) == 1 and abs(dx - px / 2) < 0.1 * px
            require(abs(links[i, j]) == (1 if neighbour else 0),
                    'rings %s and %s: linking number %d, expected %s'
                    % (where[i], where[j], links[i, j], '+-1' if neighbour else '0'))
    deg = (links != 0).sum(axis=1)
    interior = [i for i in range(n) if 0 < where[i][0] < len(rows) - 1
                and 0 < where[i][1] < len(rows[where[i][0]]) - 1]
    require(all(deg[i] == 4 for i in interior), 'an interior ring does not have 4 links')
    require(deg.max() <= 4 and deg.min() >= 1, 'link degrees out of range')
    ncomp, _ = scipy.sparse.csgraph.connected_components(scipy.sparse.csr_matrix(links != 0))
    require(ncomp == 1, 'the rings do not form one connected piece of mail (%d pieces)' % ncomp)
    require(min_clear >= 0.15 * r, 'core circles too close: clearance %.4f < 0.15 r' % min_clear)
    log('  chain mail: %d rows of %s rings, lattice px = %.4f, py = %.4f (translation period '
        '%.4f x %.4f), R = %.4f, r = %.4f' % (len(rows), '/'.join(str(len(x)) for x in rows),
                                              px, py, px, 2 * py, R, r))
    log('  chain mail: %d ring pairs tested, %d linked pairs (all |lk| = 1), %d interior rings '
        'with exactly 4 links, link graph connected' % (pairs, int((links != 0).sum() // 2),
                                                         len(interior)))
    log('  chain mail: min core-circle distance - 2r = %.4f = %.2f r (required >= 0.15 r)'
        % (min_clear, min_clear / r))
    return dict(links=int((links != 0).sum() // 2), interior=len(interior),
                clearance_r=min_clear / r)


# ----------------------------------------------------------------------------------------------

def check_swatch(path, name, log):
    V, F, header = load_obj(path)
    exp = EXPECT.get(name, {})
    require(any('licence' in h.lower() for h in header), 'no licence line in the header')
    uniq = np.unique(V, axis=0)
    require(len(uniq) == len(V), '%d duplicate vertices' % (len(V) - len(uniq)))
    nv = len(V)
    adj = scipy.sparse.coo_matrix((np.ones(3 * len(F)),
                                   (F[:, [0, 1, 2]].ravel(), F[:, [1, 2, 0]].ravel())),
                                  shape=(nv, nv))
    ncomp, lab = scipy.sparse.csgraph.connected_components(adj, directed=False)
    used = np.zeros(nv, dtype=bool)
    used[F.ravel()] = True
    require(used.all(), 'unused vertices')
    flab = lab[F[:, 0]]
    elements, genera, min_area = [], [], np.inf
    for c in range(ncomp):
        vids = np.nonzero(lab == c)[0]
        remap = -np.ones(nv, dtype=np.int64)
        remap[vids] = np.arange(len(vids))
        el, g, a = check_element(V[vids], remap[F[flab == c]], '%s element %d' % (name, c))
        elements.append(el)
        genera.append(g)
        min_area = min(min_area, a)
    # slab and footprint
    lo, hi = V.min(axis=0), V.max(axis=0)
    ext = hi - lo
    require((lo >= -1e-9).all(), 'negative coordinates: min %s' % lo)
    require(abs(lo[2]) <= 1e-9, 'min z is %.6g, expected 0' % lo[2])
    require(ext[2] <= 0.5 * min(ext[0], ext[1]), 'not a thin slab in z: extent %s' % ext)
    # expectations
    if 'elements' in exp:
        require(exp['elements'][0] <= ncomp <= exp['elements'][1],
                '%d elements, expected %s' % (ncomp, exp['elements']))
        require(exp['faces'][0] <= len(F) <= exp['faces'][1],
                '%d faces, expected %s' % (len(F), exp['faces']))
        require(all(g == exp['genus'] for g in genera), 'element genus %s, expected %d'
                % (sorted(set(genera)), exp['genus']))
    if name == 'weave':
        for el in elements:
            spans_x = el.lo[0] <= lo[0] + 1e-6 and el.hi[0] >= hi[0] - 1e-6
            spans_y = el.lo[1] <= lo[1] + 1e-6 and el.hi[1] >= hi[1] - 1e-6
            require(spans_x or spans_y, 'a thread does not run the whole length of the swatch')
    if name == 'pebbles':
        require(all(abs(el.lo[2]) <= 1e-9 for el in elements), 'a pebble does not rest on z = 0')
    # pairwise clearance
    min_gap, min_rel, n_pairs, n_bool = SEARCH, np.inf, 0, 0
    for i in range(ncomp):
        for j in range(i + 1, ncomp):
            A, B = elements[i], elements[j]
            if (np.maximum(A.lo - B.hi, B.lo - A.hi) > SEARCH).any():
                continue
            n_pairs += 1
            g = element_gap(A, B)
            need = GAP_FRACTION * min(A.size, B.size)
            require(g >= need, 'elements %d and %d: gap %.5f < %.5f' % (i, j, g, need))
            min_gap = min(min_gap, g)
            min_rel = min(min_rel, g / min(A.size, B.size))
            if (np.maximum(A.lo - B.hi, B.lo - A.hi) < 0).all():   # bounding boxes overlap
                n_bool += 1
                mi = A.manifold() ^ B.manifold()
                require(mi.volume() == 0.0 and mi.is_empty(),
                        'elements %d and %d: manifold3d intersection volume %.3g'
                        % (i, j, mi.volume()))
                mg = A.manifold().min_gap(B.manifold(), SEARCH)
                require(abs(mg - g) <= 1e-6 + 1e-3 * g,
                        'elements %d and %d: manifold3d min_gap %.6f != %.6f' % (i, j, mg, g))
    log('  %d element pairs within %.2f checked exactly (%d also by manifold3d boolean '
        'intersection + min_gap); min gap %.4f (%.1f%% of element size)'
        % (n_pairs, SEARCH, n_bool, min_gap, 100 * min_rel))
    extra = check_chainmail(elements, log) if name == 'chainmail' else {}
    fpe = [len(el.F) for el in elements]
    return dict(name=name, faces=len(F), verts=len(V), elements=ncomp, closed=ncomp,
                ext=ext, fpe=(min(fpe), max(fpe)), genus=sorted(set(genera)), gap=min_gap,
                gap_rel=min_rel, min_area=min_area, **extra)


def main(argv=None):
    ap = argparse.ArgumentParser(description='validate the meshquilt swatches')
    ap.add_argument('--dir', default=HERE)
    ap.add_argument('--only', choices=NAMES)
    ap.add_argument('--regen', action='store_true',
                    help='also check that generate.py reproduces the files byte for byte')
    args = ap.parse_args(argv)
    names = [args.only] if args.only else NAMES
    failed, rows = [], []
    for name in names:
        path = os.path.join(args.dir, name + '.obj')
        print('%s: %s' % (name, path))
        try:
            rows.append(check_swatch(path, name, print))
            print('  OK')
        except (CheckFailed, OSError) as e:
            print('  FAILED: %s' % e)
            failed.append(name)
    if args.regen:
        with tempfile.TemporaryDirectory() as tmp:
            cmd = [sys.executable, os.path.join(HERE, 'generate.py'), '--out', tmp]
            if args.only:
                cmd += ['--only', args.only]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            for name in names:
                same = filecmp.cmp(os.path.join(tmp, name + '.obj'),
                                   os.path.join(args.dir, name + '.obj'), shallow=False)
                print('regenerate %s: %s' % (name, 'byte-identical' if same else 'DIFFERENT'))
                if not same:
                    failed.append(name + ' (regeneration)')
    print()
    print('| swatch | faces | vertices | elements | closed | extent x / y / z | faces/element '
          '| genus | min gap (rel.) |')
    print('|---|---:|---:|---:|---:|---|---|---|---|')
    for r in rows:
        print('| %s | %d | %d | %d | %d | %.3f / %.3f / %.3f | %d-%d | %s | %.3f (%.1f%%) |'
              % (r['name'], r['faces'], r['verts'], r['elements'], r['closed'], r['ext'][0],
                 r['ext'][1], r['ext'][2], r['fpe'][0], r['fpe'][1],
                 ','.join(str(g) for g in r['genus']), r['gap'], 100 * r['gap_rel']))
    print()
    n_ok = len(names) - len(set(n.split()[0] for n in failed))
    print('%d passed, %d failed' % (n_ok, len(names) - n_ok))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
