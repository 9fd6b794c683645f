// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/kernel.h"

#include "core/intersect.h"
#include "meshquilt/errors.h"
#include "quilt/deform.h"
#include "quilt/fill.h"
#include "quilt/swatch.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>
#include <Eigen/Eigenvalues>
#include <maxflow.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

namespace meshquilt::quilt {

namespace {

/// A closed mesh's Euler characteristic is 2 (genus 0): V - E + F = V - F / 2 over used vertices.
bool euler_genus_zero(const Mesh& m) {
    std::vector<char> used(m.vertices.size(), 0);
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(f[k])] = 1;
    const auto v = std::count(used.begin(), used.end(), 1);
    return 2 * v - static_cast<long>(m.faces.size()) == 4;
}

/// Largest change of an element's area that deformation may make (Section 2.6 moves an element
/// half-way to its partner, which may be of another size).
constexpr double kMaxAreaChange = 1.3;
/// ... and of a strand's (is_strand: its width changes with its area; at 1.3, 5% of a draft knots
/// swatch's strands came out more than 15% thinner, 40 x 40, seed 1).
constexpr double kMaxStrandAreaChange = 1.1;

/// A stitched compact element may reach (xy box diagonal) at most this much beyond the larger of
/// its two halves' elements.
constexpr double kMaxStitchReach = 1.15;
/// A stitch deforms its element within this many mean edge lengths of the seam (see stitch_elements).
constexpr double kSeamReach = 6.0;
/// The inflating step of a thread seam's relaxation against its shrinking one (Taubin's mu over
/// lambda, negated): a little more than 1, so that the smoothing keeps a tube's cross-section
/// (relax_seam).
constexpr double kTaubinInflate = 1.06;
/// A thread is flat (flat_thread) when its half perimeter squared over its cross-section's area is
/// at least this: a flat strip w x h gives (w + h)^2 / (w h), 8 at w = 5.8 h (a circle pi). Measured
/// on whole threads (their undulation counts): the bundled weave 5.07, a weave of threads 0.8 of
/// their spacing wide 6.1, a 2/2 twill of them 5.95, the public Truchet knots 4.2-5.5 and
/// Hitomezashi loops 4.7-12.9, ribbons quilted as strips (SwatchData::solidified) 21.6.
constexpr double kFlatThread = 8.0;

/// A blob squeezed clear of its partner must keep this share of its footprint (see plan_patch).
constexpr double kMinSqueezedArea = 0.6;
/// ... and is pushed by at most this share of its width at a time.
constexpr double kMaxSqueezePush = 1.0 / 3.0;

/// Rings pair as partners only within this ratio of their xy diagonals (see plan_patch).
constexpr double kRingPartnerSize = 1.5;

using Side = std::function<bool(double, double)>;

bool in_overlap(const Side& ov, const Vec3& p) { return ov(p.x(), p.y()); }

Vec3 centroid(const Mesh& m, int f) { return face_centroid(m, static_cast<std::size_t>(f)); }

double mean_edge(const Mesh& m, int f) {
    const Tri& t = m.faces[static_cast<std::size_t>(f)];
    const auto& V = m.vertices;
    return ((V[t[0]] - V[t[1]]).norm() + (V[t[1]] - V[t[2]]).norm() + (V[t[2]] - V[t[0]]).norm()) / 3.0;
}

std::uint64_t edge_key(int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); }

/// Faces adjacent across each edge: adjacency[f][k] is the face across edge (f[k], f[k+1]) or -1.
std::vector<std::array<int, 3>> face_adjacency(const Mesh& m) {
    std::unordered_map<std::uint64_t, int> owner;
    owner.reserve(m.faces.size() * 3);
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) owner[edge_key(m.faces[f][k], m.faces[f][(k + 1) % 3])] = static_cast<int>(f);
    std::vector<std::array<int, 3>> adj(m.faces.size(), {-1, -1, -1});
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            auto it = owner.find(edge_key(m.faces[f][(k + 1) % 3], m.faces[f][k]));
            if (it != owner.end()) adj[f][static_cast<std::size_t>(k)] = it->second;
        }
    return adj;
}

// ---------------------------------------------------------------------------------------------
// Projected-overlap test (Section 2.5): do the xy projections of two elements overlap?
// Both are rasterised on a common grid over the intersection of their footprints.

/// The pixels of the grid with corner (x0, y0), square `pixel` and nx x ny cells that the xy
/// projection of `m` covers (pixel centres inside a face; a face smaller than a pixel marks the
/// pixel it lies in, a vertical face its box unless `area_only`), handed to `visit` until it
/// returns true. With `area_only` vertical faces mark nothing: a closed element's projection is
/// covered by its other faces, and the box of a slanted wall would cover much more.
bool raster_xy(const Mesh& m, double x0, double y0, double pixel, int nx, int ny, const std::function<bool(int, int)>& visit,
               bool area_only = false) {
    const double x1 = x0 + nx * pixel, y1 = y0 + ny * pixel;
    for (const Tri& f : m.faces) {
        const Vec3& p = m.vertices[f[0]];
        const Vec3& q = m.vertices[f[1]];
        const Vec3& r = m.vertices[f[2]];
        const double fx0 = std::min({p.x(), q.x(), r.x()}), fx1 = std::max({p.x(), q.x(), r.x()});
        const double fy0 = std::min({p.y(), q.y(), r.y()}), fy1 = std::max({p.y(), q.y(), r.y()});
        if (fx1 < x0 || fx0 > x1 || fy1 < y0 || fy0 > y1) continue;
        const int i0 = std::max(0, static_cast<int>(std::floor((fx0 - x0) / pixel)));
        const int i1 = std::min(nx - 1, static_cast<int>(std::floor((fx1 - x0) / pixel)));
        const int j0 = std::max(0, static_cast<int>(std::floor((fy0 - y0) / pixel)));
        const int j1 = std::min(ny - 1, static_cast<int>(std::floor((fy1 - y0) / pixel)));
        const double area = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        if (area_only && std::abs(area) < 1e-300) continue;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double cx = x0 + (i + 0.5) * pixel, cy = y0 + (j + 0.5) * pixel;
                bool inside;
                if (std::abs(area) < 1e-300) {
                    inside = true;  // vertical triangle: its footprint is a segment; count its box
                } else {
                    const double w0 = (q.x() - cx) * (r.y() - cy) - (q.y() - cy) * (r.x() - cx);
                    const double w1 = (r.x() - cx) * (p.y() - cy) - (r.y() - cy) * (p.x() - cx);
                    const double w2 = (p.x() - cx) * (q.y() - cy) - (p.y() - cy) * (q.x() - cx);
                    inside = area > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
                    // Triangles smaller than a pixel still mark the pixel they lie in.
                    inside = inside || (i0 == i1 && j0 == j1);
                }
                if (inside && visit(i, j)) return true;
            }
    }
    return false;
}

bool projections_overlap(const Mesh& a, const Mesh& b, double pixel) {
    Box3 ba = bounding_box(a), bb = bounding_box(b);
    const double x0 = std::max(ba.min.x(), bb.min.x()), x1 = std::min(ba.max.x(), bb.max.x());
    const double y0 = std::max(ba.min.y(), bb.min.y()), y1 = std::min(ba.max.y(), bb.max.y());
    if (x0 > x1 || y0 > y1) return false;
    pixel = std::max({pixel, (x1 - x0) / 512.0, (y1 - y0) / 512.0, 1e-12});
    const int nx = static_cast<int>(std::floor((x1 - x0) / pixel)) + 1;
    const int ny = static_cast<int>(std::floor((y1 - y0) / pixel)) + 1;
    std::vector<char> mask(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
    raster_xy(a, x0, y0, pixel, nx, ny, [&](int i, int j) {
        mask[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)] = 1;
        return false;
    });
    return raster_xy(b, x0, y0, pixel, nx, ny,
                     [&](int i, int j) { return mask[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)] != 0; });
}

// ---------------------------------------------------------------------------------------------
// Graph cut of one element (Section 2.7, Eq. 7).

