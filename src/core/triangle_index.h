// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Closest-point queries over a triangle mesh (a bounding volume hierarchy of its faces).

#include "meshquilt/mesh.h"

#include <memory>
#include <vector>

namespace meshquilt {

struct ClosestHit {
    int face = -1;
    double distance = 0.0;
    Vec3 point = Vec3::Zero();
    Vec3 bary = Vec3::Zero();  ///< barycentric coordinates of `point` in `face`
};

/// The matching "distance" of Zhou et al. 2006, Eq. 1: D(v, f) = (1 + lambda * Dist(v, f) / unit) *
/// (1 + |n(v) - n(f)|), with distances measured in `unit` so lambda = 1 means the same on any scale.
struct MatchMetric {
    double lambda = 1.0;
    double unit = 1.0;
    /// Truncation: D is capped at 1 + lambda * cutoff, the value at `cutoff` units with equal normals,
    /// so a point far from every face costs the same wherever it is (a robust variant of Eq. 2 that
    /// bounds the search radius). <= 0: no cap.
    double cutoff = 3.0;
};

class TriangleIndex {
public:
    TriangleIndex();
    explicit TriangleIndex(const Mesh& mesh);
    ~TriangleIndex();
    TriangleIndex(TriangleIndex&&) noexcept;
    TriangleIndex& operator=(TriangleIndex&&) noexcept;

    [[nodiscard]] bool empty() const;
    [[nodiscard]] const Mesh& mesh() const;
    [[nodiscard]] const Vec3& face_normal(int f) const;  ///< unit normal (zero for degenerate faces)

    /// Closest point on the mesh (by Euclidean distance); face -1 at infinite distance when empty().
    /// Faces at the same (computed) distance, such as those sharing the edge or vertex nearest to
    /// p, go to the lowest face index, so the answer does not depend on the tree.
    [[nodiscard]] ClosestHit closest(const Vec3& p) const;
    /// Whether closest(p).distance <= r, answered without finding the closest face (the search
    /// stops at the first face that near). False when empty().
    [[nodiscard]] bool within(const Vec3& p, double r) const;
    /// Eq. 2: the face minimising D(p, f) for a point with unit normal n, and that minimum D (capped,
    /// see MatchMetric::cutoff) in `score`. The minimum runs over the faces around the 6 nearest
    /// sample points (vertices and face centroids, in a kd-tree), which holds the closest face for
    /// any point near the surface.
    [[nodiscard]] ClosestHit best_match(const Vec3& p, const Vec3& n, const MatchMetric& metric, double* score) const;
    /// Indices of faces whose bounding boxes meet the box.
    [[nodiscard]] std::vector<int> faces_in_box(const Box3& box) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Closest point on a triangle and its barycentric coordinates (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary);

/// Cross product of a face's edges (twice its area times its unit normal).
inline Vec3 face_cross(const Mesh& mesh, std::size_t f) {
    const Tri& t = mesh.faces[f];
    return (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
}
inline double face_area(const Mesh& mesh, std::size_t f) { return 0.5 * face_cross(mesh, f).norm(); }
inline Vec3 face_centroid(const Mesh& mesh, std::size_t f) {
    const Tri& t = mesh.faces[f];
    return (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
}

/// Area-weighted unit vertex normals.
std::vector<Vec3> vertex_normals(const Mesh& mesh);
/// Unit face normals (zero for degenerate faces).
std::vector<Vec3> face_normals(const Mesh& mesh);

}  // namespace meshquilt
