// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/trim.h"

#include "core/intersect.h"
#include "core/triangle_index.h"
#include "meshquilt/analysis.h"
#include "quilt/kernel.h"
#include "quilt/swatch.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <utility>

namespace meshquilt::quilt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Moves a cut at `c` to the middle of the gap between the vertex coordinates `ts` (sorted)
/// around it, so that no vertex lies on or next to the cutting plane.
double mid_gap(const std::vector<double>& ts, double c) {
    const auto it = std::lower_bound(ts.begin(), ts.end(), c);
    if (it == ts.begin() || it == ts.end()) return c;
    return 0.5 * (*(it - 1) + *it);
}

/// `m` clipped to lo <= coordinate `axis` <= hi (either bound may be infinite), closed, as its
/// connected components (a bent thread can leave the span and come back); false when CGAL fails.
bool clip_span(const Mesh& m, int axis, double lo, double hi, std::vector<Mesh>* out) {
    SM sm;
    for (const Vec3& v : m.vertices) sm.add_vertex(K::Point_3(v.x(), v.y(), v.z()));
    for (const Tri& t : m.faces)
        if (sm.add_face(SM::Vertex_index(static_cast<SM::size_type>(t[0])), SM::Vertex_index(static_cast<SM::size_type>(t[1])),
                        SM::Vertex_index(static_cast<SM::size_type>(t[2]))) == SM::null_face())
            return false;
    // Clipping a mesh that intersects itself (or has degenerate faces, which CGAL counts so) is
    // outside PMP::clip's precondition, and its corefinement then crashed in the constrained
    // triangulation of a cut face (a Truchet knot's part on a genus-16 plate), not throwing.
    if (PMP::does_self_intersect(sm)) return false;
    const Box3 box = bounding_box(m);
    const Vec3 pad = Vec3::Constant(1.0 + box.size().maxCoeff());
    Vec3 a = box.min - pad, b = box.max + pad;
    if (std::isfinite(lo)) a[axis] = lo;
    if (std::isfinite(hi)) b[axis] = hi;
    try {
        if (!PMP::clip(sm, K::Iso_cuboid_3(K::Point_3(a.x(), a.y(), a.z()), K::Point_3(b.x(), b.y(), b.z())),
                       CGAL::parameters::clip_volume(true)))
            return false;
    } catch (const std::exception&) {
        return false;
    }
    Mesh r;
    std::vector<int> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
    for (const auto v : sm.vertices()) {
        index[v.idx()] = static_cast<int>(r.vertices.size());
        const auto& p = sm.point(v);
        r.vertices.emplace_back(p.x(), p.y(), p.z());
    }
    for (const auto f : sm.faces()) {
        Tri t{};
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3) return false;
            t[k++] = index[v.idx()];
        }
        if (k != 3) return false;
        r.faces.push_back(t);
    }
    *out = split_components(r);
    return true;
}

