// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/trim.h"

#include "core/intersect.h"
#include "meshquilt/analysis.h"
#include "quilt/kernel.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
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

}  // namespace meshquilt::quilt
