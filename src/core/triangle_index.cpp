// SPDX-License-Identifier: AGPL-3.0-or-later
#include "core/triangle_index.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <limits>
#include <utility>

namespace meshquilt {

namespace {

/// A bounding volume hierarchy over a mesh's faces for closest-point and nearness queries: a
/// binary tree of axis-aligned boxes, split at the median face centroid along the box's longest
/// side, up to kLeafFaces faces per leaf, stored depth first (a node's first child follows it).
/// A query visits the nearer child first and skips every box farther than the best face so far.
///
/// Beyond the library: it replaced CGAL's AABB_tree (with accelerate_distance_queries) here in
/// session 59. Both answer the same question, but these queries run by the million inside the
/// kernel's cuts (cut_element, anchored_faces), and CGAL's general traversal (a kd-tree hint,
/// then Epick's projection per primitive) took most of their time (docs/benchmarks.md).
class FaceBvh {
public:
    void build(const Mesh& mesh) {
        const std::size_t F = mesh.faces.size();
        corners_.resize(F);
        order_.resize(F);
        std::vector<Vec3> centre(F);
        for (std::size_t f = 0; f < F; ++f) {
            for (int k = 0; k < 3; ++k) corners_[f][static_cast<std::size_t>(k)] = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][k])];
            centre[f] = (corners_[f][0] + corners_[f][1] + corners_[f][2]) / 3.0;
            order_[f] = static_cast<int>(f);
        }
        nodes_.clear();
        nodes_.reserve(F > 0 ? 2 * (F / kLeafFaces + 1) : 0);
        if (F > 0) split(0, static_cast<int>(F), centre);
        // The leaves' corners in leaf order, so a leaf reads one contiguous run.
        std::vector<std::array<Vec3, 3>> sorted(F);
        for (std::size_t i = 0; i < F; ++i) sorted[i] = corners_[static_cast<std::size_t>(order_[i])];
        corners_ = std::move(sorted);
    }

    [[nodiscard]] bool empty() const { return nodes_.empty(); }

    /// The face nearest to p (by squared distance; the lowest index among equals, so the answer
    /// does not depend on the tree) and that squared distance; -1 and infinity when empty.
    [[nodiscard]] std::pair<int, double> nearest(const Vec3& p) const {
        double best = std::numeric_limits<double>::infinity();
        int best_face = -1;
        if (nodes_.empty()) return {best_face, best};
        std::array<std::pair<int, double>, 64> stack;
        int top = 0;
        stack[static_cast<std::size_t>(top++)] = {0, box_distance2(nodes_[0], p)};
        while (top > 0) {
            const auto [n, d2] = stack[static_cast<std::size_t>(--top)];
            if (d2 > best) continue;
            const Node& node = nodes_[static_cast<std::size_t>(n)];
            if (node.count > 0) {
                for (int i = node.first; i < node.first + node.count; ++i) {
                    const auto& c = corners_[static_cast<std::size_t>(i)];
                    const double e2 = (closest_point_on_triangle(p, c[0], c[1], c[2], nullptr) - p).squaredNorm();
                    const int f = order_[static_cast<std::size_t>(i)];
                    if (e2 < best || (e2 == best && f < best_face)) {
                        best = e2;
                        best_face = f;
                    }
                }
                continue;
            }
            const int l = n + 1, r = node.right;
            const double dl = box_distance2(nodes_[static_cast<std::size_t>(l)], p), dr = box_distance2(nodes_[static_cast<std::size_t>(r)], p);
            // The nearer child is popped first.
            if (dl <= dr) {
                stack[static_cast<std::size_t>(top++)] = {r, dr};
                stack[static_cast<std::size_t>(top++)] = {l, dl};
            } else {
                stack[static_cast<std::size_t>(top++)] = {l, dl};
                stack[static_cast<std::size_t>(top++)] = {r, dr};
            }
        }
        return {best_face, best};
    }

    /// Whether some face's closest point to p lies within distance r of it (as
    /// (closest point - p).norm() <= r, the distance TriangleIndex::closest reports).
    [[nodiscard]] bool within(const Vec3& p, double r) const {
        if (nodes_.empty() || !(r >= 0.0)) return false;
        const double limit = r * r * (1.0 + 1e-9) + std::numeric_limits<double>::min();  // boxes: a little slack for rounding
        std::array<int, 64> stack;
        int top = 0;
        stack[static_cast<std::size_t>(top++)] = 0;
        while (top > 0) {
            const Node& node = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
            if (box_distance2(node, p) > limit) continue;
            if (node.count > 0) {
                for (int i = node.first; i < node.first + node.count; ++i) {
                    const auto& c = corners_[static_cast<std::size_t>(i)];
                    if ((closest_point_on_triangle(p, c[0], c[1], c[2], nullptr) - p).norm() <= r) return true;
                }
                continue;
            }
            const int n = static_cast<int>(&node - nodes_.data());
            stack[static_cast<std::size_t>(top++)] = node.right;
            stack[static_cast<std::size_t>(top++)] = n + 1;
        }
        return false;
    }

    /// Faces whose bounding boxes meet `box`, ascending.
    [[nodiscard]] std::vector<int> in_box(const Box3& box) const {
        std::vector<int> out;
        if (nodes_.empty()) return out;
        std::array<int, 64> stack;
        int top = 0;
        stack[static_cast<std::size_t>(top++)] = 0;
        while (top > 0) {
            const Node& node = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
            if (!boxes_meet(node.lo, node.hi, box)) continue;
            if (node.count > 0) {
                for (int i = node.first; i < node.first + node.count; ++i) {
                    const auto& c = corners_[static_cast<std::size_t>(i)];
                    const Vec3 lo = c[0].cwiseMin(c[1]).cwiseMin(c[2]), hi = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
                    if (boxes_meet(lo, hi, box)) out.push_back(order_[static_cast<std::size_t>(i)]);
                }
                continue;
            }
            const int n = static_cast<int>(&node - nodes_.data());
            stack[static_cast<std::size_t>(top++)] = node.right;
            stack[static_cast<std::size_t>(top++)] = n + 1;
        }
        std::sort(out.begin(), out.end());
        return out;
    }