/// Shortest-path distances along the edges of `m` from vertex `from` (infinite where unreachable).
std::vector<double> edge_distances(const std::vector<std::vector<std::pair<int, double>>>& adj, int from) {
    std::vector<double> d(adj.size(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    d[static_cast<std::size_t>(from)] = 0.0;
    queue.push({0.0, from});
    while (!queue.empty()) {
        const auto [dist, v] = queue.top();
        queue.pop();
        if (dist > d[static_cast<std::size_t>(v)]) continue;
        for (const auto& [w, len] : adj[static_cast<std::size_t>(v)])
            if (dist + len < d[static_cast<std::size_t>(w)]) {
                d[static_cast<std::size_t>(w)] = dist + len;
                queue.push({dist + len, w});
            }
    }
    return d;
}

std::size_t farthest(const std::vector<double>& d) {
    std::size_t best = 0;
    for (std::size_t v = 0; v < d.size(); ++v)
        if (std::isfinite(d[v]) && (!std::isfinite(d[best]) || d[v] > d[best])) best = v;
    return best;
}

/// How much farther than the median band the widest band of a strand's levels may reach from its
/// centroid (lengths_along): a tube's bands are its cross-sections.
constexpr double kMaxBandSpread = 2.0;

/// Each vertex's length along strand `m` (see strand_pieces) in `t`, and the strand's girth (area
/// over twice its end-to-end length: half its cross-section's perimeter) in `girth`. False when `m` is not one
/// connected element with two distinct ends, branches (kMaxBandSpread) or the harmonic solve fails.
bool lengths_along(const Mesh& m, std::vector<double>* t, double* girth) {
    const std::size_t n = m.vertices.size();
    std::vector<std::vector<std::pair<int, double>>> adj(n);
    std::vector<char> used(n, 0);
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) {
            const int a = f[k], b = f[(k + 1) % 3];
            adj[static_cast<std::size_t>(a)].push_back({b, (m.vertices[static_cast<std::size_t>(a)] - m.vertices[static_cast<std::size_t>(b)]).norm()});
            used[static_cast<std::size_t>(a)] = 1;
        }
    const std::vector<double> d0 = edge_distances(adj, m.faces[0][0]);
    for (std::size_t v = 0; v < n; ++v)
        if (used[v] && !std::isfinite(d0[v])) return false;  // several components
    const std::size_t a = farthest(d0);
    const std::vector<double> da = edge_distances(adj, static_cast<int>(a));
    const std::size_t b = farthest(da);
    const std::vector<double> db = edge_distances(adj, static_cast<int>(b));
    const double reach = da[b];
    *girth = mesh_area(m) / std::max(2.0 * reach, 1e-300);
    const double end = 0.5 * *girth;
    if (!(reach > 4.0 * end)) return false;
    // Dirichlet ends: 0 within `end` of one extreme vertex, 1 within it of the other.
    std::vector<int> index(n, -1);
    std::vector<double> fixed(n, 0.0);
    int free_count = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        const bool near_a = da[v] < end, near_b = db[v] < end;
        if (near_a && near_b) return false;
        if (near_a) fixed[v] = 0.0;
        else if (near_b) fixed[v] = 1.0;
        else index[v] = free_count++;
    }
    // Clamped cotangent weights keep the maximum principle (no level leaves the ends' range).
    std::map<std::pair<int, int>, double> weight;
    for (const Tri& f : m.faces)
        for (int k = 0; k < 3; ++k) {
            const int i = f[k], j = f[(k + 1) % 3], o = f[(k + 2) % 3];
            const Vec3 e1 = m.vertices[static_cast<std::size_t>(i)] - m.vertices[static_cast<std::size_t>(o)];
            const Vec3 e2 = m.vertices[static_cast<std::size_t>(j)] - m.vertices[static_cast<std::size_t>(o)];
            const double cot = e1.dot(e2) / std::max(e1.cross(e2).norm(), 1e-300);
            weight[{std::min(i, j), std::max(i, j)}] += 0.5 * std::clamp(cot, 0.05, 20.0);
        }
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(free_count);
    for (const auto& [edge, w] : weight) {
        const int i = edge.first, j = edge.second;
        const int fi = index[static_cast<std::size_t>(i)], fj = index[static_cast<std::size_t>(j)];
        if (fi >= 0) entries.emplace_back(fi, fi, w);
        if (fj >= 0) entries.emplace_back(fj, fj, w);
        if (fi >= 0 && fj >= 0) {
            entries.emplace_back(fi, fj, -w);
            entries.emplace_back(fj, fi, -w);
        } else if (fi >= 0) {
            rhs[fi] += w * fixed[static_cast<std::size_t>(j)];
        } else if (fj >= 0) {
            rhs[fj] += w * fixed[static_cast<std::size_t>(i)];
        }
    }
    Eigen::SparseMatrix<double> lap(free_count, free_count);
    lap.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(lap);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd x = solver.solve(rhs);
    if (solver.info() != Eigen::Success || !x.allFinite()) return false;
    std::vector<double> s(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) s[v] = index[v] >= 0 ? std::clamp(x[index[v]], 0.0, 1.0) : fixed[v];
    // Levels to lengths: the centroids of the vertices in each of `bins` bands of levels, joined.
    const int bins = std::clamp(static_cast<int>(reach / (0.25 * *girth)), 16, 512);
    std::vector<Vec3> centre(static_cast<std::size_t>(bins), Vec3::Zero());
    std::vector<int> count(static_cast<std::size_t>(bins), 0);
    for (std::size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        const auto k = static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(s[v] * bins)));
        centre[k] += m.vertices[v];
        ++count[k];
    }
    // A tube's bands are its cross-sections, all about as wide. A branching element (a snowflake's
    // arms, a star) is no strand to cut: the level of a junction also holds the side arms, whose
    // values stay near it, and its band reaches far beyond the others.
    std::vector<double> spread(static_cast<std::size_t>(bins), 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        const auto k = static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(s[v] * bins)));
        spread[k] = std::max(spread[k], (m.vertices[v] - centre[k] / count[k]).norm());
    }
    std::vector<double> filled;
    for (int k = 0; k < bins; ++k)
        if (count[static_cast<std::size_t>(k)] > 0) filled.push_back(spread[static_cast<std::size_t>(k)]);
    std::nth_element(filled.begin(), filled.begin() + static_cast<std::ptrdiff_t>(filled.size() / 2), filled.end());
    const double typical = filled[filled.size() / 2];
    if (*std::max_element(spread.begin(), spread.end()) > kMaxBandSpread * typical) return false;
    std::vector<double> at, along;  // band middles (levels) and their lengths along the centre line
    Vec3 last = Vec3::Zero();
    for (int k = 0; k < bins; ++k) {
        if (count[static_cast<std::size_t>(k)] == 0) continue;
        const Vec3 c = centre[static_cast<std::size_t>(k)] / count[static_cast<std::size_t>(k)];
        along.push_back(along.empty() ? 0.0 : along.back() + (c - last).norm());
        at.push_back((k + 0.5) / bins);
        last = c;
    }
    t->assign(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        const auto it = std::lower_bound(at.begin(), at.end(), s[v]);
        if (it == at.begin()) (*t)[v] = along.front();
        else if (it == at.end()) (*t)[v] = along.back();
        else {
            const auto k = static_cast<std::size_t>(it - at.begin());
            const double u = (s[v] - at[k - 1]) / std::max(at[k] - at[k - 1], 1e-300);
            (*t)[v] = along[k - 1] + u * (along[k] - along[k - 1]);
        }
    }
    return true;
}