struct CutResult {
    std::vector<char> keep;      ///< per face: SOURCE side (kept)
    std::vector<char> anchored;  ///< per face: linked to SOURCE with infinite weight
};

void maxflow_error(const char* msg) { throw BackendFailure(std::string("graph cut: ") + msg); }

/// Appends the selected faces of `m` to `dst` with their own (compacted) vertices.
void append_faces(const Mesh& m, const std::vector<char>& sel, Mesh& dst) {
    std::vector<int> map(m.vertices.size(), -1);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        if (!sel[f]) continue;
        Tri t;
        for (int k = 0; k < 3; ++k) {
            int& id = map[m.faces[f][k]];
            if (id < 0) {
                id = static_cast<int>(dst.vertices.size());
                dst.vertices.push_back(m.vertices[m.faces[f][k]]);
            }
            t[k] = id;
        }
        dst.faces.push_back(t);
    }
}

/// Faces an element must keep: those farther than `reach` from its partner (only this element
/// provides geometry there) and, with `side`, those outside its side of the overlap.
std::vector<char> anchored_faces(const Mesh& m, const TriangleIndex& partner, double reach, const Side* side) {
    std::vector<char> out(m.faces.size(), 0);
    const Box3 partner_box = bounding_box(partner.mesh());  // farther than `reach` from the box is farther from the partner
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Vec3 c = centroid(m, static_cast<int>(f));
        Box3 at;
        at.extend(c);
        out[f] = (side && !in_overlap(*side, c)) || !partner_box.overlaps(at, reach) || !partner.within(c, reach);
    }
    return out;
}

/// Cuts element `a` against its partner `b` (Section 2.7). Both elements must keep the faces only
/// they provide (`a_anchor`, `b_anchor`: outside the overlap, or away from the partner). Every point p
/// gets phi(p) = dist(p, a's anchored part) - dist(p, b's anchored part): the SOURCE rule links faces
/// with phi < -band (a's own ground) to SOURCE, the SINK rule faces with phi > band (b's ground) to
/// SINK, and the min cut with Eq. 7 weights places the cut inside the band. Because both elements are
/// cut by the same field, their cuts meet. When `b_keep` is given (b was cut first), faces of `a`
/// near kept parts of `b` are pushed towards deletion and those near deleted parts towards keeping.
CutResult cut_element(const Mesh& a, const TriangleIndex& b_index, const std::vector<char>& a_anchor, const std::vector<char>& b_anchor,
                      const KernelParams& params, const std::vector<char>* b_keep) {
    const double unit = params.metric.unit;
    const double pair_distance = params.anchor_reach * unit;
    const double band = unit;
    const std::size_t nf = a.faces.size();
    const auto adj_a = face_adjacency(a);

    // Distances to b matter only around faces the cut may take (not anchored): an edge between two
    // anchored faces links two SOURCE nodes and is never cut, whatever its weight.
    std::vector<char> used(a.vertices.size(), 0);
    for (std::size_t f = 0; f < nf; ++f)
        if (!a_anchor[f])
            for (int k = 0; k < 3; ++k) used[a.faces[f][k]] = 1;
    std::vector<double> dist_b(a.vertices.size(), 0.0);
    for (std::size_t v = 0; v < a.vertices.size(); ++v)
        if (used[v]) dist_b[v] = b_index.closest(a.vertices[v]).distance;

    CutResult res;
    res.anchored = a_anchor;
    res.keep.assign(nf, 1);
    Mesh a_own, b_own;
    append_faces(a, a_anchor, a_own);
    append_faces(b_index.mesh(), b_anchor, b_own);
    const TriangleIndex a_own_index(a_own), b_own_index(b_own);
    std::vector<int> partner_face(nf, -1);
    std::vector<double> partner_dist(nf, 0.0);
    std::vector<char> sink(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) {
        if (res.anchored[f]) continue;
        const Vec3 c = centroid(a, static_cast<int>(f));
        const ClosestHit h = b_index.closest(c);
        partner_face[f] = h.face;
        partner_dist[f] = h.distance;
        const double phi = a_own_index.closest(c).distance - b_own_index.closest(c).distance;
        if (phi < -band) res.anchored[f] = 1;
        else if (phi > band) sink[f] = 1;
    }

    using Graph = maxflow::Graph<double, double, double>;
    Graph g(static_cast<int>(nf), static_cast<int>(nf * 3 / 2 + 1), maxflow_error);
    g.add_node(static_cast<int>(nf));
    const double inf = 1e15;
    double mean_w = 0.0;
    int count_w = 0;
    for (std::size_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int o = adj_a[f][static_cast<std::size_t>(k)];
            if (o <= static_cast<int>(f)) continue;
            const int vi = a.faces[f][k], vj = a.faces[f][(k + 1) % 3];
            // Eq. 7, lengths in units of the swatch's mean edge length.
            const double w = (1.0 + (a.vertices[vi] - a.vertices[vj]).norm() / unit) *
                             (1.0 + dist_b[vi] / unit + dist_b[vj] / unit);
            g.add_edge(static_cast<int>(f), o, w, w);
            mean_w += w;
            ++count_w;
        }
    mean_w = count_w > 0 ? mean_w / count_w : 1.0;
    for (std::size_t f = 0; f < nf; ++f) {
        if (res.anchored[f]) g.add_tweights(static_cast<int>(f), inf, 0);
        else if (sink[f]) g.add_tweights(static_cast<int>(f), 0, inf);
    }
    if (b_keep) {
        const double w = 100.0 * mean_w;
        for (std::size_t f = 0; f < nf; ++f) {
            if (res.anchored[f] || sink[f] || partner_dist[f] > pair_distance) continue;
            if ((*b_keep)[static_cast<std::size_t>(partner_face[f])]) g.add_tweights(static_cast<int>(f), 0, w);
            else g.add_tweights(static_cast<int>(f), w, 0);
        }
    }
    g.maxflow();
    for (std::size_t f = 0; f < nf; ++f) res.keep[f] = g.what_segment(static_cast<int>(f)) == Graph::SOURCE;

    return res;
}

// ---------------------------------------------------------------------------------------------
// Stitching helpers.

/// The faces with keep[f] that belong to an edge-connected component containing an anchored face.
std::vector<char> anchored_components(const Mesh& m, const CutResult& cut) {
    const auto adj = face_adjacency(m);
    std::vector<char> out(m.faces.size(), 0);
    std::vector<int> stack;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        if (cut.keep[f] && cut.anchored[f] && !out[f]) {
            out[f] = 1;
            stack.push_back(static_cast<int>(f));
            while (!stack.empty()) {
                const int g = stack.back();
                stack.pop_back();
                for (int o : adj[static_cast<std::size_t>(g)])
                    if (o >= 0 && cut.keep[static_cast<std::size_t>(o)] && !out[static_cast<std::size_t>(o)]) {
                        out[static_cast<std::size_t>(o)] = 1;
                        stack.push_back(o);
                    }
            }
        }
    return out;
}


Vec3 closest_on_polyline(const std::vector<Vec3>& V, const std::vector<int>& loop, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    Vec3 out = p;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec3& a = V[loop[i]];
        const Vec3& b = V[loop[(i + 1) % loop.size()]];
        const Vec3 ab = b - a;
        const double len2 = ab.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        const Vec3 q = a + t * ab;
        const double d = (q - p).squaredNorm();
        if (d < best) {
            best = d;
            out = q;
        }
    }
    return out;
}

double loop_distance(const std::vector<Vec3>& V, const std::vector<int>& la, const std::vector<int>& lb) {
    double sum = 0.0;
    for (int v : la) sum += (closest_on_polyline(V, lb, V[v]) - V[v]).norm();
    return sum / static_cast<double>(la.size());
}