private:
    static constexpr int kLeafFaces = 4;
    struct Node {
        Vec3 lo, hi;
        int first = 0, count = 0;  ///< a leaf's faces: order_[first, first + count); count 0 for an inner node
        int right = 0;             ///< an inner node's second child (its first is the next node)
    };

    static double box_distance2(const Node& n, const Vec3& p) {
        const Vec3 d = (n.lo - p).cwiseMax(p - n.hi).cwiseMax(0.0);
        return d.squaredNorm();
    }
    static bool boxes_meet(const Vec3& lo, const Vec3& hi, const Box3& b) {
        return lo.x() <= b.max.x() && b.min.x() <= hi.x() && lo.y() <= b.max.y() && b.min.y() <= hi.y() && lo.z() <= b.max.z() &&
               b.min.z() <= hi.z();
    }

    /// Builds the subtree over order_[begin, end) and returns its node's index. The depth stays
    /// below about log2(F) + 1 (median splits), far within the queries' stacks of 64.
    int split(int begin, int end, const std::vector<Vec3>& centre) {
        const int n = static_cast<int>(nodes_.size());
        nodes_.emplace_back();
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        Vec3 clo = lo, chi = hi;
        for (int i = begin; i < end; ++i) {
            const auto& c = corners_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
            for (const Vec3& v : c) {
                lo = lo.cwiseMin(v);
                hi = hi.cwiseMax(v);
            }
            clo = clo.cwiseMin(centre[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
            chi = chi.cwiseMax(centre[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])]);
        }
        nodes_[static_cast<std::size_t>(n)].lo = lo;
        nodes_[static_cast<std::size_t>(n)].hi = hi;
        if (end - begin <= kLeafFaces) {
            nodes_[static_cast<std::size_t>(n)].first = begin;
            nodes_[static_cast<std::size_t>(n)].count = end - begin;
            return n;
        }
        int axis = 0;
        const Vec3 ext = chi - clo;
        if (ext.y() > ext[axis]) axis = 1;
        if (ext.z() > ext[axis]) axis = 2;
        const int mid = begin + (end - begin) / 2;
        // Ties broken by face index: the tree, and so every answer, is the same on every run.
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
            const double ca = centre[static_cast<std::size_t>(a)][axis], cb = centre[static_cast<std::size_t>(b)][axis];
            return ca < cb || (ca == cb && a < b);
        });
        split(begin, mid, centre);
        nodes_[static_cast<std::size_t>(n)].right = split(mid, end, centre);
        return n;
    }

    std::vector<Node> nodes_;
    std::vector<int> order_;                    ///< faces in leaf order
    std::vector<std::array<Vec3, 3>> corners_;  ///< the corners of order_'s faces
};

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
    std::vector<Vec3> normals;
    FaceBvh bvh;
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
    impl_->normals = face_normals(mesh);
    impl_->bvh.build(mesh);
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

bool TriangleIndex::empty() const { return !impl_ || impl_->bvh.empty(); }
const Mesh& TriangleIndex::mesh() const { return impl_->mesh; }
const Vec3& TriangleIndex::face_normal(int f) const { return impl_->normals[static_cast<std::size_t>(f)]; }

ClosestHit TriangleIndex::closest(const Vec3& p) const {
    if (empty()) return {-1, std::numeric_limits<double>::infinity(), p, Vec3::Zero()};
    ClosestHit hit;
    hit.face = impl_->bvh.nearest(p).first;
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

bool TriangleIndex::within(const Vec3& p, double r) const { return !empty() && impl_->bvh.within(p, r); }

std::vector<int> TriangleIndex::faces_in_box(const Box3& box) const {
    if (empty()) return {};
    return impl_->bvh.in_box(box);
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
