// SPDX-License-Identifier: AGPL-3.0-or-later
#include "core/triangle_index.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <limits>

namespace meshquilt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Traits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

Point to_cgal(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

/// Sample points of the mesh (vertices and face centroids) for the kd-tree; each maps to the faces
/// around it (CSR arrays).
struct SampleCloud {
    std::vector<Vec3> points;
    std::vector<int> offset{0};
    std::vector<int> faces;
    [[nodiscard]] std::size_t kdtree_get_point_count() const { return points.size(); }
    [[nodiscard]] double kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][static_cast<int>(dim)]; }
    template <class B>
    bool kdtree_get_bbox(B&) const { return false; }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SampleCloud>, SampleCloud, 3, std::uint32_t>;

struct TriangleIndex::Impl {
    Mesh mesh;
    std::vector<Triangle> triangles;
    std::vector<Vec3> normals;
    Tree tree;
    SampleCloud cloud;
    std::unique_ptr<KdTree> kd;  ///< built on the first best_match (most indices only answer closest())
    std::once_flag kd_once;
    double max_edge = 0.0;
    void build_kd();
};

TriangleIndex::TriangleIndex() = default;
TriangleIndex::~TriangleIndex() = default;
TriangleIndex::TriangleIndex(TriangleIndex&&) noexcept = default;
TriangleIndex& TriangleIndex::operator=(TriangleIndex&&) noexcept = default;

TriangleIndex::TriangleIndex(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
    impl_->mesh = mesh;
    impl_->triangles.reserve(mesh.faces.size());
    for (const Tri& f : mesh.faces)
        impl_->triangles.emplace_back(to_cgal(mesh.vertices[f[0]]), to_cgal(mesh.vertices[f[1]]), to_cgal(mesh.vertices[f[2]]));
    impl_->normals = face_normals(mesh);
    if (!impl_->triangles.empty()) {
        impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
        impl_->tree.build();
        impl_->tree.accelerate_distance_queries();
    }
}

void TriangleIndex::Impl::build_kd() {
    // kd-tree over vertices and face centroids for the matching queries of Eq. 2.
    std::vector<std::vector<int>> faces_of(mesh.vertices.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            faces_of[static_cast<std::size_t>(mesh.faces[f][k])].push_back(static_cast<int>(f));
            max_edge = std::max(max_edge, (mesh.vertices[mesh.faces[f][k]] - mesh.vertices[mesh.faces[f][(k + 1) % 3]]).norm());
        }
    SampleCloud& c = cloud;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (faces_of[v].empty()) continue;
        c.points.push_back(mesh.vertices[v]);
        c.faces.insert(c.faces.end(), faces_of[v].begin(), faces_of[v].end());
        c.offset.push_back(static_cast<int>(c.faces.size()));
    }
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        c.points.push_back((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0);
        c.faces.push_back(static_cast<int>(f));
        c.offset.push_back(static_cast<int>(c.faces.size()));
    }
    if (!c.points.empty()) {
        kd = std::make_unique<KdTree>(3, c, nanoflann::KDTreeSingleIndexAdaptorParams(16));
        kd->buildIndex();
    }
}

bool TriangleIndex::empty() const { return !impl_ || impl_->triangles.empty(); }
const Mesh& TriangleIndex::mesh() const { return impl_->mesh; }
const Vec3& TriangleIndex::face_normal(int f) const { return impl_->normals[static_cast<std::size_t>(f)]; }

ClosestHit TriangleIndex::closest(const Vec3& p) const {
    if (empty()) return {-1, std::numeric_limits<double>::infinity(), p, Vec3::Zero()};
    const auto pp = impl_->tree.closest_point_and_primitive(to_cgal(p));
    ClosestHit hit;
    hit.face = static_cast<int>(pp.second - impl_->triangles.cbegin());
    const Tri& f = impl_->mesh.faces[static_cast<std::size_t>(hit.face)];
    const auto& V = impl_->mesh.vertices;
    hit.point = closest_point_on_triangle(p, V[f[0]], V[f[1]], V[f[2]], &hit.bary);
    hit.distance = (hit.point - p).norm();
    return hit;
}