/// Joins loop `a` (of the old part, in its faces' direction) and loop `b` (of the new part, in its
/// faces' direction) by a strip of triangles. The two parts are complementary, so `a` reversed runs
/// along `b`. False when the loops run the wrong way round.
bool zip_loops(const std::vector<Vec3>& V, std::vector<int> a, const std::vector<int>& b, std::vector<Tri>* faces) {
    std::reverse(a.begin(), a.end());
    const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
    auto nearest_in_b = [&](const Vec3& p) {
        int best = 0;
        double bd = std::numeric_limits<double>::infinity();
        for (int j = 0; j < m; ++j) {
            const double d = (V[b[j]] - p).squaredNorm();
            if (d < bd) {
                bd = d;
                best = j;
            }
        }
        return best;
    };
    // Direction check: the nearest points of b should advance with a.
    double agreement = 0.0;
    for (int i = 0; i < n; ++i) {
        const int j = nearest_in_b(V[a[i]]);
        const Vec3 da = V[a[(i + 1) % n]] - V[a[i]];
        const Vec3 db = V[b[(j + 1) % m]] - V[b[(j + m - 1) % m]];
        agreement += da.dot(db);
    }
    if (agreement <= 0.0) return false;
    const int j0 = nearest_in_b(V[a[0]]);
    std::vector<int> q(static_cast<std::size_t>(m));
    for (int j = 0; j < m; ++j) q[static_cast<std::size_t>(j)] = b[(j0 + j) % m];
    int i = 0, j = 0;
    while (i < n || j < m) {
        const int pi = a[i % n], pi1 = a[(i + 1) % n];
        const int qj = q[static_cast<std::size_t>(j % m)], qj1 = q[static_cast<std::size_t>((j + 1) % m)];
        const bool advance_a = j == m || (i < n && (V[pi1] - V[qj]).squaredNorm() < (V[pi] - V[qj1]).squaredNorm());
        if (advance_a) {
            faces->push_back(Tri(pi, pi1, qj));
            ++i;
        } else {
            faces->push_back(Tri(pi, qj1, qj));
            ++j;
        }
    }
    return true;
}

/// Uniform Laplacian relaxation of the vertices within `rings` rings of `seed` vertices, `iterations`
/// steps. With `keep_tube`, each shrinking step is followed by an inflating one (Taubin 1995,
/// lambda|mu smoothing with mu = -kTaubinInflate lambda): plain Laplacian steps pull a thin tube in
/// towards its axis, and a stitched thread's seam came out pinched, a tenth narrower than the
/// thread (session 31). Compact elements (pebbles, scales) keep the plain steps, which smooth a
/// seam's ragged strip more.
void relax_seam(Mesh& m, const std::vector<int>& seeds, int rings, int iterations, bool keep_tube) {
    std::vector<std::vector<int>> nbr(m.vertices.size());
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) {
            nbr[f[k]].push_back(f[(k + 1) % 3]);
            nbr[f[k]].push_back(f[(k + 2) % 3]);
        }
    for (auto& N : nbr) {
        std::sort(N.begin(), N.end());
        N.erase(std::unique(N.begin(), N.end()), N.end());
    }
    std::vector<int> depth(m.vertices.size(), -1);
    std::vector<int> frontier = seeds, band;
    for (int s : seeds) depth[s] = 0;
    band = seeds;
    for (int r = 1; r <= rings; ++r) {
        std::vector<int> next;
        for (int v : frontier)
            for (int w : nbr[v])
                if (depth[w] < 0) {
                    depth[w] = r;
                    next.push_back(w);
                    band.push_back(w);
                }
        frontier = std::move(next);
    }
    std::sort(band.begin(), band.end());
    const int steps = keep_tube ? 2 * iterations : iterations;
    for (int it = 0; it < steps; ++it) {
        const double sign = keep_tube && it % 2 == 1 ? -kTaubinInflate : 1.0;
        std::vector<Vec3> moved(band.size());
        for (std::size_t k = 0; k < band.size(); ++k) {
            const int v = band[k];
            Vec3 avg = Vec3::Zero();
            for (int w : nbr[v]) avg += m.vertices[w];
            avg /= static_cast<double>(std::max<std::size_t>(1, nbr[v].size()));
            // Seam vertices move fully, the band fades out towards its edge.
            const double weight = 0.5 * (1.0 - static_cast<double>(depth[v]) / (rings + 1));
            moved[k] = m.vertices[v] + sign * weight * (avg - m.vertices[v]);
        }
        for (std::size_t k = 0; k < band.size(); ++k) m.vertices[band[k]] = moved[k];
    }
}

/// A closed genus-0 element that is neither a thread nor a strand (`strand`: a pebble, a stone, a
/// rivet head; not a ring, not knot work).
bool is_blob(const Mesh& m, bool strand) {
    return !strand && !is_elongated(m) && is_closed_oriented(m) && euler_genus_zero(m);
}

/// Is `m`, of swatch element `source` (-1: unknown), a strand (KernelParams::strands)? Of a swatch
/// without strands, nothing is (no raster drawn for a pebble of unknown source).
bool strand_of(const Mesh& m, int source, const KernelParams& params) {
    if (!params.strands.empty()) {
        if (source >= 0 && static_cast<std::size_t>(source) < params.strands.size()) return params.strands[static_cast<std::size_t>(source)] != 0;
        if (std::find(params.strands.begin(), params.strands.end(), 1) == params.strands.end()) return false;
    }
    return is_strand(m);
}

int count_components(const Mesh& m) {
    std::vector<int> parent(m.vertices.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    std::vector<char> used(m.vertices.size(), 0);
    for (const Tri& f : m.faces) {
        for (int k = 0; k < 3; ++k) used[f[k]] = 1;
        parent[find(f[0])] = find(f[1]);
        parent[find(f[1])] = find(f[2]);
    }
    int c = 0;
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
        if (used[v] && find(static_cast<int>(v)) == static_cast<int>(v)) ++c;
    return c;
}

}  // namespace

/// Boundary loops, each in the direction its faces traverse it. False when a vertex has several
/// outgoing boundary edges (the boundary is not a set of simple loops).
bool boundary_loops(const Mesh& m, std::vector<std::vector<int>>* loops) {
    std::unordered_map<std::uint64_t, char> directed;
    directed.reserve(m.faces.size() * 3);
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) directed[edge_key(f[k], f[(k + 1) % 3])] = 1;
    std::map<int, int> next;
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) {
            const int a = f[k], b = f[(k + 1) % 3];
            if (directed.count(edge_key(b, a))) continue;
            if (!next.emplace(a, b).second) return false;
        }
    std::map<int, char> done;
    for (const auto& [start, unused] : next) {
        if (done.count(start)) continue;
        std::vector<int> loop;
        int v = start;
        while (!done.count(v)) {
            done[v] = 1;
            loop.push_back(v);
            auto it = next.find(v);
            if (it == next.end()) return false;
            v = it->second;
        }
        if (v != start || loop.size() < 3) return false;
        loops->push_back(std::move(loop));
    }
    return true;
}

// -------------------------------------------------------------------------------------------------

bool is_closed_oriented(const Mesh& m) {
    std::unordered_map<std::uint64_t, int> count;
    count.reserve(m.faces.size() * 3);
    for (const Tri& f : m.faces) {
        if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return false;
        for (int k = 0; k < 3; ++k)
            if (++count[edge_key(f[k], f[(k + 1) % 3])] > 1) return false;
    }
    for (const auto& [key, c] : count) {
        const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
        if (!count.count(edge_key(b, a))) return false;
    }
    return !m.faces.empty();
}

double projected_overlap_share(const Mesh& a, const Mesh& b, int resolution) {
    const Box3 ba = bounding_box(a), bb = bounding_box(b);
    if (a.faces.empty() || b.faces.empty() || ba.max.x() < bb.min.x() || bb.max.x() < ba.min.x() || ba.max.y() < bb.min.y() ||
        bb.max.y() < ba.min.y())
        return 0.0;
    const double pixel = std::max({ba.size().x(), ba.size().y(), 1e-12}) / std::max(resolution, 1);
    const int nx = static_cast<int>(std::floor(ba.size().x() / pixel)) + 1, ny = static_cast<int>(std::floor(ba.size().y() / pixel)) + 1;
    std::vector<char> mask(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
    auto cell = [&](int i, int j) -> char& { return mask[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)]; };
    raster_xy(
        a, ba.min.x(), ba.min.y(), pixel, nx, ny,
        [&](int i, int j) {
            cell(i, j) = 1;
            return false;
        },
        true);
    const auto covered = std::count(mask.begin(), mask.end(), 1);
    raster_xy(
        b, ba.min.x(), ba.min.y(), pixel, nx, ny,
        [&](int i, int j) {
            if (cell(i, j) == 1) cell(i, j) = 2;
            return false;
        },
        true);
    return covered ? static_cast<double>(std::count(mask.begin(), mask.end(), 2)) / static_cast<double>(covered) : 0.0;
}

