// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/patch.h"

#include "core/triangle_index.h"
#include "meshquilt/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace meshquilt::quilt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;

SM to_surface_mesh(const Mesh& m) {
    SM sm;
    sm.reserve(static_cast<SM::size_type>(m.vertices.size()), static_cast<SM::size_type>(3 * m.faces.size() / 2),
               static_cast<SM::size_type>(m.faces.size()));
    for (const Vec3& v : m.vertices) sm.add_vertex(K::Point_3(v.x(), v.y(), v.z()));
    for (const Tri& t : m.faces) {
        const SM::Face_index f = sm.add_face(SM::Vertex_index(static_cast<SM::size_type>(t[0])), SM::Vertex_index(static_cast<SM::size_type>(t[1])),
                                             SM::Vertex_index(static_cast<SM::size_type>(t[2])));
        if (f == SM::null_face()) throw BackendFailure("base mesh: a face could not be added to the halfedge structure (non-manifold?)");
    }
    return sm;
}
}  // namespace

std::vector<int> grow_disc(const Mesh& mesh, const std::vector<std::array<int, 3>>& nb, const std::vector<Vec3>& centroids, int seed,
                           double radius, bool close_slits) {
    std::vector<int> region;
    // Sparse per-call state: faces and vertices touched, in maps keyed by index.
    std::unordered_map<int, double> dist;
    std::unordered_map<int, int> tries;
    std::unordered_set<int> in;
    std::unordered_map<int, int> vcount;
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    queue.emplace(0.0, seed);
    dist[seed] = 0.0;
    while (!queue.empty()) {
        const auto [d, f] = queue.top();
        queue.pop();
        if (in.count(f) || d > radius) continue;
        const auto fi = static_cast<std::size_t>(f);
        int shared_edges = 0, shared_vertices = 0;
        for (int k = 0; k < 3; ++k) {
            const int g = nb[fi][static_cast<std::size_t>(k)];
            if (g >= 0 && in.count(g)) ++shared_edges;
            auto it = vcount.find(mesh.faces[fi][k]);
            if (it != vcount.end() && it->second > 0) ++shared_vertices;
        }
        const bool ok = region.empty() || (shared_edges == 1 && shared_vertices == 2) || (shared_edges == 2 && shared_vertices == 3);
        if (!ok) {
            ++tries[f];
            continue;
        }
        in.insert(f);
        region.push_back(f);
        for (int k = 0; k < 3; ++k) ++vcount[mesh.faces[fi][k]];
        for (int g : nb[fi]) {
            if (g < 0 || in.count(g) || tries[g] > 3) continue;
            const double nd = d + (centroids[static_cast<std::size_t>(g)] - centroids[fi]).norm();
            auto it = dist.find(g);
            // Re-queue at a shorter or equal distance, and a face refused earlier whenever another
            // of its neighbours joins, at its shortest distance: it would have pinched the disc then
            // (one edge shared and its third corner already taken) but may close it now (two edges
            // shared). Refused faces re-queued only on a path as short as before were left out for
            // good, and the fronts passing on both sides of them left a slit into the disc, a cut
            // next to its seed: on a thin capsule's caps, patches marked 1-20 faces each (step 9)
            // and the run took 16 minutes instead of 21 s (docs/surface.md, step 4).
            if (it == dist.end() || nd <= it->second || (close_slits && tries[g] > 0)) {
                dist[g] = std::min(nd, it == dist.end() ? nd : it->second);
                queue.emplace(dist[g], g);
            }
        }
    }
    return region;
}