ClosestHit TriangleIndex::best_match(const Vec3& p, const Vec3& n, const MatchMetric& m, double* score) const {
    // Eq. 2 over the faces around the nearest sample points (vertices and face centroids): the kd-tree
    // plays the part of the paper's octree. Points farther than the cutoff from every face get the cap.
    constexpr std::size_t kNeighbours = 6;
    std::uint32_t idx[kNeighbours];
    double d2[kNeighbours];
    std::call_once(impl_->kd_once, [this] { impl_->build_kd(); });
    if (!impl_->kd) {
        if (score) *score = std::numeric_limits<double>::infinity();
        return {};
    }
    // Approximate search (neighbours within 1.5 times the true distances) is enough to collect the
    // candidate faces; D itself is evaluated exactly on them.
    nanoflann::KNNResultSet<double, std::uint32_t> knn(kNeighbours);
    knn.init(idx, d2);
    impl_->kd->findNeighbors(knn, p.data(), nanoflann::SearchParams(32, 0.5f));
    const std::size_t found = knn.size();
    const double cap = m.cutoff > 0 ? 1.0 + m.lambda * m.cutoff : std::numeric_limits<double>::infinity();
    const auto& V = impl_->mesh.vertices;
    int faces[kNeighbours * 16];
    std::size_t nfaces = 0;
    for (std::size_t i = 0; i < found; ++i) {
        const SampleCloud& c = impl_->cloud;
        for (int k = c.offset[idx[i]]; k < c.offset[idx[i] + 1] && nfaces < kNeighbours * 16; ++k) faces[nfaces++] = c.faces[static_cast<std::size_t>(k)];
    }
    std::sort(faces, faces + nfaces);
    ClosestHit best;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nfaces; ++i) {
        if (i > 0 && faces[i] == faces[i - 1]) continue;
        const int fi = faces[i];
        const Tri& f = impl_->mesh.faces[static_cast<std::size_t>(fi)];
        Vec3 bary;
        const Vec3 q = closest_point_on_triangle(p, V[f[0]], V[f[1]], V[f[2]], &bary);
        const double dist = (q - p).norm();
        const double d = (1.0 + m.lambda * dist / m.unit) * (1.0 + (n - impl_->normals[static_cast<std::size_t>(fi)]).norm());
        if (d < best_d) {
            best_d = d;
            best = ClosestHit{fi, dist, q, bary};
        }
    }
    if (score) *score = std::min(best_d, cap);
    return best;
}

std::vector<int> TriangleIndex::faces_in_box(const Box3& box) const {
    std::vector<int> out;
    if (empty()) return out;
    const CGAL::Bbox_3 q(box.min.x(), box.min.y(), box.min.z(), box.max.x(), box.max.y(), box.max.z());
    std::vector<Primitive::Id> ids;
    impl_->tree.all_intersected_primitives(q, std::back_inserter(ids));
    out.reserve(ids.size());
    for (const auto& id : ids) out.push_back(static_cast<int>(id - impl_->triangles.cbegin()));
    std::sort(out.begin(), out.end());
    return out;
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    auto out = [&](double u, double v, double w) {
        if (bary) *bary = Vec3(u, v, w);
        return Vec3(u * a + v * b + w * c);
    };
    if (d1 <= 0 && d2 <= 0) return out(1, 0, 0);
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return out(0, 1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return out(1 - v, v, 0);
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return out(0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return out(1 - w, 0, w);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return out(0, 1 - w, w);
    }
    const double denom = va + vb + vc;
    if (!(std::abs(denom) > 0)) return out(1, 0, 0);  // degenerate triangle
    const double v = vb / denom, w = vc / denom;
    return out(1 - v - w, v, w);
}

std::vector<Vec3> face_normals(const Mesh& mesh) {
    std::vector<Vec3> n(mesh.faces.size(), Vec3::Zero());
    for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        const Vec3 c = face_cross(mesh, i);
        const double len = c.norm();
        if (len > 0) n[i] = c / len;
    }
    return n;
}

std::vector<Vec3> vertex_normals(const Mesh& mesh) {
    std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
    for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        const Vec3 c = face_cross(mesh, i);
        for (int k = 0; k < 3; ++k) n[mesh.faces[i][k]] += c;
    }
    for (Vec3& v : n) {
        const double len = v.norm();
        if (len > 0) v /= len;
    }
    return n;
}

}  // namespace meshquilt