double selected_area(const Mesh& m, const std::vector<char>& sel) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        if (sel[f]) a += face_area(m, f);
    return a;
}

namespace {

using HullKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

}  // namespace

std::vector<Vec2> xy_hull(const Mesh& m) {
    std::vector<char> used(m.vertices.size(), 0);
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) used[f[k]] = 1;
    std::vector<HullKernel::Point_2> pts, hull;
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
        if (used[v]) pts.emplace_back(m.vertices[v].x(), m.vertices[v].y());
    CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
    std::vector<Vec2> out;
    for (const auto& p : hull) out.emplace_back(p.x(), p.y());
    return out;
}

namespace {

}  // namespace

double polygon_area(const std::vector<Vec2>& h) {
    double a = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const Vec2& p = h[i];
        const Vec2& q = h[(i + 1) % h.size()];
        a += p.x() * q.y() - p.y() * q.x();
    }
    return 0.5 * std::abs(a);
}

namespace {

/// The shortest push of hull `b` along an edge normal of either hull that leaves `gap` between it and
/// hull `a`: `depth` <= 0 when they are that far apart already. `axis` points from `a` to `b`.
struct Push {
    Vec2 axis = Vec2::Zero();
    double depth = -1e300;
    double lo = 0.0, hi = 0.0;  ///< b's extent along the axis
};
Push shortest_push(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double gap) {
    Push best;
    best.depth = 1e300;
    auto range = [](const std::vector<Vec2>& h, const Vec2& n, double* lo, double* hi) {
        *lo = 1e300;
        *hi = -1e300;
        for (const Vec2& p : h) {
            *lo = std::min(*lo, n.dot(p));
            *hi = std::max(*hi, n.dot(p));
        }
    };
    for (const std::vector<Vec2>* h : {&a, &b})
        for (std::size_t i = 0; i < h->size(); ++i) {
            const Vec2 e = (*h)[(i + 1) % h->size()] - (*h)[i];
            if (e.norm() < 1e-300) continue;
            const Vec2 n0 = Vec2(e.y(), -e.x()).normalized();
            for (const Vec2& n : {n0, Vec2(-n0)}) {
                double a_lo, a_hi, b_lo, b_hi;
                range(a, n, &a_lo, &a_hi);
                range(b, n, &b_lo, &b_hi);
                const double depth = a_hi + gap - b_lo;
                if (depth < best.depth) best = {n, depth, b_lo, b_hi};
            }
        }
    return best;
}

}  // namespace

void push_side(Mesh& m, const Vec2& axis, double lo, double hi, double depth) {
    const double width = hi - lo;
    if (!(width > 0.0)) return;
    // s -> s + depth (1 - t)^2, t = (s - lo) / width in [0, 1]: the side at `lo` moves by `depth`, the
    // far side stays; the derivative 1 - 2 depth (1 - t) / width is positive while depth < width / 2.
    for (Vec3& v : m.vertices) {
        const Vec2 xy(v.x(), v.y());
        const double t = std::clamp((axis.dot(xy) - lo) / width, 0.0, 1.0);
        const Vec2 moved = xy + axis * (depth * (1.0 - t) * (1.0 - t));
        v.x() = moved.x();
        v.y() = moved.y();
    }
}

bool squeeze_clear(Mesh& m, const std::vector<const Mesh*>& others, double gap, double min_area, double max_push) {
    const Box3 box = bounding_box(m);
    std::vector<std::vector<Vec2>> near;
    for (const Mesh* o : others)
        if (o && !o->faces.empty() && box.overlaps(bounding_box(*o), gap + 0.5 * std::max(box.size().x(), box.size().y())))
            near.push_back(xy_hull(*o));
    return squeeze_clear(m, near, gap, min_area, max_push);
}

bool squeeze_clear(Mesh& m, const std::vector<std::vector<Vec2>>& others, double gap, double min_area, double max_push) {
    std::vector<Vec2> hull = xy_hull(m);
    const double area0 = polygon_area(hull);
    if (hull.size() < 3 || !(area0 > 0.0)) return false;
    const Box3 box = bounding_box(m);
    // Hulls whose box is farther than the gap plus a third of the element's width cannot be reached.
    const double pad = gap + std::max(box.size().x(), box.size().y()) / 3.0;
    std::vector<const std::vector<Vec2>*> near;
    for (const auto& o : others) {
        if (o.size() < 3) continue;
        Box3 ob;
        for (const Vec2& p : o) ob.extend(Vec3(p.x(), p.y(), box.min.z()));
        if (box.overlaps(ob, pad)) near.push_back(&o);
    }
    const double tiny = 1e-9 * std::max(box.size().x(), box.size().y());
    for (int round = 0; round <= 8; ++round) {
        Push deepest;
        for (const auto* o : near) {
            const Push p = shortest_push(*o, hull, gap);
            if (p.depth > deepest.depth) deepest = p;
        }
        if (deepest.depth <= tiny) return polygon_area(hull) >= min_area * area0;
        if (round == 8) return false;
        const double width = deepest.hi - deepest.lo;
        if (!(width > 0.0) || deepest.depth > max_push * width) return false;
        push_side(m, deepest.axis, deepest.lo, deepest.hi, deepest.depth);
        hull = xy_hull(m);
    }
    return false;
}

double slenderness(const Mesh& m) {
    if (m.faces.empty()) return 0.0;
    const Box3 box = bounding_box(m);
    const double side = std::max(box.size().x(), box.size().y());
    if (!(side > 0.0) || !std::isfinite(side)) return 0.0;
    // The footprint on a raster of kSlenderPixels along the box's longer side, one pixel of margin
    // (Coverage: a pixel is covered when its centre lies in a face's projection).
    const double px = side / kSlenderPixels;
    Coverage cov(box.min.x() - px, box.min.y() - px, box.max.x() + px, box.max.y() + px, px);
    cov.add(m);
    // Squared distance to the nearest pixel outside the footprint (0 there, infinity inside).
    const int nx = cov.nx(), ny = cov.ny();
    std::vector<double> sq(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0.0);
    long covered = 0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            if (cov.covered(i, j)) {
                sq[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)] = std::numeric_limits<double>::infinity();
                ++covered;
            }
    if (covered == 0) return 0.0;
    squared_distance_transform(sq, nx, ny);
    const double deepest = std::sqrt(*std::max_element(sq.begin(), sq.end()));
    // A pixel is inside when its centre is: the nearest outside centre lies just beyond the
    // footprint's border, and the deepest pixel near the widest disc's centre (both within about
    // half a pixel): twice its distance is the width of the widest disc in the footprint.
    const double w = 2.0 * deepest * px;
    if (!(w > 0.0)) return 0.0;
    return static_cast<double>(covered) * px * px / (w * w);
}

bool is_strand(const Mesh& m) {
    return !is_elongated(m) && is_closed_oriented(m) && euler_genus_zero(m) && slenderness(m) >= kSlender;
}

bool is_elongated(const Mesh& m) {
    if (!m.faces.empty() && 2 * m.vertices.size() <= m.faces.size()) return false;
    const Vec3 d = bounding_box(m).size();
    return std::max(d.x(), d.y()) > 3.0 * std::max(std::min(d.x(), d.y()), 1e-300);
}

