// SPDX-License-Identifier: AGPL-3.0-or-later
// The stretch-optimised tetrahedral shell map (Zhou et al. 2006 Section 3.2; Porumbescu et al.
// 2005). See include/meshquilt/shellmap.h for the construction and the stretch measure.

#include "meshquilt/shellmap.h"

#include "core/triangle_index.h"
#include "meshquilt/errors.h"
#include "meshquilt/surface.h"
#include "quilt/field.h"
#include "quilt/patch.h"
#include "quilt/swatch.h"
#include "shellmap/visibility.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Intersections_3/Tetrahedron_3_Triangle_3.h>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <random>

namespace meshquilt {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Charts are grown as discs and shrunk until LSCM distorts area by at most this (98th over 2nd
/// percentile) and folds no face.
constexpr double kChartDistortion = 1.25;
/// A ray along the offset direction must meet no other part of the base within this many heights.
constexpr double kRayClearance = 2.2;
/// Offset heights change by at most this much per unit length along an edge.
constexpr double kHeightSlope = 0.5;
/// A shell tetrahedron must keep at least this fraction of its straight prism's volume share.
constexpr double kMinWorldVolume = 1e-3;
/// Heights are never lowered below this fraction of H by the clearance and intersection rules...
constexpr double kMinHeight = 0.02;
/// ... except to mend an inverted prism, whose volumes are positive to first order in the heights,
/// or to part offset faces that meet each other: such corners may go down to this fraction.
constexpr double kMinPrismHeight = 1e-4;
/// Offset directions must make at least this cosine with every incident face's normal.
constexpr double kMinDirectionCos = shell::kMinSeeingCos;
/// Smoothing steps of the offset directions everywhere...
constexpr int kDirectionSteps = 5;
/// ... and where a prism inverts at full height: steps at most, rounds, and the reach around the
/// inverted prisms in heights H (offset_directions).
constexpr int kBumpySteps = 200;
constexpr int kBumpyRounds = 3;
constexpr double kBumpyReach = 2.0;
/// A patch keeps its further smoothing when at most this share of its inverted prisms is left.
constexpr double kBumpyKeep = 0.5;

/// Corner code of a prism: local corner c (0..2) on the base (c) or on the offset (c + 3).
using TetCodes = std::array<int, 4>;

SM to_cgal(const Mesh& m) {
    SM sm;
    for (const Vec3& v : m.vertices) sm.add_vertex(K::Point_3(v.x(), v.y(), v.z()));
    for (const Tri& t : m.faces)
        sm.add_face(SM::Vertex_index(static_cast<SM::size_type>(t[0])), SM::Vertex_index(static_cast<SM::size_type>(t[1])),
                    SM::Vertex_index(static_cast<SM::size_type>(t[2])));
    return sm;
}

double det3(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

}  // namespace

/// Point location in one chart's texture space: a uniform grid over the chart's (u, v), each cell
/// listing the prisms whose footprint (bottom and offset triangles) overlaps it.
struct ChartGrid {
    Vec2 lo = Vec2::Zero();
    double cell = 1.0;
    int nx = 1, ny = 1;
    std::vector<std::vector<int>> bucket;
};

struct ShellMap::Impl {
    Mesh base;
    ShellOptions opt;
    double H = 0.0;
    std::vector<std::array<int, 3>> nb;
    std::vector<Vec3> face_normal;
    std::vector<double> face_area;
    std::vector<std::vector<int>> vertex_faces;
    std::vector<Vec3> dir, top;
    std::vector<double> height;
    // Atlas: per face its chart and texture vertex per corner; per texture vertex its base vertex,
    // chart uv (bottom), offset uv (top, optimised) and whether it may move.
    std::vector<int> chart_of_face;
    std::vector<std::array<int, 3>> tex_corner;
    std::vector<Vec2> tex_uv, tex_top;
    std::vector<char> tex_free;
    std::vector<std::vector<int>> tex_faces;
    std::vector<std::array<TetCodes, 3>> tets;  ///< per face
    std::size_t offset_intersections = 0;
    std::vector<ChartGrid> grids;  ///< per chart, built once the offset corners are final
    /// Per face, the LU factors of its three texture tetrahedra's edge matrices (tet_coordinates),
    /// built once the offset corners are final.
    std::vector<std::array<Eigen::PartialPivLU<Eigen::Matrix3d>, 3>> factors;
    ShellStatistics stats;

    // ---- corners of tetrahedra ----
    [[nodiscard]] Vec3 tex_point(std::size_t f, int code) const {
        const auto t = static_cast<std::size_t>(tex_corner[f][static_cast<std::size_t>(code % 3)]);
        if (code < 3) return {tex_uv[t].x(), tex_uv[t].y(), 0.0};
        return {tex_top[t].x(), tex_top[t].y(), H};
    }
    [[nodiscard]] Vec3 world_point(std::size_t f, int code) const {
        const auto v = static_cast<std::size_t>(base.faces[f][code % 3]);
        return code < 3 ? base.vertices[v] : top[v];
    }
    [[nodiscard]] double world_volume(std::size_t f, int k) const {
        const TetCodes& c = tets[f][static_cast<std::size_t>(k)];
        const Vec3 p0 = world_point(f, c[0]);
        return det3(world_point(f, c[1]) - p0, world_point(f, c[2]) - p0, world_point(f, c[3]) - p0) / 6.0;
    }
    [[nodiscard]] double texture_volume(std::size_t f, int k) const {
        const TetCodes& c = tets[f][static_cast<std::size_t>(k)];
        const Vec3 p0 = tex_point(f, c[0]);
        return det3(tex_point(f, c[1]) - p0, tex_point(f, c[2]) - p0, tex_point(f, c[3]) - p0) / 6.0;
    }
    /// |J|_F^2 of the texture-to-shell map on a tetrahedron; infinity when the texture tet is flat.
    [[nodiscard]] double frobenius2(std::size_t f, int k) const {
        const TetCodes& c = tets[f][static_cast<std::size_t>(k)];
        Eigen::Matrix3d T, W;
        const Vec3 t0 = tex_point(f, c[0]), w0 = world_point(f, c[0]);
        for (int j = 1; j < 4; ++j) {
            T.col(j - 1) = tex_point(f, c[static_cast<std::size_t>(j)]) - t0;
            W.col(j - 1) = world_point(f, c[static_cast<std::size_t>(j)]) - w0;
        }
        const double d = T.determinant();
        if (!(std::fabs(d) > 0)) return std::numeric_limits<double>::infinity();
        return (W * T.inverse()).squaredNorm();
    }

    /// The edge matrix of texture tetrahedron k of face f (columns: corners 1-3 minus corner 0).
    [[nodiscard]] Eigen::Matrix3d texture_edges(std::size_t f, int k) const {
        const TetCodes& c = tets[f][static_cast<std::size_t>(k)];
        Eigen::Matrix3d T;
        const Vec3 t0 = tex_point(f, c[0]);
        for (int j = 1; j < 4; ++j) T.col(j - 1) = tex_point(f, c[static_cast<std::size_t>(j)]) - t0;
        return T;
    }

    /// Barycentric coordinates of texture point `p` in tetrahedron k of face f, solved with the
    /// factorisation of its edge matrix kept once the texture corners are final (`factors`, built
    /// at the end of build(): the same factors as factorising anew, so the same coordinates).
    [[nodiscard]] Eigen::Vector4d tet_coordinates(std::size_t f, int k, const Vec3& p) const {
        const Vec3 t0 = tex_point(f, tets[f][static_cast<std::size_t>(k)][0]);
        const Vec3 l = factors[f][static_cast<std::size_t>(k)].solve(p - t0);
        return {1.0 - l.sum(), l.x(), l.y(), l.z()};
    }

    void build();
    void offset_directions();
    void limit_heights();
    void build_atlas();
    void build_tets();
    [[nodiscard]] double stretch() const;
    void optimise();
    void collect_statistics();
    void build_grids();
    [[nodiscard]] SurfacePoint unfold(SurfacePoint sp) const;
};

// ---------------------------------------------------------------------------------------------
// 1. Offset directions

void ShellMap::Impl::offset_directions() {
    const std::size_t V = base.vertices.size(), F = base.faces.size();
    // Angle-weighted normals.
    std::vector<Vec3> n(V, Vec3::Zero());
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::size_t>(base.faces[f][k]);
            const Vec3 e1 = base.vertices[static_cast<std::size_t>(base.faces[f][(k + 1) % 3])] - base.vertices[a];
            const Vec3 e2 = base.vertices[static_cast<std::size_t>(base.faces[f][(k + 2) % 3])] - base.vertices[a];
            const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
            n[a] += angle * face_normal[f];
        }
    for (Vec3& d : n)
        if (d.norm() > 0) d.normalize();
    // Neighbours by edges; concave vertices (neighbours above the tangent plane on average) are
    // smoothed more: their directions converge, and smoothing spreads the convergence out.
    std::vector<std::vector<int>> ring(V);
    for (const Tri& t : base.faces)
        for (int k = 0; k < 3; ++k) {
            ring[static_cast<std::size_t>(t[k])].push_back(t[(k + 1) % 3]);
            ring[static_cast<std::size_t>(t[(k + 1) % 3])].push_back(t[k]);
        }
    std::vector<double> weight(V, 0.2);
    for (std::size_t v = 0; v < V; ++v) {
        auto& r = ring[v];
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
        double above = 0.0, len = 0.0;
        for (int w : r) {
            above += (base.vertices[static_cast<std::size_t>(w)] - base.vertices[v]).dot(n[v]);
            len += (base.vertices[static_cast<std::size_t>(w)] - base.vertices[v]).norm();
        }
        if (len > 0 && above / len > 0.02) weight[v] = 0.6;
    }
    auto worst_cos = [&](std::size_t v, const Vec3& d) {
        double c = 1.0;
        for (int f : vertex_faces[v]) c = std::min(c, d.dot(face_normal[static_cast<std::size_t>(f)]));
        return c;
    };
    dir = n;
    // Jacobi steps; with `steps`, vertex v takes steps[v] of them (none where 0).
    auto smooth = [&](int rounds, const std::vector<int>* steps) {
        for (int it = 0; it < rounds; ++it) {
            std::vector<Vec3> next = dir;
            for (std::size_t v = 0; v < V; ++v) {
                if (ring[v].empty() || (steps && (*steps)[v] <= it)) continue;
                Vec3 avg = Vec3::Zero();
                for (int w : ring[v]) avg += dir[static_cast<std::size_t>(w)];
                Vec3 d = (1.0 - weight[v]) * dir[v] + weight[v] * avg.normalized();
                if (d.norm() == 0) continue;
                d.normalize();
                if (worst_cos(v, d) >= std::max(kMinDirectionCos, std::min(0.5, worst_cos(v, dir[v])))) next[v] = d;
            }
            dir.swap(next);
        }
    };
    smooth(kDirectionSteps, nullptr);
    // Bumpy bases (a scan's skin, with bumps narrower than H): five steps leave neighbouring
    // directions turned against each other, so prisms at full height invert and the shell is
    // lowered far around them (the armadillo: 44% of its area at the chain mail's height). Where a
    // prism inverts at full height, the directions within kBumpyReach H of it are smoothed further,
    // each vertex by as many steps as spread a direction over about H along its edges
    // (5 (H / its mean edge)^2, at most kBumpySteps). Each connected patch of such vertices keeps
    // its smoothing only when at most kBumpyKeep of the patch's inverted prisms are left: bumps
    // are mended so, while a concave place wider than the bumps (a mouth, an eye socket) is not,
    // and there smoothing would only turn the directions off the normals (smoothing every vertex
    // more, session 26, or every patch tried, session 34, lost rings on the camelhead). Up to
    // kBumpyRounds rounds; a patch refused is left as it is in later rounds.
    build_tets();
    top.resize(V);
    std::vector<double> mean_edge(V, 0.0);
    for (std::size_t v = 0; v < V; ++v) {
        for (int w : ring[v]) mean_edge[v] += (base.vertices[static_cast<std::size_t>(w)] - base.vertices[v]).norm();
        if (!ring[v].empty()) mean_edge[v] /= static_cast<double>(ring[v].size());
    }
    auto inverted = [&] {  // per face: its prism at full height inverts or flattens
        for (std::size_t v = 0; v < V; ++v) top[v] = base.vertices[v] + H * dir[v];
        std::vector<char> bad(F, 0);
        for (std::size_t f = 0; f < F; ++f) {
            const double straight = face_area[f] * H / 3.0;
            for (int k = 0; k < 3 && !bad[f]; ++k) bad[f] = static_cast<char>(!(world_volume(f, k) > kMinWorldVolume * straight));
        }
        return bad;
    };
    std::vector<char> kept(V, 0);  // vertices whose smoothing was refused stay as they are
    std::vector<char> bad = inverted();
    for (int round = 0; round < kBumpyRounds; ++round) {
        // Vertices within reach of an inverted prism (Dijkstra along edges).
        std::vector<double> dist(V, std::numeric_limits<double>::infinity());
        using Item = std::pair<double, int>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        for (std::size_t f = 0; f < F; ++f)
            if (bad[f])
                for (int k = 0; k < 3; ++k)
                    if (const auto v = static_cast<std::size_t>(base.faces[f][k]); !kept[v] && dist[v] > 0) {
                        dist[v] = 0.0;
                        queue.emplace(0.0, static_cast<int>(v));
                    }
        if (queue.empty()) break;
        const double reach = kBumpyReach * H;
        while (!queue.empty()) {
            const auto [d, v] = queue.top();
            queue.pop();
            if (d > dist[static_cast<std::size_t>(v)]) continue;
            for (int w : ring[static_cast<std::size_t>(v)])
                if (const double dw = d + (base.vertices[static_cast<std::size_t>(w)] - base.vertices[static_cast<std::size_t>(v)]).norm();
                    !kept[static_cast<std::size_t>(w)] && dw <= reach && dw < dist[static_cast<std::size_t>(w)]) {
                    dist[static_cast<std::size_t>(w)] = dw;
                    queue.emplace(dw, w);
                }
        }
        // Connected patches of them.
        std::vector<int> patch(V, -1);
        int patches = 0;
        for (std::size_t s = 0; s < V; ++s) {
            if (!(dist[s] <= reach) || patch[s] >= 0) continue;
            std::vector<std::size_t> stack{s};
            patch[s] = patches;
            while (!stack.empty()) {
                const std::size_t v = stack.back();
                stack.pop_back();
                for (int w : ring[v])
                    if (dist[static_cast<std::size_t>(w)] <= reach && patch[static_cast<std::size_t>(w)] < 0) {
                        patch[static_cast<std::size_t>(w)] = patches;
                        stack.push_back(static_cast<std::size_t>(w));
                    }
            }
            ++patches;
        }
        auto count = [&](const std::vector<char>& b) {  // inverted prisms per patch
            std::vector<int> n(static_cast<std::size_t>(patches), 0);
            for (std::size_t f = 0; f < F; ++f) {
                if (!b[f]) continue;
                int p = -1;
                for (int k = 0; k < 3 && p < 0; ++k) p = patch[static_cast<std::size_t>(base.faces[f][k])];
                if (p >= 0) ++n[static_cast<std::size_t>(p)];
            }
            return n;
        };
        const std::vector<int> before = count(bad);
        std::vector<int> steps(V, 0);
        int most = 0;
        for (std::size_t v = 0; v < V; ++v) {
            if (patch[v] < 0 || !(mean_edge[v] > 0.0)) continue;
            const double r = H / mean_edge[v];
            steps[v] = static_cast<int>(std::clamp(5.0 * r * r, static_cast<double>(kDirectionSteps), static_cast<double>(kBumpySteps)));
            most = std::max(most, steps[v]);
        }
        const std::vector<Vec3> old = dir;
        smooth(most, &steps);
        bad = inverted();
        const std::vector<int> after = count(bad);
        bool any = false;
        for (std::size_t v = 0; v < V; ++v)
            if (const int p = patch[v]; p >= 0 && after[static_cast<std::size_t>(p)] > kBumpyKeep * before[static_cast<std::size_t>(p)]) {
                dir[v] = old[v];
                kept[v] = 1;
                any = true;
            }
        if (any) bad = inverted();
    }
    // Repair directions that do not see every incident face from outside: the direction that best
    // sees them all (maximising the least cosine) lies on a face normal or is equidistant from two
    // or three of them; all such candidates are tried.
    for (std::size_t v = 0; v < V; ++v) {
        if (vertex_faces[v].empty()) continue;
        if (!(dir[v].norm() > 0)) dir[v] = face_normal[static_cast<std::size_t>(vertex_faces[v][0])];
        if (worst_cos(v, dir[v]) >= kMinDirectionCos) continue;
        std::vector<Vec3> normals;
        for (int f : vertex_faces[v])
            if (face_normal[static_cast<std::size_t>(f)].norm() > 0) normals.push_back(face_normal[static_cast<std::size_t>(f)]);
        if (normals.empty()) continue;
        Vec3 best;
        shell::best_visibility(normals, dir[v], &best);
        dir[v] = best;
    }
}

// ---------------------------------------------------------------------------------------------
// 2. Offset heights

void ShellMap::Impl::limit_heights() {
    const std::size_t V = base.vertices.size(), F = base.faces.size();
    height.assign(V, H);
    // (a) Clearance along the direction: a ray must not meet another part of the base soon.
    const SM base_sm = to_cgal(base);
    using Primitive = CGAL::AABB_face_graph_triangle_primitive<SM>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
    const Tree tree(faces(base_sm).first, faces(base_sm).second, base_sm);
    {
        for (std::size_t v = 0; v < V; ++v) {
            if (vertex_faces[v].empty()) continue;
            const Vec3& p = base.vertices[v];
            const Vec3 q = p + dir[v];
            const K::Ray_3 ray(K::Point_3(p.x(), p.y(), p.z()), K::Point_3(q.x(), q.y(), q.z()));
            const auto& incident = vertex_faces[v];
            auto skip = [&](SM::Face_index f) { return std::find(incident.begin(), incident.end(), static_cast<int>(f.idx())) != incident.end(); };
            const auto hit = tree.first_intersection(ray, skip);
            if (!hit) continue;
            double t = std::numeric_limits<double>::infinity();
            if (const K::Point_3* pt = boost::get<K::Point_3>(&hit->first))
                t = std::sqrt(CGAL::squared_distance(*pt, ray.source()));
            else if (const K::Segment_3* sg = boost::get<K::Segment_3>(&hit->first))
                t = std::sqrt(std::min(CGAL::squared_distance(sg->source(), ray.source()), CGAL::squared_distance(sg->target(), ray.source())));
            height[v] = std::max(kMinHeight * H, std::min(height[v], t / kRayClearance));
        }
    }
    std::vector<std::vector<std::pair<int, double>>> edges(V);
    for (const Tri& t : base.faces)
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::size_t>(t[k]), b = static_cast<std::size_t>(t[(k + 1) % 3]);
            const double len = (base.vertices[a] - base.vertices[b]).norm();
            edges[a].emplace_back(static_cast<int>(b), len);
            edges[b].emplace_back(static_cast<int>(a), len);
        }
    // (b) Slope limit: Dijkstra from the lowest heights.
    auto limit_slope = [&] {
        using Item = std::pair<double, int>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        for (std::size_t v = 0; v < V; ++v)
            if (height[v] < H) queue.emplace(height[v], static_cast<int>(v));
        while (!queue.empty()) {
            const auto [h, v] = queue.top();
            queue.pop();
            if (h > height[static_cast<std::size_t>(v)]) continue;
            for (const auto& [w, len] : edges[static_cast<std::size_t>(v)]) {
                const double cap = h + kHeightSlope * len;
                if (cap < height[static_cast<std::size_t>(w)]) {
                    height[static_cast<std::size_t>(w)] = cap;
                    queue.emplace(cap, w);
                }
            }
        }
    };
    auto update_top = [&] {
        top.resize(V);
        for (std::size_t v = 0; v < V; ++v) top[v] = base.vertices[v] + height[v] * dir[v];
    };
    build_tets();
    for (int round = 0; round < 40; ++round) {
        limit_slope();
        update_top();
        bool changed = false;
        // (c) No inverted or flattened prism. To first order in the heights a prism's volumes are
        // positive when its directions point to the face's outer side, so lowering mends it; a
        // prism on a crumpled spot, where no direction sees every face from outside, cannot be
        // mended this way and is left (counted as inverted).
        for (int pass = 0; pass < 80; ++pass) {
            std::vector<char> lower(V, 0);
            bool any = false;
            for (std::size_t f = 0; f < F; ++f) {
                const Tri& t = base.faces[f];
                bool mendable = true;
                for (int k = 0; k < 3; ++k) mendable = mendable && dir[static_cast<std::size_t>(t[k])].dot(face_normal[f]) > 0.5 * kMinDirectionCos;
                if (!mendable) continue;
                const double hbar = (height[static_cast<std::size_t>(t[0])] + height[static_cast<std::size_t>(t[1])] + height[static_cast<std::size_t>(t[2])]) / 3.0;
                const double straight = face_area[f] * hbar / 3.0;
                bool bad = false;
                for (int k = 0; k < 3; ++k) bad = bad || !(world_volume(f, k) > kMinWorldVolume * straight);
                if (!bad) continue;
                for (int k = 0; k < 3; ++k) {
                    const auto v = static_cast<std::size_t>(t[k]);
                    if (height[v] > kMinPrismHeight * H) {
                        lower[v] = 1;
                        any = true;
                    }
                }
            }
            if (!any) break;
            for (std::size_t v = 0; v < V; ++v)
                if (lower[v]) {
                    height[v] = std::max(kMinPrismHeight * H, 0.8 * height[v]);
                    top[v] = base.vertices[v] + height[v] * dir[v];
                }
            changed = true;
        }
        // (d) The offset surface meets neither itself nor the base (exact, CGAL).
        Mesh both = base;
        const int off = static_cast<int>(V);
        for (std::size_t v = 0; v < V; ++v) both.vertices.push_back(top[v]);
        for (const Tri& t : base.faces) both.faces.emplace_back(t[0] + off, t[1] + off, t[2] + off);
        const SM sm = to_cgal(both);
        std::vector<std::pair<SM::Face_index, SM::Face_index>> pairs;
        PMP::self_intersections<CGAL::Parallel_if_available_tag>(faces(sm), sm, std::back_inserter(pairs));
        // lower: 1 down to the floor kMinHeight; 2 (the offset surface meeting itself, where
        // lowering cannot bring it onto the base) down to kMinPrismHeight.
        std::vector<char> lower(V, 0);
        for (const auto& [a, b] : pairs) {
            const char level = a.idx() >= F && b.idx() >= F ? 2 : 1;
            for (const SM::Face_index g : {a, b})
                if (g.idx() >= F)
                    for (int k = 0; k < 3; ++k) {
                        char& l = lower[static_cast<std::size_t>(base.faces[g.idx() - F][k])];
                        l = std::max(l, level);
                    }
        }
        // (e) No other part of the base inside a prism: a ridge or a thin part can enter through a
        // prism's side without touching its vertical edges or its offset face. Faces sharing a
        // corner with the prism's face are its neighbours and touch it by construction.
        std::vector<char> intruded(F, 0);
        tbb::parallel_for(std::size_t{0}, F, [&](std::size_t f) {
            const Tri& t = base.faces[f];
            CGAL::Bbox_3 box;
            std::array<K::Point_3, 6> p;
            for (int code = 0; code < 6; ++code) {
                const Vec3 q = world_point(f, code);
                p[static_cast<std::size_t>(code)] = K::Point_3(q.x(), q.y(), q.z());
                box += p[static_cast<std::size_t>(code)].bbox();
            }
            std::vector<SM::Face_index> near;
            tree.all_intersected_primitives(box, std::back_inserter(near));
            for (const SM::Face_index g : near) {
                const Tri& tg = base.faces[g.idx()];
                bool neighbour = false;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) neighbour = neighbour || tg[a] == t[b];
                if (neighbour) continue;
                const K::Triangle_3 tri(base_sm.point(SM::Vertex_index(static_cast<SM::size_type>(tg[0]))),
                                        base_sm.point(SM::Vertex_index(static_cast<SM::size_type>(tg[1]))),
                                        base_sm.point(SM::Vertex_index(static_cast<SM::size_type>(tg[2]))));
                for (int k = 0; k < 3 && !intruded[f]; ++k) {
                    const TetCodes& c = tets[f][static_cast<std::size_t>(k)];
                    const K::Tetrahedron_3 tet(p[static_cast<std::size_t>(c[0])], p[static_cast<std::size_t>(c[1])], p[static_cast<std::size_t>(c[2])],
                                               p[static_cast<std::size_t>(c[3])]);
                    if (!tet.is_degenerate() && CGAL::do_intersect(tet, tri)) intruded[f] = 1;
                }
                if (intruded[f]) break;
            }
        });
        std::size_t intrusions = 0;
        for (std::size_t f = 0; f < F; ++f)
            if (intruded[f]) {
                ++intrusions;
                for (int k = 0; k < 3; ++k) {
                    char& l = lower[static_cast<std::size_t>(base.faces[f][k])];
                    l = std::max<char>(l, 1);
                }
            }
        // Lowered to a floor: below 2% of H the offset would lie on the base, where rounding alone
        // makes faces meet; offset faces meeting each other may go further (what remains is counted).
        for (std::size_t v = 0; v < V; ++v)
            if (const double floor = (lower[v] == 2 ? kMinPrismHeight : kMinHeight) * H; lower[v] && height[v] > floor) {
                height[v] = std::max(floor, 0.7 * height[v]);
                top[v] = base.vertices[v] + height[v] * dir[v];
                changed = true;
            }
        offset_intersections = pairs.size() + intrusions;
        if (!changed) break;
    }
    update_top();
}