namespace {
/// Sine of a face's smallest angle (the angle opposite its shortest edge: 2 * area over the product
/// of the two longer edges) and its longest edge; 0 for a degenerate face.
std::pair<double, double> thinness(const SM& sm, SM::Face_index f) {
    std::array<K::Point_3, 3> p;
    int k = 0;
    for (SM::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) p[static_cast<std::size_t>(k++)] = sm.point(v);
    std::array<double, 3> e{std::sqrt(CGAL::squared_distance(p[0], p[1])), std::sqrt(CGAL::squared_distance(p[1], p[2])),
                            std::sqrt(CGAL::squared_distance(p[2], p[0]))};
    std::sort(e.begin(), e.end());
    const double twice_area = std::sqrt(CGAL::cross_product(p[1] - p[0], p[2] - p[0]).squared_length());
    const double denom = e[1] * e[2];
    return {denom > 0.0 ? twice_area / denom : 0.0, e[2]};
}

/// Flips the edge opposite the flat angle of each cap (a face with an angle over kCapAngleDegrees,
/// its corners nearly on one line) when the two new faces turn less than 60 degrees from the face
/// that was across the edge and neither is a cap; an edge on the border or `sharp`, or whose new
/// edge exists already, is never flipped. The remesher's flips leave caps along constrained
/// polylines whose vertices lie nearly on one line (a hole's rim of 48 sides split into collinear
/// pieces): a face on the line, its normal noise, and a face bridging a corner of the rim from the
/// hole's side, both folds of the base and inverted prisms of the shell. The surface moves by at
/// most a cap's height. (CGAL 5.5's experimental remove_almost_degenerate_faces left two of six
/// such caps on a refined plate with three holes, as "not the best diagonal".)
template <class SharpMap>
void flip_caps(SM& sm, const SharpMap& sharp) {
    const double max_cos = std::cos(kCapAngleDegrees * M_PI / 180.0);
    auto cap_edge = [&](SM::Face_index f) { return PMP::is_cap_triangle_face(f, sm, max_cos); };
    auto normal = [&](SM::Face_index f) {
        const SM::Halfedge_index h = sm.halfedge(f);
        const K::Point_3 &p = sm.point(sm.source(h)), &q = sm.point(sm.target(h)), &r = sm.point(sm.target(sm.next(h)));
        const K::Vector_3 n = CGAL::cross_product(q - p, r - p);
        const double l = std::sqrt(n.squared_length());
        return l > 0.0 ? n / l : n;
    };
    for (int round = 0; round < 4; ++round) {
        bool flipped = false;
        for (SM::Face_index f : sm.faces()) {
            const SM::Halfedge_index h = cap_edge(f);
            if (h == SM::null_halfedge() || sharp[sm.edge(h)] || sm.is_border(sm.edge(h))) continue;
            const SM::Face_index g = sm.face(sm.opposite(h));
            if (cap_edge(g) != SM::null_halfedge()) continue;
            const SM::Vertex_index b = sm.target(sm.next(h)), d = sm.target(sm.next(sm.opposite(h)));
            if (b == d || CGAL::halfedge(b, d, sm).second) continue;
            const K::Vector_3 across = normal(g);
            CGAL::Euler::flip_edge(h, sm);
            const SM::Face_index f1 = sm.face(h), f2 = sm.face(sm.opposite(h));
            if (cap_edge(f1) == SM::null_halfedge() && cap_edge(f2) == SM::null_halfedge() && normal(f1) * across > 0.5 && normal(f2) * across > 0.5) {
                flipped = true;
                continue;
            }
            CGAL::Euler::flip_edge(h, sm);  // back as it was
        }
        if (!flipped) break;
    }
}

/// Remeshes the thin and the large faces (see refine_long_edges) with one ring of faces around them;
/// returns the number of input faces in the remeshed region.
int remesh_thin_faces(SM& sm, double max_length) {
    const double min_sine = std::sin(kMinCellAngleDegrees * M_PI / 180.0);
    auto in_region = sm.add_property_map<SM::Face_index, char>("f:thin_region", 0).first;
    auto is_thin = sm.add_property_map<SM::Face_index, char>("f:thin", 0).first;
    bool any = false;
    double total_area = 0.0, thin_area = 0.0;
    for (SM::Face_index f : sm.faces()) {
        const auto [sine, longest] = thinness(sm, f);
        const double area = PMP::face_area(f, sm);
        total_area += area;
        if (sine < min_sine && longest > kThinFaceMinLength * max_length) {
            is_thin[f] = 1;
            any = true;
            thin_area += area;
        }
    }
    // Large faces (a cube's, a low-poly model's) are remeshed whatever their shape: split_long_edges
    // only splits edges, so a face many cells across would become a fan of slivers that reach across it.
    std::vector<SM::Face_index> thin;
    for (SM::Face_index f : sm.faces())
        if (!is_thin[f] && thinness(sm, f).second > kLargeFaceCells * max_length) thin.push_back(f);
    // Clusters of thin faces (sharing edges) smaller than kThinClusterFootprints of a footprint (six
    // cells across) lie within one patch among well-shaped faces, and are left as they are, unless
    // thin faces cover kThinBaseShare of the base or more.
    const bool all_clusters = thin_area >= kThinBaseShare * total_area;
    if (any) {
        auto seen = sm.add_property_map<SM::Face_index, char>("f:seen", 0).first;
        const double footprint = 36.0 * max_length * max_length;
        for (SM::Face_index f0 : sm.faces()) {
            if (!is_thin[f0] || seen[f0]) continue;
            std::vector<SM::Face_index> cluster{f0};
            seen[f0] = 1;
            double area = 0.0;
            for (std::size_t i = 0; i < cluster.size(); ++i) {
                area += PMP::face_area(cluster[i], sm);
                for (SM::Halfedge_index h : CGAL::halfedges_around_face(sm.halfedge(cluster[i]), sm)) {
                    const SM::Face_index g = sm.face(sm.opposite(h));
                    if (g != SM::null_face() && is_thin[g] && !seen[g]) {
                        seen[g] = 1;
                        cluster.push_back(g);
                    }
                }
            }
            if (all_clusters || area >= kThinClusterFootprints * footprint) thin.insert(thin.end(), cluster.begin(), cluster.end());
        }
        sm.remove_property_map(seen);
    }
    sm.remove_property_map(is_thin);
    if (thin.empty()) {
        sm.remove_property_map(in_region);
        return 0;
    }
    // One ring of faces around each thin face gives the remesher room to flip and move vertices.
    std::vector<SM::Face_index> region;
    for (SM::Face_index f : thin)
        for (SM::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm))
            for (SM::Face_index g : CGAL::faces_around_target(sm.halfedge(v), sm))
                if (g != SM::null_face() && !in_region[g]) {
                    in_region[g] = 1;
                    region.push_back(g);
                }
    // Target: the edge of an equilateral triangle of the region's mean area (about as many faces as
    // before, well shaped), at most kThinFaceTarget of the cell edge (the mean edge that splitting
    // leaves elsewhere: halves of edges up to twice the cell edge).
    double area = 0.0;
    for (SM::Face_index f : region) area += PMP::face_area(f, sm);
    const double equilateral = std::sqrt(4.0 * area / (std::sqrt(3.0) * static_cast<double>(region.size())));
    // Large faces alone are remeshed at the cell edge (split_long_edges then halves what is longer).
    const double target = std::min((thin_area > 0.0 ? kThinFaceTarget : kLargeFaceTarget) * max_length, equilateral);
    // Sharp edges (and the mesh's boundary, by default) keep their polylines: split, never collapsed
    // or flipped; their corners stay.
    auto sharp = sm.add_property_map<SM::Edge_index, bool>("e:sharp", false).first;
    PMP::detect_sharp_edges(sm, kSharpEdgeDegrees, sharp);
    auto corner = sm.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
    for (SM::Vertex_index v : sm.vertices()) {
        int n = 0;
        for (SM::Halfedge_index h : CGAL::halfedges_around_target(v, sm)) n += sharp[sm.edge(h)] ? 1 : 0;
        corner[v] = n != 0 && n != 2;
    }
    if (target > 0.0)
        PMP::isotropic_remeshing(region, target, sm,
                                 CGAL::parameters::number_of_iterations(3)
                                     .edge_is_constrained_map(sharp)
                                     .vertex_is_constrained_map(corner)
                                     .collapse_constraints(false));
    if (target > 0.0) flip_caps(sm, sharp);
    const auto n = static_cast<int>(region.size());
    sm.remove_property_map(in_region);
    sm.remove_property_map(sharp);
    sm.remove_property_map(corner);
    sm.collect_garbage();
    return n;
}
}  // namespace