/// A thread's width: its area over twice its length (a flat tube's cross-section is about twice as
/// long as it is wide), the length taken along its principal axis in xy.
double thread_width(const Mesh& m) {
    if (m.vertices.empty()) return 0.0;
    Vec2 mean = Vec2::Zero();
    for (const Vec3& v : m.vertices) mean += v.head<2>();
    mean /= static_cast<double>(m.vertices.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const Vec3& v : m.vertices) cov += (v.head<2>() - mean) * (v.head<2>() - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    const Vec2 axis = eig.eigenvectors().col(1);
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const Vec3& v : m.vertices) {
        lo = std::min(lo, axis.dot(v.head<2>()));
        hi = std::max(hi, axis.dot(v.head<2>()));
    }
    return mesh_area(m) / std::max(2.0 * (hi - lo), 1e-300);
}

bool flat_thread(const Mesh& m) {
    double volume = 0.0;
    for (const Tri& f : m.faces) volume += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]]));
    volume = std::fabs(volume) / 6.0;
    return volume > 0.0 && thread_width(m) * mesh_area(m) / (2.0 * volume) >= kFlatThread;
}

/// Beyond the paper: the targets of a thread's constraints (Eq. 5-6) replaced by their sources moved
/// by the mean shift of all constraints within one thread width (thread_width), so that the
/// deformation moves the thread's cross-sections whole. Vertex by vertex, a thread's sides are
/// pulled half-way to its partner's nearest points, and where the partner is narrower or offset the
/// averaged sides draw in: threads came out 5% narrower wherever two patches met (planar weave,
/// 40 x 40, seed 2: median width 0.760 against the swatch's 0.794, a tenth of the cross-sections
/// below 0.67; session 32).
void whole_section_targets(const Mesh& m, std::vector<PointConstraint>* cons) {
    const std::size_t n = cons->size();
    if (n == 0) return;
    const double r = thread_width(m);
    std::vector<Vec3> source(n), shift(n);
    for (std::size_t k = 0; k < n; ++k) {
        const PointConstraint& c = (*cons)[k];
        source[k] = c.bary[0] * m.vertices[static_cast<std::size_t>(c.v[0])] + c.bary[1] * m.vertices[static_cast<std::size_t>(c.v[1])] +
                    c.bary[2] * m.vertices[static_cast<std::size_t>(c.v[2])];
        shift[k] = c.target - source[k];
    }
    // A sweep over the sources in order along the axis (x or y) they spread most along.
    Box3 spread;
    for (const Vec3& p : source) spread.extend(p);
    const int a = spread.size().x() >= spread.size().y() ? 0 : 1;
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return source[i][a] < source[j][a] || (source[i][a] == source[j][a] && i < j); });
    std::size_t first = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = source[order[i]];
        while (source[order[first]][a] < p[a] - r) ++first;
        Vec3 sum = Vec3::Zero();
        int count = 0;
        for (std::size_t j = first; j < n && source[order[j]][a] <= p[a] + r; ++j)
            if ((source[order[j]] - p).squaredNorm() <= r * r) {
                sum += shift[order[j]];
                ++count;
            }
        (*cons)[order[i]].target = p + sum / static_cast<double>(count);
    }
}

double element_gap(const Mesh& a, const Box3& a_box, const Mesh& b, double cap) {
    if (!a_box.overlaps(bounding_box(b), cap)) return cap;
    // At most about 2,000 vertices of each side (a stride), so large elements stay cheap.
    const std::size_t sa = std::max<std::size_t>(1, a.vertices.size() / 2000), sb = std::max<std::size_t>(1, b.vertices.size() / 2000);
    double best = cap * cap;
    for (std::size_t j = 0; j < b.vertices.size(); j += sb) {
        const Vec3& v = b.vertices[j];
        if (((a_box.min.array() - cap) > v.array()).any() || (v.array() > (a_box.max.array() + cap)).any()) continue;
        for (std::size_t i = 0; i < a.vertices.size(); i += sa) best = std::min(best, (a.vertices[i] - v).squaredNorm());
    }
    return std::sqrt(best);
}

bool stitch_elements(const Mesh& c_out, const Mesh& c_in, const Overlap& ov, const KernelParams& params, Mesh* result, std::string* why,
                     StitchOutcome* outcome, OwnAreas* own) {
    auto fail = [why](const char* reason) {
        if (why) *why = reason;
        return false;
    };
    const TriangleIndex idx_out(c_out), idx_in(c_in);
    const double reach = params.anchor_reach * params.metric.unit;
    const std::vector<char> anchor_out = anchored_faces(c_out, idx_in, reach, &ov.old_side);
    const std::vector<char> anchor_in = anchored_faces(c_in, idx_out, reach, nullptr);
    if (own) {
        own->old_part = selected_area(c_out, anchor_out);
        own->new_part = selected_area(c_in, anchor_in);
    }
    const bool out_free = std::find(anchor_out.begin(), anchor_out.end(), 1) == anchor_out.end();
    const bool in_free = std::find(anchor_in.begin(), anchor_in.end(), 1) == anchor_in.end();
    if (outcome) *outcome = StitchOutcome::Stitched;
    if (out_free) {  // the old element lies entirely where the new one is: replace it (Section 2.7)
        if (outcome) *outcome = StitchOutcome::UseNew;
        *result = c_in;
        return true;
    }
    if (in_free) {  // the new element lies entirely where the old one is: keep the old
        if (outcome) *outcome = StitchOutcome::KeepOld;
        *result = c_out;
        return true;
    }
    // Beyond the paper: open elements (a cap, a leaf, a ribbon modelled as one sheet) are not
    // joined. Their cut parts hold the element's own rim among their boundary loops, and zipping
    // the loops of two such parts joined rim to rim: the only stitches of open elements that
    // passed the closed-result test below were such crumpled blobs. The element that covers more
    // of its own ground stays whole instead (plan_patch), as when a stitch fails.
    if (!is_closed_oriented(c_out) || !is_closed_oriented(c_in)) return fail("an open element is not stitched");
    CutResult cut_out = cut_element(c_out, idx_in, anchor_out, anchor_in, params, nullptr);
    CutResult cut_in = cut_element(c_in, idx_out, anchor_in, anchor_out, params, &cut_out.keep);
    const std::vector<char> sel_out = anchored_components(c_out, cut_out);
    const std::vector<char> sel_in = anchored_components(c_in, cut_in);
    const auto kept_out = std::count(sel_out.begin(), sel_out.end(), 1);
    const auto kept_in = std::count(sel_in.begin(), sel_in.end(), 1);
    if (kept_out == 0 || kept_in == 0) return fail("a cut kept nothing");

    Mesh part_out, part_in;
    append_faces(c_out, sel_out, part_out);
    append_faces(c_in, sel_in, part_in);
    std::vector<std::vector<int>> loops_out, loops_in;
    if (!boundary_loops(part_out, &loops_out) || !boundary_loops(part_in, &loops_in)) return fail("cut boundary is not simple loops");
    if (loops_out.empty()) return fail("cut left no boundary");
    if (loops_out.size() != loops_in.size()) return fail("different numbers of cut loops");

    // One mesh holding both parts; loops of the new part are shifted by the old part's vertex count.
    Mesh joined = part_out;
    const int offset = static_cast<int>(joined.vertices.size());
    for (const Vec3& v : part_in.vertices) joined.vertices.push_back(v);
    for (const Tri& f : part_in.faces) joined.faces.push_back(f + Tri::Constant(offset));
    for (auto& l : loops_in)
        for (int& v : l) v += offset;

    // Pair loops greedily by mean distance.
    struct Cand { double d; std::size_t i, j; };
    std::vector<Cand> cands;
    for (std::size_t i = 0; i < loops_out.size(); ++i)
        for (std::size_t j = 0; j < loops_in.size(); ++j)
            cands.push_back({0.5 * (loop_distance(joined.vertices, loops_out[i], loops_in[j]) +
                                    loop_distance(joined.vertices, loops_in[j], loops_out[i])), i, j});
    std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) {
        return x.d < y.d || (x.d == y.d && (x.i < y.i || (x.i == y.i && x.j < y.j)));
    });
    std::vector<int> partner(loops_out.size(), -1);
    std::vector<char> taken(loops_in.size(), 0);
    for (const Cand& c : cands) {
        if (partner[c.i] >= 0 || taken[c.j]) continue;
        // Loops farther apart than a few edge lengths are not two sides of one cut.
        if (c.d > 4.0 * params.metric.unit) {
            return fail("cut loops too far apart");
        }
        partner[c.i] = static_cast<int>(c.j);
        taken[c.j] = 1;
    }

    // Averaged boundary points as constraints, deformation with Eq. 5.
    std::vector<PointConstraint> cons;
    for (std::size_t i = 0; i < loops_out.size(); ++i) {
        const auto& la = loops_out[i];
        const auto& lb = loops_in[static_cast<std::size_t>(partner[i])];
        for (int v : la) cons.push_back(PointConstraint::vertex(v, 0.5 * (joined.vertices[v] + closest_on_polyline(joined.vertices, lb, joined.vertices[v]))));
        for (int v : lb) cons.push_back(PointConstraint::vertex(v, 0.5 * (joined.vertices[v] + closest_on_polyline(joined.vertices, la, joined.vertices[v]))));
    }
    // Beyond the paper: when two threads are stitched only the seam's neighbourhood moves; farther
    // than kSeamReach mean edge lengths from every cut loop each half stays exactly where it is, clear
    // of the threads crossing it there. (With the loops alone constrained, Eq. 5 carries each half
    // whole towards the seam. Compact elements still do, as in the paper: see plan_patch.)
    std::vector<char> far(joined.vertices.size(), 0);
    if (is_elongated(c_out) && is_elongated(c_in)) {
        std::vector<Vec3> loop_points;
        for (const auto& l : loops_out)
            for (int v : l) loop_points.push_back(joined.vertices[v]);
        for (const auto& l : loops_in)
            for (int v : l) loop_points.push_back(joined.vertices[v]);
        const double r2 = std::pow(kSeamReach * params.metric.unit, 2);
        for (std::size_t v = 0; v < joined.vertices.size(); ++v) {
            const Vec3& p = joined.vertices[v];
            bool near = false;
            for (const Vec3& q : loop_points)
                if ((p - q).squaredNorm() < r2) {
                    near = true;
                    break;
                }
            far[v] = !near;
        }
    }
    joined.vertices = laplacian_deform(joined, cons, params.mu, far);

    std::vector<int> seam;
    for (std::size_t i = 0; i < loops_out.size(); ++i) {
        const auto& lb = loops_in[static_cast<std::size_t>(partner[i])];
        if (!zip_loops(joined.vertices, loops_out[i], lb, &joined.faces)) {
            return fail("cut loops run the same way");
        }
        seam.insert(seam.end(), loops_out[i].begin(), loops_out[i].end());
        seam.insert(seam.end(), lb.begin(), lb.end());
    }
    relax_seam(joined, seam, params.smoothing_rings, 4,
               is_elongated(c_out) && is_elongated(c_in) && (params.keep_thread_widths || flat_thread(c_out) || flat_thread(c_in)));

    if (!is_closed_oriented(joined)) return fail("joined element not closed");
    if (count_components(joined) != 1) return fail("joined element in pieces");
    if (count_self_intersections(joined, 1) > 0) return fail("joined element self-intersects");
    *result = std::move(joined);
    return true;
}