// ---------------------------------------------------------------------------------------------
// 3. Atlas

void ShellMap::Impl::build_atlas() {
    const std::size_t F = base.faces.size();
    std::vector<Vec3> centroid(F);
    for (std::size_t f = 0; f < F; ++f) centroid[f] = face_centroid(base, f);
    const double diag = bounding_box(base).size().norm();
    std::vector<std::array<int, 3>> open = nb;  // neighbours not yet in a chart
    chart_of_face.assign(F, -1);
    tex_corner.assign(F, {-1, -1, -1});
    int charts = 0;
    // Seeds follow face order, so neighbouring charts see similar curvature: each starts from 1.5
    // times the radius that passed last (each try costs a disc and an LSCM solve).
    double last = 0.15 * diag;
    for (std::size_t seed = 0; seed < F; ++seed) {
        if (chart_of_face[seed] >= 0) continue;
        double radius = std::min(0.15 * diag, 1.5 * last);
        quilt::FlatPatch flat;
        for (;;) {
            const std::vector<int> faces = quilt::grow_disc(base, open, centroid, static_cast<int>(seed), radius, opt.close_chart_slits);
            bool ok = quilt::flatten_lscm(base, faces, &flat);
            if (ok && faces.size() > 1) {
                for (const Tri& lt : flat.local) {
                    const Vec2 e1 = flat.uv[static_cast<std::size_t>(lt[1])] - flat.uv[static_cast<std::size_t>(lt[0])];
                    const Vec2 e2 = flat.uv[static_cast<std::size_t>(lt[2])] - flat.uv[static_cast<std::size_t>(lt[0])];
                    if (!(e1.x() * e2.y() - e1.y() * e2.x() > 0)) ok = false;
                }
                ok = ok && quilt::area_distortion(base, flat) <= kChartDistortion;
            }
            if (ok || faces.size() <= 1) {
                last = radius;
                if (!ok && !quilt::flatten_lscm(base, {static_cast<int>(seed)}, &flat)) {
                    // A zero-area face: a chart of its own with the corners where they fall.
                    flat = {};
                    flat.faces = {static_cast<int>(seed)};
                    flat.local = {Tri(0, 1, 2)};
                    for (int k = 0; k < 3; ++k) {
                        flat.vertices.push_back(base.faces[seed][k]);
                        flat.uv.push_back(base.vertices[static_cast<std::size_t>(base.faces[seed][k])].head<2>());
                    }
                }
                break;
            }
            radius *= 0.6;
        }
        const int first = static_cast<int>(tex_uv.size());
        for (std::size_t lv = 0; lv < flat.vertices.size(); ++lv) tex_uv.push_back(flat.uv[lv]);
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            const auto f = static_cast<std::size_t>(flat.faces[lf]);
            chart_of_face[f] = charts;
            for (int k = 0; k < 3; ++k) {
                // flat.local keeps the face's corner order.
                tex_corner[f][static_cast<std::size_t>(k)] = first + flat.local[lf][k];
            }
            for (int k = 0; k < 3; ++k) {
                const int g = nb[f][static_cast<std::size_t>(k)];
                if (g < 0) continue;
                for (int& back : open[static_cast<std::size_t>(g)])
                    if (back == static_cast<int>(f)) back = -1;
            }
        }
        ++charts;
    }
    stats.charts = charts;
    tex_top = tex_uv;
    tex_faces.assign(tex_uv.size(), {});
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) tex_faces[static_cast<std::size_t>(tex_corner[f][static_cast<std::size_t>(k)])].push_back(static_cast<int>(f));
    // Free: every face around the base vertex is in this chart and no edge around it is a border.
    std::vector<int> base_of(tex_uv.size(), -1);
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) base_of[static_cast<std::size_t>(tex_corner[f][static_cast<std::size_t>(k)])] = base.faces[f][k];
    std::vector<char> on_border(base.vertices.size(), 0);
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k)
            if (nb[f][static_cast<std::size_t>(k)] < 0) {
                on_border[static_cast<std::size_t>(base.faces[f][k])] = 1;
                on_border[static_cast<std::size_t>(base.faces[f][(k + 1) % 3])] = 1;
            }
    tex_free.assign(tex_uv.size(), 0);
    for (std::size_t t = 0; t < tex_uv.size(); ++t) {
        const auto v = static_cast<std::size_t>(base_of[t]);
        tex_free[t] = !on_border[v] && tex_faces[t].size() == vertex_faces[v].size();
        stats.free_offset_vertices += tex_free[t];
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Tetrahedra: Porumbescu et al.'s split, diagonals by vertex index.

void ShellMap::Impl::build_tets() {
    const std::size_t F = base.faces.size();
    tets.resize(F);
    for (std::size_t f = 0; f < F; ++f) {
        std::array<int, 3> c{0, 1, 2};
        std::sort(c.begin(), c.end(), [&](int x, int y) { return base.faces[f][x] < base.faces[f][y]; });
        const int a = c[0], b = c[1], cc = c[2];
        // Lateral quad (i, j) is cut along (min bottom, max top): a-b', b-c', a-c'.
        tets[f] = {TetCodes{a, b, cc, cc + 3}, TetCodes{a, b, b + 3, cc + 3}, TetCodes{a, a + 3, b + 3, cc + 3}};
        // Orientation: positive for a straight prism over the face (outward normal).
        const Vec3 up = face_normal[f];
        for (TetCodes& t : tets[f]) {
            auto p = [&](int code) {
                const Vec3 x = base.vertices[static_cast<std::size_t>(base.faces[f][code % 3])];
                return code < 3 ? x : Vec3(x + up);
            };
            if (det3(p(t[1]) - p(t[0]), p(t[2]) - p(t[0]), p(t[3]) - p(t[0])) < 0) std::swap(t[0], t[1]);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 5. Stretch (Eq. 8-9) and its optimisation

double ShellMap::Impl::stretch() const {
    double num = 0.0, vw = 0.0, vt = 0.0;
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const double w = world_volume(f, k), t = texture_volume(f, k);
            if (!(w > 0) || !(t > 0)) continue;
            num += frobenius2(f, k) / 3.0 * w;
            vw += w;
            vt += t;
        }
    if (!(vw > 0)) return 0.0;
    return std::sqrt(num / vw) * std::cbrt(vt / vw);
}

void ShellMap::Impl::optimise() {
    const std::size_t T = tex_uv.size();
    // Per free texture vertex: the tetrahedra (face, k) that use its offset corner, and a step.
    std::vector<std::vector<std::pair<int, int>>> uses(T);
    std::vector<double> step(T, 0.0), max_step(T, 0.0);
    std::vector<double> floor_volume;  // per (face, k): least texture volume allowed
    floor_volume.resize(3 * base.faces.size());
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) floor_volume[3 * f + static_cast<std::size_t>(k)] = 0.05 * texture_volume(f, k);
    for (std::size_t t = 0; t < T; ++t) {
        if (!tex_free[t]) continue;
        double shortest = std::numeric_limits<double>::infinity();
        for (int f : tex_faces[t]) {
            const auto fi = static_cast<std::size_t>(f);
            int corner = 0;
            while (tex_corner[fi][static_cast<std::size_t>(corner)] != static_cast<int>(t)) ++corner;
            for (int k = 0; k < 3; ++k) {
                const TetCodes& c = tets[fi][static_cast<std::size_t>(k)];
                if (std::find(c.begin(), c.end(), corner + 3) != c.end()) uses[t].emplace_back(f, k);
            }
            for (int j = 0; j < 3; ++j)
                if (j != corner)
                    shortest = std::min(shortest, (tex_uv[static_cast<std::size_t>(tex_corner[fi][static_cast<std::size_t>(j)])] - tex_uv[t]).norm());
        }
        step[t] = 0.25 * shortest;
        max_step[t] = 0.5 * shortest;
    }
    auto energy = [&](std::size_t t, bool* valid) {
        double e = 0.0;
        *valid = true;
        for (const auto& [f, k] : uses[t]) {
            const auto fi = static_cast<std::size_t>(f);
            if (!(texture_volume(fi, k) > floor_volume[3 * fi + static_cast<std::size_t>(k)])) {
                *valid = false;
                return e;
            }
            const double w = world_volume(fi, k);
            if (w > 0) e += frobenius2(fi, k) * w;
        }
        return e;
    };
    double total = 0.0;
    for (std::size_t t = 0; t < T; ++t) {
        bool valid = true;
        if (tex_free[t]) total += energy(t, &valid);
    }
    // Colours: free vertices that share a face get different colours. A vertex's energy involves
    // only the offset corners of its own faces, so the vertices of one colour move independently:
    // in parallel, each with its own random stream (results do not depend on scheduling).
    std::vector<int> colour(T, -1);
    std::vector<std::vector<std::size_t>> by_colour;
    for (std::size_t t = 0; t < T; ++t) {
        if (!tex_free[t] || uses[t].empty()) continue;
        std::vector<char> taken(by_colour.size() + 1, 0);
        for (int f : tex_faces[t])
            for (int k = 0; k < 3; ++k) {
                const int c = colour[static_cast<std::size_t>(tex_corner[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)])];
                if (c >= 0) taken[static_cast<std::size_t>(c)] = 1;
            }
        const auto c = static_cast<std::size_t>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
        if (c == by_colour.size()) by_colour.emplace_back();
        colour[t] = static_cast<int>(c);
        by_colour[c].push_back(t);
    }
    auto mix = [](std::uint64_t x) {  // splitmix64
        x += 0x9E3779B97F4A7C15ULL;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
        return x ^ (x >> 31);
    };
    std::vector<double> gain_of(T, 0.0);
    for (int pass = 0; pass < opt.max_passes; ++pass) {
        opt.reporter.report("shell map", 0.4 + 0.6 * pass / opt.max_passes);
        std::fill(gain_of.begin(), gain_of.end(), 0.0);
        for (const auto& group : by_colour)
            tbb::parallel_for(std::size_t{0}, group.size(), [&](std::size_t i) {
                const std::size_t t = group[i];
                if (step[t] < 1e-3 * max_step[t]) return;
                bool valid = true;
                const double e0 = energy(t, &valid);
                const Vec2 start = tex_top[t];
                std::mt19937_64 rng(mix(opt.seed ^ mix(static_cast<std::uint64_t>(pass) * T + t)));
                const double a = std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(rng);
                const Vec2 d(std::cos(a), std::sin(a));
                double best = e0;
                Vec2 best_pos = start;
                int best_level = -1;
                for (int level = 0; level < 3; ++level)
                    for (const double sign : {1.0, -1.0}) {
                        tex_top[t] = start + sign * std::ldexp(step[t], -level) * d;
                        const double e = energy(t, &valid);
                        if (valid && e < best) {
                            best = e;
                            best_pos = tex_top[t];
                            best_level = level;
                        }
                    }
                // Steps adapt: longer after a full step paid, shorter after nothing did.
                if (best_level == 0) step[t] = std::min(1.5 * step[t], max_step[t]);
                if (best_level < 0) step[t] *= 0.5;
                tex_top[t] = best_pos;
                gain_of[t] = e0 - best;
            });
        double gain = 0.0;
        for (double g : gain_of) gain += g;
        stats.optimisation_passes = pass + 1;
        if (!(gain > opt.min_relative_gain * total)) break;
        total -= gain;
    }
}

void ShellMap::Impl::build_grids() {
    std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(stats.charts));
    for (std::size_t f = 0; f < base.faces.size(); ++f) faces_of[static_cast<std::size_t>(chart_of_face[f])].push_back(static_cast<int>(f));
    grids.assign(faces_of.size(), {});
    auto footprint = [&](std::size_t f, Vec2* lo, Vec2* hi) {
        *lo = Vec2::Constant(std::numeric_limits<double>::infinity());
        *hi = -*lo;
        for (int code = 0; code < 6; ++code) {
            const Vec3 q = tex_point(f, code);
            *lo = lo->cwiseMin(q.head<2>());
            *hi = hi->cwiseMax(q.head<2>());
        }
    };
    for (std::size_t c = 0; c < faces_of.size(); ++c) {
        ChartGrid& g = grids[c];
        Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (int f : faces_of[c]) {
            Vec2 a, b;
            footprint(static_cast<std::size_t>(f), &a, &b);
            lo = lo.cwiseMin(a);
            hi = hi.cwiseMax(b);
        }
        const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-300});
        g.cell = extent / std::max(1.0, std::sqrt(static_cast<double>(faces_of[c].size())));
        g.lo = lo;
        g.nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / g.cell)) + 1);
        g.ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / g.cell)) + 1);
        g.bucket.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), {});
        for (int f : faces_of[c]) {
            Vec2 a, b;
            footprint(static_cast<std::size_t>(f), &a, &b);
            const int i0 = std::clamp(static_cast<int>(std::floor((a.x() - g.lo.x()) / g.cell)), 0, g.nx - 1);
            const int i1 = std::clamp(static_cast<int>(std::floor((b.x() - g.lo.x()) / g.cell)), 0, g.nx - 1);
            const int j0 = std::clamp(static_cast<int>(std::floor((a.y() - g.lo.y()) / g.cell)), 0, g.ny - 1);
            const int j1 = std::clamp(static_cast<int>(std::floor((b.y() - g.lo.y()) / g.cell)), 0, g.ny - 1);
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) g.bucket[static_cast<std::size_t>(j * g.nx + i)].push_back(f);
        }
    }
}