/// Keeps the part of closed mesh `m` where field `t` (per vertex) is above `level` (`above`) or
/// below it, splitting the faces that straddle it, and closes each cut loop with a fan from its
/// centroid. `level` must differ from every vertex's value. False when a cut loop is not simple.
bool clip_level(Mesh& m, std::vector<double>& t, double level, bool above) {
    auto inside = [&](int v) { return above ? t[static_cast<std::size_t>(v)] > level : t[static_cast<std::size_t>(v)] < level; };
    std::map<std::pair<int, int>, int> split;
    auto cut = [&](int a, int b) {
        const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
        if (const auto it = split.find(key); it != split.end()) return it->second;
        const double ta = t[static_cast<std::size_t>(a)], tb = t[static_cast<std::size_t>(b)];
        const double u = (level - ta) / (tb - ta);
        const int id = static_cast<int>(m.vertices.size());
        m.vertices.push_back(m.vertices[static_cast<std::size_t>(a)] + u * (m.vertices[static_cast<std::size_t>(b)] - m.vertices[static_cast<std::size_t>(a)]));
        t.push_back(level);
        split.emplace(key, id);
        return id;
    };
    std::vector<Tri> faces;
    for (const Tri& f : m.faces) {
        const int in = inside(f[0]) + inside(f[1]) + inside(f[2]);
        if (in == 3) faces.push_back(f);
        if (in == 0 || in == 3) continue;
        // Rotate so that f[r] is the odd vertex out (the one inside when in == 1, outside when 2).
        int r = 0;
        for (int k = 0; k < 3; ++k)
            if (inside(f[k]) == (in == 1)) r = k;
        const int i = f[r], j = f[(r + 1) % 3], k = f[(r + 2) % 3];
        const int xij = cut(i, j), xki = cut(k, i);
        if (in == 1) {
            faces.push_back({i, xij, xki});
        } else {
            faces.push_back({xij, j, k});
            faces.push_back({xij, k, xki});
        }
    }
    m.faces = std::move(faces);
    // Cap the cut loops: the original was closed, so every boundary edge is on the cut.
    std::vector<std::vector<int>> loops;
    if (!boundary_loops(m, &loops)) return false;
    for (const std::vector<int>& loop : loops) {
        Vec3 c = Vec3::Zero();
        for (int u : loop) c += m.vertices[static_cast<std::size_t>(u)];
        const int centre = static_cast<int>(m.vertices.size());
        m.vertices.push_back(c / static_cast<double>(loop.size()));
        t.push_back(level);
        for (std::size_t q = 0; q < loop.size(); ++q) m.faces.push_back({loop[(q + 1) % loop.size()], loop[q], centre});
    }
    return true;
}

