// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/trim.h"

#include "core/intersect.h"
#include "meshquilt/analysis.h"
#include "quilt/kernel.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

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
    int count = 0;
    const std::vector<int> component = connected_components(r, &count);
    out->assign(static_cast<std::size_t>(count), Mesh());
    std::vector<int> local(r.vertices.size(), -1);
    for (std::size_t f = 0; f < r.faces.size(); ++f) {
        Mesh& piece = (*out)[static_cast<std::size_t>(component[f])];
        Tri t{};
        for (int k = 0; k < 3; ++k) {
            int& l = local[static_cast<std::size_t>(r.faces[f][k])];
            if (l < 0) {
                l = static_cast<int>(piece.vertices.size());
                piece.vertices.push_back(r.vertices[static_cast<std::size_t>(r.faces[f][k])]);
            }
            t[k] = l;
        }
        piece.faces.push_back(t);
    }
    return true;
}

/// The spans along the axis of thread `m` (set in `axis`) left free by its faces flagged in `bad`,
/// each widened by `margin`, in order.
std::vector<std::pair<double, double>> free_spans(const Mesh& m, const std::vector<char>& bad, double margin, int* axis) {
    const Box3 box = bounding_box(m);
    *axis = box.size().x() >= box.size().y() ? 0 : 1;
    // Spans blocked by flagged faces, merged.
    std::vector<std::pair<double, double>> blocked;
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        if (!bad[f]) continue;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k < 3; ++k) {
            const double t = m.vertices[static_cast<std::size_t>(m.faces[f][k])][*axis];
            lo = std::min(lo, t);
            hi = std::max(hi, t);
        }
        blocked.emplace_back(lo - margin, hi + margin);
    }
    std::sort(blocked.begin(), blocked.end());
    const double t0 = box.min[*axis], t1 = box.max[*axis];
    std::vector<std::pair<double, double>> free;
    double from = t0;
    for (const auto& [lo, hi] : blocked) {
        if (lo > from) free.emplace_back(from, lo);
        from = std::max(from, hi);
    }
    if (from < t1) free.emplace_back(from, t1);
    return free;
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

}  // namespace meshquilt::quilt