void ShellMap::Impl::collect_statistics() {
    const std::size_t V = base.vertices.size(), F = base.faces.size();
    stats.vertices = static_cast<int>(V);
    stats.prisms = static_cast<int>(F);
    stats.tetrahedra = static_cast<int>(3 * F);
    stats.inverted_world = stats.inverted_texture = 0;
    stats.offset_intersections = static_cast<int>(offset_intersections);
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) {
            if (!(world_volume(f, k) > 0)) ++stats.inverted_world;
            if (!(texture_volume(f, k) > 0)) ++stats.inverted_texture;
        }
    const double limit = 0.99 * H;
    std::vector<double> corner_area(V, 0.0);
    double total = 0.0, limited = 0.0;
    for (std::size_t f = 0; f < F; ++f) {
        total += face_area[f];
        for (int k = 0; k < 3; ++k) corner_area[static_cast<std::size_t>(base.faces[f][k])] += face_area[f] / 3.0;
    }
    stats.height_limited_vertices = 0;
    stats.min_height_ratio = 1.0;
    for (std::size_t v = 0; v < V; ++v) {
        if (vertex_faces[v].empty()) continue;
        stats.min_height_ratio = std::min(stats.min_height_ratio, height[v] / H);
        if (height[v] < limit) {
            ++stats.height_limited_vertices;
            limited += corner_area[v];
        }
    }
    stats.limited_area_fraction = total > 0 ? limited / total : 0.0;
    // Regions: edge-connected limited vertices.
    std::vector<int> region(V, -1);
    std::vector<ShellLimitedRegion> regions;
    for (std::size_t s = 0; s < V; ++s) {
        if (region[s] >= 0 || vertex_faces[s].empty() || height[s] >= limit) continue;
        ShellLimitedRegion r;
        std::vector<int> stack{static_cast<int>(s)};
        region[s] = static_cast<int>(regions.size());
        while (!stack.empty()) {
            const auto v = static_cast<std::size_t>(stack.back());
            stack.pop_back();
            r.centre += base.vertices[v];
            ++r.vertices;
            r.min_ratio = std::min(r.min_ratio, height[v] / H);
            for (int f : vertex_faces[v])
                for (int k = 0; k < 3; ++k) {
                    const auto w = static_cast<std::size_t>(base.faces[static_cast<std::size_t>(f)][k]);
                    if (region[w] < 0 && height[w] < limit) {
                        region[w] = region[s];
                        stack.push_back(static_cast<int>(w));
                    }
                }
        }
        r.centre /= r.vertices;
        regions.push_back(r);
    }
    std::stable_sort(regions.begin(), regions.end(), [](const ShellLimitedRegion& a, const ShellLimitedRegion& b) { return a.vertices > b.vertices; });
    if (regions.size() > 20) regions.resize(20);
    stats.limited_regions = std::move(regions);
}