/// The level in the widest gap between the sorted values `ts` whose middle lies in [lo, hi]; NaN
/// when no gap's middle does.
double widest_gap(const std::vector<double>& ts, double lo, double hi) {
    double best = 0.0, level = std::numeric_limits<double>::quiet_NaN();
    auto first = std::lower_bound(ts.begin(), ts.end(), lo);
    if (first != ts.begin()) --first;
    for (auto it = first; it + 1 != ts.end() && *it <= hi; ++it) {
        const double mid = 0.5 * (*it + *(it + 1)), gap = *(it + 1) - *it;
        if (mid >= lo && mid <= hi && gap > best) {
            best = gap;
            level = mid;
        }
    }
    return level;
}

/// The spans of [t0, t1] of a per-vertex value `t` of `m` left free by its faces flagged in `bad`
/// (each blocks the values its vertices span, widened by `margin`), in order.
std::vector<std::pair<double, double>> free_values(const Mesh& m, const std::vector<double>& t, const std::vector<char>& bad, double margin,
                                                   double t0, double t1) {
    // Values blocked by flagged faces, merged.
    std::vector<std::pair<double, double>> blocked;
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        if (!bad[f]) continue;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k < 3; ++k) {
            lo = std::min(lo, t[static_cast<std::size_t>(m.faces[f][k])]);
            hi = std::max(hi, t[static_cast<std::size_t>(m.faces[f][k])]);
        }
        blocked.emplace_back(lo - margin, hi + margin);
    }
    std::sort(blocked.begin(), blocked.end());
    std::vector<std::pair<double, double>> free;
    double from = t0;
    for (const auto& [lo, hi] : blocked) {
        if (lo > from) free.emplace_back(from, lo);
        from = std::max(from, hi);
    }
    if (from < t1) free.emplace_back(from, t1);
    return free;
}

/// The spans along the axis of thread `m` (set in `axis`) left free by its faces flagged in `bad`,
/// each widened by `margin`, in order.
std::vector<std::pair<double, double>> free_spans(const Mesh& m, const std::vector<char>& bad, double margin, int* axis) {
    const Box3 box = bounding_box(m);
    *axis = box.size().x() >= box.size().y() ? 0 : 1;
    std::vector<double> t;
    t.reserve(m.vertices.size());
    for (const Vec3& v : m.vertices) t.push_back(v[*axis]);
    return free_values(m, t, bad, margin, box.min[*axis], box.max[*axis]);
}

/// The lowest and highest heights of thread `m`'s vertices in each of `n` cells `cell` long from
/// `t0` along axis `along` (vertices beyond the ends count in the end cells; an empty cell has
/// lo = inf, hi = -inf).
void cell_heights(const Mesh& m, int along, double t0, double cell, long n, std::vector<double>* lo, std::vector<double>* hi) {
    const double inf = std::numeric_limits<double>::infinity();
    lo->assign(static_cast<std::size_t>(n), inf);
    hi->assign(static_cast<std::size_t>(n), -inf);
    for (const Vec3& v : m.vertices) {
        const auto i = static_cast<std::size_t>(std::clamp(static_cast<long>(std::floor((v[along] - t0) / cell)), 0L, n - 1));
        (*lo)[i] = std::min((*lo)[i], v.z());
        (*hi)[i] = std::max((*hi)[i], v.z());
    }
}

/// The median over the cells that hold vertices of the height spanned in each (a thread's
/// thickness; cell_heights).
double median_thickness(const std::vector<double>& lo, const std::vector<double>& hi) {
    std::vector<double> t;
    for (std::size_t i = 0; i < lo.size(); ++i)
        if (hi[i] >= lo[i]) t.push_back(hi[i] - lo[i]);
    if (t.empty()) return 0.0;
    std::nth_element(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(t.size() / 2), t.end());
    return t[t.size() / 2];
}