PatchPlan plan_patch(const std::vector<OldElement>& old, const std::vector<NewElement>& fresh, const Overlap& ov,
                     const KernelParams& params, const std::vector<Mesh>& obstacles) {
    PatchPlan plan;
    if (fresh.empty()) return plan;

    // All new elements in one index; faces remember their element and local face.
    std::vector<const Mesh*> parts;
    for (const NewElement& ne : fresh) parts.push_back(&ne.mesh);
    const ElementMesh combined = concatenate(parts);
    const Mesh& all = combined.mesh;
    const std::vector<int>& elem_of_face = combined.element_of_face;
    std::vector<int> local_face(all.faces.size());
    for (std::size_t f = 0, first = 0; f < all.faces.size(); ++f) {
        if (f > 0 && elem_of_face[f] != elem_of_face[f - 1]) first = f;
        local_face[f] = static_cast<int>(f - first);
    }
    const TriangleIndex index(all);

    // Section 2.5: vertex-face pairs over the overlap, pruned; element relations.
    struct Pair { int vertex; int face; Vec3 bary; Vec3 point; };
    // Per old element (in parallel, merged in order so the result does not depend on scheduling).
    std::vector<std::map<int, std::vector<Pair>>> per_old(old.size());
    tbb::parallel_for(std::size_t(0), old.size(), [&](std::size_t o) {
        const Mesh& m = old[o].mesh;
        const std::vector<Vec3> normals = vertex_normals(m);
        std::vector<char> used(m.vertices.size(), 0);
        for (const Tri& f : m.faces)
            for (int k = 0; k < 3; ++k) used[f[k]] = 1;
        for (std::size_t v = 0; v < m.vertices.size(); ++v) {
            if (!used[v] || !in_overlap(ov.old_side, m.vertices[v])) continue;
            double score = 0.0;
            const ClosestHit h = index.best_match(m.vertices[v], normals[v], params.metric, &score);
            if (normals[v].dot(index.face_normal(h.face)) < 0.0) continue;           // opposite normals
            if (h.distance > params.prune_factor * mean_edge(all, h.face)) continue;  // far pair
            const int e = elem_of_face[static_cast<std::size_t>(h.face)];
            per_old[o][e].push_back({static_cast<int>(v), local_face[static_cast<std::size_t>(h.face)], h.bary, h.point});
        }
    });
    std::map<std::pair<int, int>, std::vector<Pair>> relations;  // (old index, new index) -> pairs
    for (std::size_t o = 0; o < old.size(); ++o)
        for (auto& [e, pairs] : per_old[o]) relations[{static_cast<int>(o), e}] = std::move(pairs);
    // Projected-overlap test removes false relations; then one partner per element, strongest first.
    // Beyond the paper: a ring pairs only with a ring of its genus and about its size (interlocked
    // rings touch: a big ring of a Japanese 4-in-1 mail and a small ring through it share many
    // close vertex-face pairs, and deforming one into the other breaks both).
    struct Shape { long genus; double diagonal; };
    auto shape = [](const Mesh& m) {
        const Vec3 d = bounding_box(m).size();
        const long v = static_cast<long>(m.vertices.size()), f = static_cast<long>(m.faces.size());
        return Shape{2 * v <= f ? (2 - v + f / 2) / 2 : 0, std::hypot(d.x(), d.y())};
    };
    std::vector<Shape> old_shape, new_shape;
    for (const OldElement& oe : old) old_shape.push_back(shape(oe.mesh));
    for (const NewElement& ne : fresh) new_shape.push_back(shape(ne.mesh));
    auto compatible = [&](int o, int e) {
        const Shape& a = old_shape[static_cast<std::size_t>(o)];
        const Shape& b = new_shape[static_cast<std::size_t>(e)];
        if (a.genus == 0 && b.genus == 0) return true;
        return a.genus == b.genus && std::max(a.diagonal, b.diagonal) <= kRingPartnerSize * std::min(a.diagonal, b.diagonal);
    };
    struct Rel { std::size_t count; int o, e; };
    std::vector<Rel> rels;
    for (const auto& [key, pairs] : relations)
        if (compatible(key.first, key.second) && projections_overlap(old[static_cast<std::size_t>(key.first)].mesh, fresh[static_cast<std::size_t>(key.second)].mesh, 0.5 * params.metric.unit))
            rels.push_back({pairs.size(), key.first, key.second});
    std::sort(rels.begin(), rels.end(), [](const Rel& a, const Rel& b) {
        return a.count > b.count || (a.count == b.count && (a.o < b.o || (a.o == b.o && a.e < b.e)));
    });
    std::vector<int> partner_of_old(old.size(), -1), partner_of_new(fresh.size(), -1);
    for (const Rel& r : rels) {
        if (partner_of_old[static_cast<std::size_t>(r.o)] >= 0 || partner_of_new[static_cast<std::size_t>(r.e)] >= 0) continue;
        partner_of_old[static_cast<std::size_t>(r.o)] = r.e;
        partner_of_new[static_cast<std::size_t>(r.e)] = r.o;
    }

    // Deformation and merging of each corresponding pair, in parallel; results kept in pair order.
    std::vector<std::size_t> matched;
    for (std::size_t o = 0; o < old.size(); ++o)
        if (partner_of_old[o] >= 0) matched.push_back(o);
    plan.correspondences = static_cast<int>(matched.size());
    std::vector<PatchPlan::Change> merged_changes(matched.size()), squeezed(matched.size()), remnants(matched.size());
    std::vector<std::string> failures(matched.size());
    // The old elements and obstacles, for the test of a stitched thread's first try (below): does
    // it cross an old element but its own? (The new patch's elements are not tested: some of them
    // will not land, and the stage tests what does.) Built only when two threads correspond.
    ElementCollider standing;
    std::vector<int> standing_id(old.size(), -1);
    if (params.keep_thread_widths && std::any_of(matched.begin(), matched.end(), [&](std::size_t o) {
            return is_elongated(old[o].mesh) && is_elongated(fresh[static_cast<std::size_t>(partner_of_old[o])].mesh);
        })) {
        for (std::size_t o = 0; o < old.size(); ++o) standing_id[o] = standing.add(old[o].mesh);
        for (const Mesh& ob : obstacles) standing.add(ob);
    }
    tbb::parallel_for(std::size_t(0), matched.size(), [&](std::size_t k) {
        const std::size_t o = matched[k];
        const int e = partner_of_old[o];
        const auto& pairs = relations.at({static_cast<int>(o), e});
        // Section 2.6: deform both elements towards the averaged targets (Eq. 5 and Eq. 6).
        std::vector<PointConstraint> cons_out, cons_in;
        const Mesh& mo = old[o].mesh;
        const Mesh& mi = fresh[static_cast<std::size_t>(e)].mesh;
        for (const Pair& p : pairs) {
            const Vec3 c = 0.5 * (mo.vertices[static_cast<std::size_t>(p.vertex)] + p.point);
            cons_out.push_back(PointConstraint::vertex(p.vertex, c));
            const Tri& f = mi.faces[static_cast<std::size_t>(p.face)];
            cons_in.push_back({{f[0], f[1], f[2]}, p.bary, c});
        }
        std::vector<char> fixed_out, fixed_in;
        const bool threads = is_elongated(mo) && is_elongated(mi);
        if (threads) {
            // Beyond the paper: two threads deform only on contested ground; elsewhere each stays
            // where it is, clear of the threads crossing it there. (Eq. 5-6 alone would shift a whole
            // thread along with its overlapping end, into its crossings. Compact elements move whole
            // and keep their shape, as in the paper; anchoring part of a pebble or a ring would
            // stretch it.)
            fixed_out.resize(mo.vertices.size());
            fixed_in.resize(mi.vertices.size());
            for (std::size_t v = 0; v < mo.vertices.size(); ++v) fixed_out[v] = !in_overlap(ov.old_side, mo.vertices[v]);
            for (std::size_t v = 0; v < mi.vertices.size(); ++v) fixed_in[v] = !in_overlap(ov.new_side, mi.vertices[v]);
        }
        auto crosses_old = [&](const Mesh& m) { return standing.collides(m, {standing_id[o]}); };

        // Section 2.7: merge.
        PatchPlan::Change ch;
        ch.old_id = old[o].id;
        Mesh out_d = mo, in_d = mi, merged;
        std::string why;
        StitchOutcome outcome = StitchOutcome::Stitched;
        OwnAreas own;
        bool stitched = false;
        // Beyond the paper: two threads deform first with whole cross-sections (whole_section_targets),
        // which keeps their width; the paper's targets are the second try when that stitch fails or
        // crosses an old element (a thread moved whole towards its partner may reach into a crossing
        // thread that the paper's targets, narrowing it, would have cleared).
        for (int attempt = threads && params.keep_thread_widths ? 0 : 1; attempt < 2 && !stitched; ++attempt) {
            std::vector<PointConstraint> whole_out, whole_in;  // the first try's targets
            if (attempt == 0) {
                whole_out = cons_out;
                whole_in = cons_in;
                whole_section_targets(mo, &whole_out);
                whole_section_targets(mi, &whole_in);
            }
            out_d.vertices = laplacian_deform(mo, attempt == 0 ? whole_out : cons_out, params.mu, fixed_out);
            in_d.vertices = laplacian_deform(mi, attempt == 0 ? whole_in : cons_in, params.mu, fixed_in);
            merged = Mesh();
            why.clear();
            outcome = StitchOutcome::Stitched;
            own = OwnAreas();
            stitched = stitch_elements(out_d, in_d, ov, params, &merged, &why, &outcome, &own);
            if (stitched && attempt == 0 && crosses_old(merged)) stitched = false;
        }
        // When the stitch fails or its result does not fit, the element that covers more ground of its
        // own survives whole (the paper removes elements it cannot make whole; we keep one of the two).
        if (stitched) {
            ch.kind = outcome == StitchOutcome::UseNew    ? PatchPlan::Change::Replaced
                      : outcome == StitchOutcome::KeepOld ? PatchPlan::Change::Deformed
                                                          : PatchPlan::Change::Stitched;
            // A stitched element is of the swatch element that gave it more of its own area.
            ch.source = outcome == StitchOutcome::KeepOld || (outcome == StitchOutcome::Stitched && own.old_part > own.new_part)
                            ? -1
                            : fresh[static_cast<std::size_t>(e)].source;
            ch.mesh = std::move(merged);
            if (outcome == StitchOutcome::Stitched && own.new_part > own.old_part) ch.fallback = in_d;
        } else if (own.new_part > own.old_part && !(params.thread_remnants && is_elongated(mo) && is_elongated(mi))) {
            failures[k] = why.empty() ? "unknown" : why;
            ch.kind = PatchPlan::Change::Replaced;
            ch.source = fresh[static_cast<std::size_t>(e)].source;
            ch.mesh = std::move(in_d);
        } else {
            failures[k] = why.empty() ? "unknown" : why;
            ch.kind = PatchPlan::Change::Deformed;
            ch.source = -1;
            ch.mesh = std::move(out_d);
        }
        // Beyond the paper: deformation towards a partner of another size (pebbles vary 2x) must not
        // resize an element much; past kMaxAreaChange the undeformed element is used instead.
        // A strand (is_strand) changes its width with its area, which shows sooner: kMaxStrandAreaChange.
        const bool strand_o = strand_of(mo, old[o].source, params), strand_i = strand_of(mi, fresh[static_cast<std::size_t>(e)].source, params);
        const double max_change = strand_o || strand_i ? kMaxStrandAreaChange : kMaxAreaChange;
        auto resized = [max_change](const Mesh& m, const Mesh& ref) {
            const double r = mesh_area(m) / std::max(mesh_area(ref), 1e-300);
            return r > max_change || r < 1.0 / max_change;
        };
        // A stitch joins halves of two elements; unless they are long elements that stitching is
        // meant to extend (threads, strands), the result must keep about the size of the one it is counted as.
        // In a layered swatch, nor may it reach much beyond both halves' elements: two partners
        // offset by a good part of their length (a scale and the one of the next row whose tip
        // lies over it) would stitch into one element half as long again, of about the area of
        // one. (For pebbles the rule would leave more losers to be squeezed in beside the winners:
        // the eight with pebbles went from 0.994-1.094 to 1.047-1.146 of the swatch's density.)
        auto lengthened = [&params](const Mesh& m, const Mesh& a, const Mesh& b) {
            const auto reach = [](const Mesh& x) { return bounding_box(x).size().head<2>().norm(); };
            return params.layered && reach(m) > kMaxStitchReach * std::max(reach(a), reach(b));
        };
        const bool extends = (is_elongated(mo) && is_elongated(mi)) || (strand_o && strand_i);  // threads, strands
        if (ch.kind == PatchPlan::Change::Stitched && !extends &&
            (resized(ch.mesh, own.old_part > own.new_part ? mo : mi) || lengthened(ch.mesh, mo, mi))) {
            const bool new_wins = own.new_part > own.old_part;
            ch.kind = new_wins ? PatchPlan::Change::Replaced : PatchPlan::Change::Deformed;
            ch.source = new_wins ? fresh[static_cast<std::size_t>(e)].source : -1;
            ch.mesh = new_wins ? in_d : out_d;
            ch.fallback = Mesh();
        }
        if (ch.kind == PatchPlan::Change::Replaced && resized(ch.mesh, mi)) ch.mesh = mi;
        else if (ch.kind == PatchPlan::Change::Deformed && resized(ch.mesh, mo)) ch.mesh = mo;
        if (!ch.fallback.faces.empty() && resized(ch.fallback, mi)) ch.fallback = mi;
        // Beyond the paper: of two blobs (cobbles, pebbles) that could not be merged into one, the
        // loser used to be dropped, and its ground beyond the winner stayed bare: a tessellation
        // (cobbles) lost a fifth of its density in slivers between the two patches' stones. The loser
        // is now kept when a squeeze of at most a third of its width clears the winner and the
        // elements around it by the swatch's clearance (squeeze_clear), like a stone cut to fit.
        const bool new_lost = ch.kind == PatchPlan::Change::Deformed;
        const bool old_lost = ch.kind == PatchPlan::Change::Replaced && old[o].source >= 0;
        if (params.blob_gap > 0.0 && (new_lost || old_lost) && is_blob(mo, strand_o) && is_blob(mi, strand_i)) {
            Mesh loser = new_lost ? mi : mo;
            std::vector<const Mesh*> others{&ch.mesh};
            for (std::size_t o2 = 0; o2 < old.size(); ++o2)
                if (o2 != o) others.push_back(&old[o2].mesh);
            for (std::size_t e2 = 0; e2 < fresh.size(); ++e2)
                if (static_cast<int>(e2) != e) others.push_back(&fresh[e2].mesh);
            for (const Mesh& ob : obstacles) others.push_back(&ob);
            if (squeeze_clear(loser, others, params.blob_gap, kMinSqueezedArea, kMaxSqueezePush)) {
                squeezed[k].kind = PatchPlan::Change::Added;
                squeezed[k].source = new_lost ? fresh[static_cast<std::size_t>(e)].source : old[o].source;
                squeezed[k].mesh = std::move(loser);
            }
        } else if (params.layer_gap > 0.0 && (new_lost || old_lost) && is_blob(mo, strand_o) && is_blob(mi, strand_i)) {
            // A layered swatch's blobs (scales) overlap in xy, so no squeeze clears them; the loser
            // is kept whole where it keeps the swatch's clearance in 3D from the winner, which then
            // stays as it was too (shingles of two patches offset by part of a row overlap as the
            // swatch's do; deformed, each would move half-way into the other). The stage tests the
            // loser against the rest as any addition (collisions, clearance).
            Mesh loser = new_lost ? mi : mo;
            const Mesh& winner = new_lost ? mo : mi;
            if (!meshes_intersect(loser, winner) && keeps_gap(element_gap(loser, bounding_box(loser), winner, params.layer_gap), params.layer_gap)) {
                ch.mesh = winner;
                ch.fallback = Mesh();
                squeezed[k].kind = PatchPlan::Change::Added;
                squeezed[k].source = new_lost ? fresh[static_cast<std::size_t>(e)].source : old[o].source;
                squeezed[k].mesh = std::move(loser);
            }
        }
        else if (params.strand_losers && (new_lost || old_lost) && strand_o && strand_i) {
            // Beyond the paper: a strand that lost is handed back whole as an addition; the stage
            // cuts it where it meets the winner (strand_pieces), as knot work passes under.
            squeezed[k].kind = PatchPlan::Change::Added;
            squeezed[k].source = new_lost ? fresh[static_cast<std::size_t>(e)].source : old[o].source;
            squeezed[k].mesh = new_lost ? mi : mo;
        }
        if (params.thread_remnants && new_lost && is_elongated(mo) && is_elongated(mi)) {
            remnants[k].kind = PatchPlan::Change::Added;
            remnants[k].source = fresh[static_cast<std::size_t>(e)].source;
            remnants[k].mesh = in_d;
        }
        merged_changes[k] = std::move(ch);
    });
    for (std::size_t k = 0; k < matched.size(); ++k) {
        if (!failures[k].empty()) {
            ++plan.stitch_failures;
            ++plan.failure_reasons[failures[k]];
        }
        plan.changes.push_back(std::move(merged_changes[k]));
    }
    std::vector<PatchPlan::Change> squeezed_additions;
    for (PatchPlan::Change& ch : squeezed)
        if (!ch.mesh.faces.empty()) squeezed_additions.push_back(std::move(ch));
    plan.squeezed = static_cast<int>(squeezed_additions.size());
    for (std::size_t e = 0; e < fresh.size(); ++e) {
        if (partner_of_new[e] >= 0) continue;
        // An element without partner joins the output unless it lies mostly on ground the output
        // already covers and an old element stands at about the same place (adding it there would
        // crowd a porous pattern such as chain mail or rivets, which a collision test alone allows).
        const Mesh& m = fresh[e].mesh;
        double on_new = 0.0, total = 0.0;
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            const double a = face_area(m, f);
            total += a;
            if (!in_overlap(ov.new_side, centroid(m, static_cast<int>(f)))) on_new += a;
        }
        if (on_new < 0.5 * total) {
            // ... and when an old element stands at about the same place: their footprints (xy boxes)
            // overlap by at least half of their union. (A distance between centres would call a long
            // thread the twin of its parallel neighbour.)
            const Box3 b = bounding_box(m);
            const double area_b = b.size().x() * b.size().y();
            bool twin = false;
            std::vector<const Mesh*> standing;
            for (const OldElement& oe : old) standing.push_back(&oe.mesh);
            for (const Mesh& m2 : obstacles) standing.push_back(&m2);
            for (const Mesh* om : standing) {
                if (om->faces.empty()) continue;
                const Box3 ob = bounding_box(*om);
                const double ix = std::min(b.max.x(), ob.max.x()) - std::max(b.min.x(), ob.min.x());
                const double iy = std::min(b.max.y(), ob.max.y()) - std::max(b.min.y(), ob.min.y());
                if (ix <= 0 || iy <= 0) continue;
                const double inter = ix * iy;
                if (inter >= 0.5 * (area_b + ob.size().x() * ob.size().y() - inter)) {
                    twin = true;
                    break;
                }
            }
            if (twin) {
                ++plan.crowding;
                continue;
            }
        }
        PatchPlan::Change ch;
        ch.kind = PatchPlan::Change::Added;
        ch.source = fresh[e].source;
        ch.mesh = fresh[e].mesh;
        // Beyond the paper: a blob that would collide with the output may go in squeezed clear of
        // it instead (see squeeze_clear; the fallback of an addition is always such a squeeze).
        if (params.blob_gap > 0.0 && is_blob(m, strand_of(m, fresh[e].source, params))) {
            std::vector<const Mesh*> others;
            for (const OldElement& oe : old) others.push_back(&oe.mesh);
            for (std::size_t e2 = 0; e2 < fresh.size(); ++e2)
                if (e2 != e) others.push_back(&fresh[e2].mesh);
            for (const Mesh& ob : obstacles) others.push_back(&ob);
            Mesh squeezed_mesh = m;
            if (squeeze_clear(squeezed_mesh, others, params.blob_gap, kMinSqueezedArea, kMaxSqueezePush) && squeezed_mesh.vertices != m.vertices)
                ch.fallback = std::move(squeezed_mesh);
        }
        plan.changes.push_back(std::move(ch));
    }
    plan.squeezed_from = plan.changes.size();
    for (PatchPlan::Change& ch : squeezed_additions) plan.changes.push_back(std::move(ch));
    for (PatchPlan::Change& ch : remnants)
        if (!ch.mesh.faces.empty()) plan.changes.push_back(std::move(ch));
    return plan;
}

}  // namespace meshquilt::quilt