void ShellMap::Impl::build() {
    auto t0 = quilt::Clock::now();
    const std::size_t V = base.vertices.size(), F = base.faces.size();
    nb = quilt::face_neighbours(base);
    face_normal = face_normals(base);
    face_area.resize(F);
    vertex_faces.assign(V, {});
    for (std::size_t f = 0; f < F; ++f) {
        face_area[f] = meshquilt::face_area(base, f);
        for (int k = 0; k < 3; ++k) vertex_faces[static_cast<std::size_t>(base.faces[f][k])].push_back(static_cast<int>(f));
    }
    opt.reporter.report("shell map", 0.0);
    offset_directions();
    opt.reporter.report("shell map", 0.1);
    limit_heights();
    opt.reporter.report("shell map", 0.3);
    build_atlas();
    opt.reporter.report("shell map", 0.4);
    stats.stretch_l2_initial = stretch();
    stats.seconds_build = quilt::seconds_since(t0);
    t0 = quilt::Clock::now();
    if (opt.optimise) optimise();
    stats.stretch_l2_final = stretch();
    stats.seconds_optimise = quilt::seconds_since(t0);
    build_grids();
    factors.resize(F);
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) factors[f][static_cast<std::size_t>(k)].compute(texture_edges(f, k));
    collect_statistics();
}