/// A crossing thread met by a thread along axis `along`: its run of cells [first, last] (in cells
/// from t0) and the lowest and highest heights of its vertices in each of them.
struct CrossingRun {
    long first = 0, last = 0;
    std::vector<double> lo, hi;
};

/// The runs of the `crossing` threads' vertices within `width` / 2 of line `u` (across axis
/// `along`), on `n` cells of length `cell` from `t0` along it.
static std::vector<CrossingRun> crossing_runs(int along, double u, double width, double t0, double cell, long n,
                                              const std::vector<const Mesh*>& crossing) {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> lo(static_cast<std::size_t>(n), inf), hi(lo.size(), -inf);
    for (const Mesh* o : crossing)
        for (const Vec3& v : o->vertices) {
            const auto i = static_cast<long>(std::floor((v[along] - t0) / cell));
            if (i < 0 || i >= n || std::fabs(v[1 - along] - u) > 0.5 * width) continue;
            lo[static_cast<std::size_t>(i)] = std::min(lo[static_cast<std::size_t>(i)], v.z());
            hi[static_cast<std::size_t>(i)] = std::max(hi[static_cast<std::size_t>(i)], v.z());
        }
    std::vector<CrossingRun> runs;
    for (long i = 0; i < n;) {
        if (!(hi[static_cast<std::size_t>(i)] > -inf)) {
            ++i;
            continue;
        }
        CrossingRun r;
        r.first = i;
        for (; i < n && hi[static_cast<std::size_t>(i)] > -inf; ++i) {
            r.lo.push_back(lo[static_cast<std::size_t>(i)]);
            r.hi.push_back(hi[static_cast<std::size_t>(i)]);
        }
        r.last = i - 1;
        runs.push_back(std::move(r));
    }
    return runs;
}

}  // namespace

double longest_free_span(const Mesh& m, const std::vector<char>& bad, double margin) {
    if (m.faces.empty() || bad.size() != m.faces.size()) return 0.0;
    int axis = 0;
    double longest = 0.0;
    for (const auto& [lo, hi] : free_spans(m, bad, margin, &axis)) longest = std::max(longest, hi - lo);
    return longest;
}

std::vector<Mesh> thread_pieces(const Mesh& m, const std::vector<char>& bad, const ThreadCut& cut) {
    if (m.faces.empty() || bad.size() != m.faces.size()) return {};
    if (std::none_of(bad.begin(), bad.end(), [](char b) { return b != 0; })) return {m};
    int axis = 0;
    const std::vector<std::pair<double, double>> free = free_spans(m, bad, cut.margin, &axis);
    const Box3 box = bounding_box(m);
    std::vector<double> ts;
    ts.reserve(m.vertices.size());
    for (const Vec3& v : m.vertices) ts.push_back(v[axis]);
    std::sort(ts.begin(), ts.end());
    const double t0 = box.min[axis], t1 = box.max[axis];
    std::vector<Mesh> pieces;
    const double inf = std::numeric_limits<double>::infinity();
    for (const auto& [lo, hi] : free) {
        if (hi - lo < cut.min_length) continue;
        const double a = lo > t0 ? mid_gap(ts, lo) : -inf;
        const double b = hi < t1 ? mid_gap(ts, hi) : inf;
        // A span between two neighbouring vertex coordinates (under long faces) moves both cuts to
        // the same gap: the box would have no width, and CGAL's clip crashed on it (a segmentation
        // fault; tests/data/trim/strand_clip.obj). Such a span holds no vertex: no piece.
        if (!(b > a)) continue;
        std::vector<Mesh> parts;
        if (!clip_span(m, axis, a, b, &parts)) continue;
        for (Mesh& piece : parts) {
            const Vec3 size = bounding_box(piece).size();
            if (std::max(size.x(), size.y()) < cut.min_length || !is_closed_oriented(piece) || count_self_intersections(piece, 1) > 0) continue;
            pieces.push_back(std::move(piece));
        }
    }
    return pieces;
}