Mesh refine_long_edges(const Mesh& mesh, double max_length, std::vector<int>* parent, int* thin_remeshed) {
    SM sm = to_surface_mesh(mesh);
    const int thin = remesh_thin_faces(sm, max_length);
    if (thin_remeshed) *thin_remeshed = thin;
    PMP::split_long_edges(edges(sm), max_length, sm);
    Mesh out;
    out.vertices.reserve(sm.number_of_vertices());
    for (SM::Vertex_index v : sm.vertices()) {
        const K::Point_3& p = sm.point(v);
        out.vertices.emplace_back(p.x(), p.y(), p.z());
    }
    for (SM::Face_index f : sm.faces()) {
        Tri t;
        int k = 0;
        for (SM::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = static_cast<int>(v.idx());
        out.faces.push_back(t);
    }
    if (parent) {
        // New faces lie inside input faces; the closest input face to a centroid is its parent.
        const TriangleIndex index(mesh);
        parent->resize(out.faces.size());
        for (std::size_t f = 0; f < out.faces.size(); ++f) (*parent)[f] = index.closest(face_centroid(out, f)).face;
    }
    return out;
}

namespace {

/// CGAL's default solver for ARAP (sparse LU) that factors a matrix once: ARAP's global step solves
/// the same cotangent matrix for u and for v in every iteration, and CGAL's Eigen_solver_traits
/// factors it anew for each solve (2 x iterations LU factorisations of one matrix per patch).
class CachedLUTraits : public CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType>> {
    using Base = CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType>>;

public:
    using Base::linear_solver;
    bool linear_solver(const Matrix& A, const Vector& B, Vector& X, NT& D) {
        D = 1;
        const auto& m = A.eigen_object();
        // Same matrix as the factored one: same shape, pattern and values (compared, not assumed:
        // the traits object outlives one parameterisation only by accident of CGAL's code).
        const bool same = cached_->rows == m.rows() && cached_->cols == m.cols() && cached_->values.size() == static_cast<std::size_t>(m.nonZeros()) &&
                          std::equal(cached_->values.begin(), cached_->values.end(), m.valuePtr()) &&
                          std::equal(cached_->inner.begin(), cached_->inner.end(), m.innerIndexPtr()) &&
                          std::equal(cached_->outer.begin(), cached_->outer.end(), m.outerIndexPtr());
        if (!same) {
            if (!m.isCompressed()) return Base::linear_solver(A, B, X, D);
            solver().compute(m);
            if (solver().info() != Eigen::Success) {
                *cached_ = Cache();
                return false;
            }
            cached_->rows = m.rows();
            cached_->cols = m.cols();
            cached_->values.assign(m.valuePtr(), m.valuePtr() + m.nonZeros());
            cached_->inner.assign(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
            cached_->outer.assign(m.outerIndexPtr(), m.outerIndexPtr() + m.outerSize() + 1);
        }
        X = solver().solve(B);
        return solver().info() == Eigen::Success;
    }

private:
    struct Cache {
        Eigen::Index rows = -1, cols = -1;
        std::vector<double> values;
        std::vector<int> inner, outer;
    };
    std::shared_ptr<Cache> cached_ = std::make_shared<Cache>();  // CGAL copies the traits by value
};

/// LSCM (arap_iterations 0) or ARAP started from it; see flatten_lscm.
bool flatten(const Mesh& mesh, const std::vector<int>& faces, FlatPatch* patch, int arap_iterations) {
    FlatPatch p;
    p.faces = faces;
    std::unordered_map<int, int> local;
    Mesh sub;
    for (int f : faces) {
        Tri t;
        for (int k = 0; k < 3; ++k) {
            const int v = mesh.faces[static_cast<std::size_t>(f)][k];
            auto it = local.find(v);
            if (it == local.end()) {
                it = local.emplace(v, static_cast<int>(p.vertices.size())).first;
                p.vertices.push_back(v);
                sub.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
            }
            t[k] = it->second;
        }
        p.local.push_back(t);
        sub.faces.push_back(t);
    }
    p.uv.assign(p.vertices.size(), Vec2::Zero());
    if (faces.size() == 1) {
        // One triangle: its own plane.
        const Vec3 a = sub.vertices[0], b = sub.vertices[1], c = sub.vertices[2];
        const Vec3 e1 = (b - a).normalized(), n = (b - a).cross(c - a).normalized(), e2 = n.cross(e1);
        p.uv[1] = Vec2((b - a).norm(), 0.0);
        p.uv[2] = Vec2((c - a).dot(e1), (c - a).dot(e2));
    } else {
        SM sm = to_surface_mesh(sub);
        const auto border = PMP::longest_border(sm).first;
        if (border == SM::null_halfedge()) return false;
        auto uvmap = sm.add_property_map<SM::Vertex_index, K::Point_2>("v:uv").first;
        SMP::Error_code err;
        if (arap_iterations > 0) {
            // lambda 1000 (CGAL's default): close to pure ARAP; its start is LSCM's map.
            using ARAP = SMP::ARAP_parameterizer_3<SM, SMP::Two_vertices_parameterizer_3<SM>, CachedLUTraits>;
            err = SMP::parameterize(sm, ARAP(ARAP::Border_parameterizer(), CachedLUTraits(), 1000.0, static_cast<unsigned>(arap_iterations)), border, uvmap);
        } else {
            err = SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SM>(), border, uvmap);
        }
        if (err != SMP::OK) return false;
        for (SM::Vertex_index v : sm.vertices()) p.uv[v.idx()] = Vec2(uvmap[v].x(), uvmap[v].y());
    }
    // Scale to the 3D area; mirror if LSCM turned the patch over.
    double flat = 0.0, area = 0.0;
    for (std::size_t f = 0; f < p.local.size(); ++f) {
        const Tri& t = p.local[f];
        const Vec2 e1 = p.uv[static_cast<std::size_t>(t[1])] - p.uv[static_cast<std::size_t>(t[0])];
        const Vec2 e2 = p.uv[static_cast<std::size_t>(t[2])] - p.uv[static_cast<std::size_t>(t[0])];
        flat += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
        area += face_area(sub, f);
    }
    if (!std::isfinite(flat) || flat == 0.0 || area <= 0.0) return false;
    const double s = std::sqrt(area / std::fabs(flat));
    for (Vec2& q : p.uv) q = Vec2(q.x() * s, (flat < 0 ? -q.y() : q.y()) * s);
    for (const Vec2& q : p.uv)
        if (!q.allFinite()) return false;
    *patch = std::move(p);
    return true;
}

}  // namespace

bool flatten_lscm(const Mesh& mesh, const std::vector<int>& faces, FlatPatch* patch) { return flatten(mesh, faces, patch, 0); }

bool flatten_arap(const Mesh& mesh, const std::vector<int>& faces, FlatPatch* patch, int iterations) {
    return flatten(mesh, faces, patch, std::max(1, iterations));
}

double area_distortion(const Mesh& mesh, const FlatPatch& p) {
    std::vector<std::pair<double, double>> ratio;  // (flat / 3D, 3D area)
    double total = 0.0;
    for (std::size_t f = 0; f < p.local.size(); ++f) {
        const Tri& t = p.local[f];
        const Vec2 e1 = p.uv[static_cast<std::size_t>(t[1])] - p.uv[static_cast<std::size_t>(t[0])];
        const Vec2 e2 = p.uv[static_cast<std::size_t>(t[2])] - p.uv[static_cast<std::size_t>(t[0])];
        const double a = face_area(mesh, static_cast<std::size_t>(p.faces[f]));
        if (a <= 0) continue;
        const double flat = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
        ratio.emplace_back(flat / a, a);
        total += a;
    }
    if (ratio.empty()) return 1.0;
    std::sort(ratio.begin(), ratio.end());
    auto quantile = [&](double q) {
        double acc = 0.0;
        for (const auto& [r, a] : ratio) {
            acc += a;
            if (acc >= q * total) return r;
        }
        return ratio.back().first;
    };
    const double lo = quantile(0.02), hi = quantile(0.98);
    if (lo <= 0) return std::numeric_limits<double>::infinity();  // folded faces
    return hi / lo;
}

PatchLocator::PatchLocator(const FlatPatch& patch) : patch_(patch) {
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& q : patch.uv) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-12});
    const double n = std::max(1.0, std::sqrt(static_cast<double>(patch.local.size())));
    cell_ = extent / n;
    origin_ = lo;
    nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell_)) + 1);
    ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell_)) + 1);
    bucket_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
    for (std::size_t f = 0; f < patch.local.size(); ++f) {
        Vec2 a = patch.uv[static_cast<std::size_t>(patch.local[f][0])], b = a;
        for (int k = 1; k < 3; ++k) {
            a = a.cwiseMin(patch.uv[static_cast<std::size_t>(patch.local[f][k])]);
            b = b.cwiseMax(patch.uv[static_cast<std::size_t>(patch.local[f][k])]);
        }
        const int i0 = std::clamp(static_cast<int>((a.x() - origin_.x()) / cell_), 0, nx_ - 1);
        const int i1 = std::clamp(static_cast<int>((b.x() - origin_.x()) / cell_), 0, nx_ - 1);
        const int j0 = std::clamp(static_cast<int>((a.y() - origin_.y()) / cell_), 0, ny_ - 1);
        const int j1 = std::clamp(static_cast<int>((b.y() - origin_.y()) / cell_), 0, ny_ - 1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) bucket_[static_cast<std::size_t>(j * nx_ + i)].push_back(static_cast<int>(f));
    }
}