// ---------------------------------------------------------------------------------------------

ShellMap::ShellMap(const Mesh& base, const ShellOptions& options) : impl_(std::make_unique<Impl>()) {
    if (!std::isfinite(options.height) || options.height <= 0)
        throw InvalidInput("shell height must be positive, got " + quilt::num(options.height));
    if (base.faces.empty()) throw InvalidInput("shell map: the base has no faces");
    if (options.max_passes < 0) throw InvalidInput("shell map: the number of optimisation passes must be >= 0");
    impl_->base = base;
    impl_->opt = options;
    impl_->H = options.height;
    impl_->build();
}

ShellMap::~ShellMap() = default;
ShellMap::ShellMap(ShellMap&&) noexcept = default;
ShellMap& ShellMap::operator=(ShellMap&&) noexcept = default;

SurfacePoint ShellMap::Impl::unfold(SurfacePoint sp) const {
    // A point given beyond its face's edge (extrapolated coordinates) continues onto the face across
    // that edge, turned about the edge into its plane, up to 64 faces on (a point beyond a
    // corner walks round the corner's fan): extrapolating in the face's own plane would put it
    // under the neighbour at a convex edge, and into the base where the surface curves up.
    for (int step = 0; step < 64; ++step) {
        int k = 0;
        sp.bary.minCoeff(&k);
        if (sp.bary[k] >= 0) break;
        const auto f = static_cast<std::size_t>(sp.face);
        const int g = nb[f][static_cast<std::size_t>((k + 1) % 3)];  // across the edge opposite corner k
        if (g < 0) break;
        const Tri& t = base.faces[f];
        const Vec3 p = sp.bary[0] * base.vertices[static_cast<std::size_t>(t[0])] + sp.bary[1] * base.vertices[static_cast<std::size_t>(t[1])] +
                       sp.bary[2] * base.vertices[static_cast<std::size_t>(t[2])];
        const Vec3 a = base.vertices[static_cast<std::size_t>(t[(k + 1) % 3])], b = base.vertices[static_cast<std::size_t>(t[(k + 2) % 3])];
        const Vec3 e = b - a;
        if (!(e.squaredNorm() > 0)) break;
        const double along = (p - a).dot(e) / e.squaredNorm();
        const double out = (p - a - along * e).norm();  // distance beyond the edge
        const Tri& tg = base.faces[static_cast<std::size_t>(g)];
        int opposite = 0;
        while (tg[opposite] == t[(k + 1) % 3] || tg[opposite] == t[(k + 2) % 3]) ++opposite;
        const Vec3 c = base.vertices[static_cast<std::size_t>(tg[opposite])];
        Vec3 inward = (c - a) - (c - a).dot(e) / e.squaredNorm() * e;
        if (!(inward.norm() > 0)) break;
        const Vec3 q = a + along * e + out * inward.normalized();
        // Barycentric coordinates of q in g.
        const Vec3 g0 = base.vertices[static_cast<std::size_t>(tg[0])], g1 = base.vertices[static_cast<std::size_t>(tg[1])],
                   g2 = base.vertices[static_cast<std::size_t>(tg[2])];
        const Vec3 n = (g1 - g0).cross(g2 - g0);
        const double area2 = n.squaredNorm();
        if (!(area2 > 0)) break;
        const double l0 = (g1 - q).cross(g2 - q).dot(n) / area2;
        const double l2 = (g1 - g0).cross(q - g0).dot(n) / area2;
        sp.face = g;
        sp.bary = Vec3(l0, 1.0 - l0 - l2, l2);
    }
    return sp;
}