Mesh woven(const Mesh& m, int along, const std::vector<const Mesh*>& crossing, double width, double zmin, double zmax) {
    const Box3 box = bounding_box(m);
    const double cell = 0.25 * width, u = 0.5 * (box.min[1 - along] + box.max[1 - along]);
    const double t0 = box.min[along];
    const long n = static_cast<long>(std::ceil((box.max[along] - t0) / cell)) + 1;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> lo, hi;
    cell_heights(m, along, t0, cell, n, &lo, &hi);
    const double thick = median_thickness(lo, hi);
    // Knots: (cell, target centre height), cell by cell through each crossing run, on the side
    // (over or under) with the more room at the run's narrowest cell; and per cell the share of its
    // thickness the thread keeps there (squash: 1 where the room takes it whole).
    std::vector<std::pair<double, double>> knots;
    std::vector<double> squash(static_cast<std::size_t>(n), 1.0);
    for (const CrossingRun& r : crossing_runs(along, u, width, t0, cell, n, crossing)) {
        double over = inf, under = inf;
        for (std::size_t k = 0; k < r.lo.size(); ++k) {
            over = std::min(over, zmax - r.hi[k]);
            under = std::min(under, r.lo[k] - zmin);
        }
        const bool above = over >= under;
        for (std::size_t k = 0; k < r.lo.size(); ++k) {
            const double room = std::max(above ? zmax - r.hi[k] : r.lo[k] - zmin, 0.0);
            const double keep = thick > 0.0 && room < thick ? std::max(kSquashFill * room / thick, kMinSquash) : 1.0;
            const double half = 0.5 * keep * thick;
            const double z = above ? r.hi[k] + 0.5 * room : zmin + 0.5 * room;
            knots.emplace_back(static_cast<double>(r.first + static_cast<long>(k)), std::clamp(z, zmin + half, std::max(zmax - half, zmin + half)));
            // The squash eases back to the whole thickness over a thread's width either side.
            const long at = r.first + static_cast<long>(k);
            for (long i = std::max(0L, at - 4); i <= std::min(n - 1, at + 4); ++i) {
                const double d = std::max(0.0, std::fabs(static_cast<double>(i - at)) - 1.0) / 3.0;
                const double w = d >= 1.0 ? 0.0 : 0.5 + 0.5 * std::cos(d * 3.14159265358979323846);
                squash[static_cast<std::size_t>(i)] = std::min(squash[static_cast<std::size_t>(i)], 1.0 - (1.0 - keep) * w);
            }
        }
    }
    if (knots.empty()) return m;
    // The thread's own centre line, per bin (empty bins take their neighbours').
    std::vector<double> centre(static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < centre.size(); ++i)
        if (hi[i] > -inf) centre[i] = 0.5 * (lo[i] + hi[i]);
    for (std::size_t i = 1; i < centre.size(); ++i)
        if (std::isnan(centre[i])) centre[i] = centre[i - 1];
    for (std::size_t i = centre.size() - 1; i-- > 0;)
        if (std::isnan(centre[i])) centre[i] = centre[i + 1];
    auto target = [&](double b) {
        if (b <= knots.front().first) return knots.front().second;
        if (b >= knots.back().first) return knots.back().second;
        std::size_t k = 1;
        while (knots[k].first < b) ++k;
        const double s = (b - knots[k - 1].first) / (knots[k].first - knots[k - 1].first);
        const double ease = 0.5 - 0.5 * std::cos(s * 3.14159265358979323846);
        return knots[k - 1].second + ease * (knots[k].second - knots[k - 1].second);
    };
    // Linear between bin centres (own centre line, squash).
    auto per_bin = [&](const std::vector<double>& values, double b) {
        const double f = std::clamp(b, 0.0, static_cast<double>(n - 1));
        const auto i = static_cast<std::size_t>(std::min(static_cast<long>(f), n - 2 < 0 ? 0L : n - 2));
        const double s = f - static_cast<double>(i);
        return i + 1 < values.size() ? (1.0 - s) * values[i] + s * values[i + 1] : values[i];
    };
    Mesh out = m;
    for (Vec3& v : out.vertices) {
        const double b = (v[along] - t0) / cell - 0.5;  // bin coordinate of v (bin centres at integers)
        const double own = per_bin(centre, b);
        v.z() = target(b) + per_bin(squash, b) * (v.z() - own);
    }
    return out;
}