PatchLocator::Hit PatchLocator::locate(const Vec2& p, double reach) const {
    auto bary_of = [&](int f) {
        const Tri& t = patch_.local[static_cast<std::size_t>(f)];
        const Vec2 a = patch_.uv[static_cast<std::size_t>(t[0])], b = patch_.uv[static_cast<std::size_t>(t[1])],
                   c = patch_.uv[static_cast<std::size_t>(t[2])];
        const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
        if (det == 0.0) return Vec3(Vec3::Constant(-1e30));
        const Vec2 d = p - a;
        const double l1 = (d.x() * (c - a).y() - d.y() * (c - a).x()) / det;
        const double l2 = ((b - a).x() * d.y() - (b - a).y() * d.x()) / det;
        return Vec3(1.0 - l1 - l2, l1, l2);
    };
    const int ci = static_cast<int>(std::floor((p.x() - origin_.x()) / cell_));
    const int cj = static_cast<int>(std::floor((p.y() - origin_.y()) / cell_));
    Hit best;
    double best_out = std::numeric_limits<double>::infinity();
    const int rings = std::max(0, static_cast<int>(std::ceil(reach / cell_)));
    for (int r = 0; r <= rings; ++r) {
        for (int j = cj - r; j <= cj + r; ++j)
            for (int i = ci - r; i <= ci + r; ++i) {
                if (std::max(std::abs(i - ci), std::abs(j - cj)) != r) continue;
                if (i < 0 || j < 0 || i >= nx_ || j >= ny_) continue;
                for (int f : bucket_[static_cast<std::size_t>(j * nx_ + i)]) {
                    const Vec3 b = bary_of(f);
                    const double out = -std::min(0.0, b.minCoeff());
                    if (out == 0.0) return {f, b, true};
                    if (out < best_out) {
                        best_out = out;
                        best = {f, b, false};
                    }
                }
            }
        // A containing face would have been found in ring 0; nearest faces are found in the first
        // rings that hold any face.
        if (best.local_face >= 0 && r >= 1) break;
    }
    if (best.local_face < 0) return best;
    // Distance check: the point reconstructed from clamped coordinates.
    const Tri& t = patch_.local[static_cast<std::size_t>(best.local_face)];
    Vec3 cb = best.bary.cwiseMax(0.0);
    cb /= cb.sum();
    const Vec2 q = cb[0] * patch_.uv[static_cast<std::size_t>(t[0])] + cb[1] * patch_.uv[static_cast<std::size_t>(t[1])] +
                   cb[2] * patch_.uv[static_cast<std::size_t>(t[2])];
    if ((q - p).norm() > reach) return {};
    return best;
}

}  // namespace meshquilt::quilt