Vec3 ShellMap::map(const SurfacePoint& given) const {
    const Impl& m = *impl_;
    const SurfacePoint sp = given.bary.minCoeff() < 0 ? m.unfold(given) : given;
    const auto f0 = static_cast<std::size_t>(sp.face);
    Vec2 uv = Vec2::Zero();
    for (int k = 0; k < 3; ++k) uv += sp.bary[k] * m.tex_uv[static_cast<std::size_t>(m.tex_corner[f0][static_cast<std::size_t>(k)])];
    // Located with the height clamped to the shell; heights beyond it extrapolate that tetrahedron.
    const Vec3 p(uv.x(), uv.y(), sp.height), inside(uv.x(), uv.y(), std::clamp(sp.height, 0.0, m.H));
    // The prism of the point's face first, then prisms of the same chart around it (offset corners
    // moved by the optimisation lean prisms over their neighbours).
    double best_min = -std::numeric_limits<double>::infinity();
    std::size_t best_f = f0;
    int best_k = 0;
    auto try_face = [&](std::size_t f) {
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector4d lam = m.tet_coordinates(f, k, inside);
            if (!lam.allFinite()) continue;
            if (lam.minCoeff() > best_min) {
                best_min = lam.minCoeff();
                best_f = f;
                best_k = k;
            }
        }
    };
    try_face(f0);
    if (best_min < -1e-12) {
        // Offset corners moved by the optimisation lean prisms over their neighbours: the chart's
        // grid of prism footprints gives every prism that may hold the point.
        const ChartGrid& g = m.grids[static_cast<std::size_t>(m.chart_of_face[f0])];
        const int i = std::clamp(static_cast<int>(std::floor((uv.x() - g.lo.x()) / g.cell)), 0, g.nx - 1);
        const int j = std::clamp(static_cast<int>(std::floor((uv.y() - g.lo.y()) / g.cell)), 0, g.ny - 1);
        for (int f : g.bucket[static_cast<std::size_t>(j * g.nx + i)]) {
            if (static_cast<std::size_t>(f) != f0) try_face(static_cast<std::size_t>(f));
            if (best_min >= -1e-12) break;
        }
    }
    if (!(best_min > -std::numeric_limits<double>::infinity())) {
        // Only a degenerate prism (a zero-area face): interpolate along the offset directions.
        Vec3 out = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(m.base.faces[f0][k]);
            out += sp.bary[k] * (m.base.vertices[v] + (sp.height / m.H) * m.height[v] * m.dir[v]);
        }
        return out;
    }
    const Eigen::Vector4d lam = m.tet_coordinates(best_f, best_k, p);
    const TetCodes& c = m.tets[best_f][static_cast<std::size_t>(best_k)];
    Vec3 out = Vec3::Zero();
    for (int j = 0; j < 4; ++j) out += lam[j] * m.world_point(best_f, c[static_cast<std::size_t>(j)]);
    return out;
}

const ShellStatistics& ShellMap::statistics() const { return impl_->stats; }

Mesh ShellMap::offset_surface() const {
    Mesh m;
    m.vertices = impl_->top;
    m.faces = impl_->base.faces;
    return m;
}

const std::vector<double>& ShellMap::heights() const { return impl_->height; }

std::vector<ShellTet> ShellMap::tetrahedra() const {
    const Impl& m = *impl_;
    std::vector<ShellTet> out;
    out.reserve(3 * m.base.faces.size());
    for (std::size_t f = 0; f < m.base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            ShellTet t;
            for (int j = 0; j < 4; ++j) {
                t.texture[static_cast<std::size_t>(j)] = m.tex_point(f, m.tets[f][static_cast<std::size_t>(k)][static_cast<std::size_t>(j)]);
                t.world[static_cast<std::size_t>(j)] = m.world_point(f, m.tets[f][static_cast<std::size_t>(k)][static_cast<std::size_t>(j)]);
            }
            out.push_back(t);
        }
    return out;
}

double ShellMap::stretch_l2() const { return impl_->stretch(); }

}  // namespace meshquilt