std::vector<Mesh> split_components(const Mesh& m) {
    int count = 0;
    const std::vector<int> component = connected_components(m, &count);
    std::vector<Mesh> out(static_cast<std::size_t>(count));
    std::vector<int> local(m.vertices.size(), -1);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        Mesh& piece = out[static_cast<std::size_t>(component[f])];
        Tri tri{};
        for (int k = 0; k < 3; ++k) {
            int& l = local[static_cast<std::size_t>(m.faces[f][k])];
            if (l < 0) {
                l = static_cast<int>(piece.vertices.size());
                piece.vertices.push_back(m.vertices[static_cast<std::size_t>(m.faces[f][k])]);
            }
            tri[k] = l;
        }
        piece.faces.push_back(tri);
    }
    return out;
}

Mesh join_meshes(const std::vector<Mesh>& parts) {
    Mesh joined;
    for (const Mesh& p : parts) {
        const int offset = static_cast<int>(joined.vertices.size());
        joined.vertices.insert(joined.vertices.end(), p.vertices.begin(), p.vertices.end());
        for (const Tri& t : p.faces) joined.faces.push_back(t + Tri::Constant(offset));
    }
    return joined;
}

std::vector<char> faces_near(const Mesh& m, const std::vector<const Mesh*>& others, double gap) {
    const Box3 box = bounding_box(m);
    std::vector<char> close(m.vertices.size(), 0);
    for (const Mesh* o : others)
        for (const Vec3& w : o->vertices) {
            if (((box.min.array() - gap) > w.array()).any() || (w.array() > (box.max.array() + gap)).any()) continue;
            for (std::size_t v = 0; v < m.vertices.size(); ++v)
                if ((m.vertices[v] - w).squaredNorm() < gap * gap) close[v] = 1;
        }
    std::vector<char> out(m.faces.size(), 0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) out[f] = static_cast<char>(out[f] | close[static_cast<std::size_t>(m.faces[f][k])]);
    return out;
}

double unflagged_area(const Mesh& m, const std::vector<char>& flags) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size() && f < flags.size(); ++f)
        if (!flags[f]) a += face_area(m, f);
    return a;
}

std::vector<Mesh> strand_pieces(const Mesh& m, const std::vector<char>& bad, const ThreadCut& cut) {
    if (m.faces.empty() || bad.size() != m.faces.size()) return {};
    if (std::none_of(bad.begin(), bad.end(), [](char b) { return b != 0; })) return {m};
    std::vector<double> t;
    double girth = 0.0;
    if (!lengths_along(m, &t, &girth)) return {};
    std::vector<double> ts = t;
    std::sort(ts.begin(), ts.end());
    const double t0 = ts.front(), t1 = ts.back();
    // Lengths blocked by flagged faces, widened by the margin; the free ones between them.
    const std::vector<std::pair<double, double>> free = free_values(m, t, bad, cut.margin, t0, t1);
    const double slack = 0.25 * girth;  // how far a cut may move into its piece to pass between vertex rings
    std::vector<Mesh> pieces;
    const double min_length = std::max(cut.min_length, cut.min_girths * girth);
    for (const auto& [lo, hi] : free) {
        if (hi - lo < min_length) continue;
        const double a = lo > t0 ? widest_gap(ts, lo, lo + slack) : -std::numeric_limits<double>::infinity();
        const double b = hi < t1 ? widest_gap(ts, hi - slack, hi) : std::numeric_limits<double>::infinity();
        if (std::isnan(a) || std::isnan(b) || !(b - a >= min_length)) continue;
        Mesh part = m;
        std::vector<double> tp = t;
        if (std::isfinite(a) && !clip_level(part, tp, a, true)) continue;
        if (std::isfinite(b) && !clip_level(part, tp, b, false)) continue;
        for (Mesh& piece : split_components(part)) {
            if (!is_closed_oriented(piece) || count_self_intersections(piece, 1) > 0) continue;
            pieces.push_back(std::move(piece));
        }
    }
    return pieces;
}

}  // namespace meshquilt::quilt
