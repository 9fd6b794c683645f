// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file mesh.h
/// The one indexed triangle-mesh type of the public API: flat arrays, so it crosses language
/// boundaries (Python, Blender) without conversion. Connectivity-heavy algorithms build their own
/// structures from it internally.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace meshquilt {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Tri = Eigen::Vector3i;

/// An indexed triangle mesh. `faces[f]` holds three 0-based indices into `vertices`,
/// counter-clockwise seen from outside (outward normals by the right-hand rule).
struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<Tri> faces;

    [[nodiscard]] std::size_t num_vertices() const { return vertices.size(); }
    [[nodiscard]] std::size_t num_faces() const { return faces.size(); }
    [[nodiscard]] bool empty() const { return faces.empty(); }
};

/// Axis-aligned bounding box. An empty box has min > max.
struct Box3 {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
    void extend(const Vec3& p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
    void extend(const Box3& b) { min = min.cwiseMin(b.min); max = max.cwiseMax(b.max); }
    [[nodiscard]] bool empty() const { return (min.array() > max.array()).any(); }
    [[nodiscard]] Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
    [[nodiscard]] bool overlaps(const Box3& b, double pad = 0.0) const {
        return (min.array() - pad <= b.max.array()).all() && (b.min.array() - pad <= max.array()).all();
    }
};

/// Bounding box of the vertices that faces use (unreferenced vertices are ignored).
Box3 bounding_box(const Mesh& mesh);

/// A mesh whose faces are grouped into elements (connected components or labelled bodies).
/// `element_of_face[f]` is the element id of face f, in [0, num_elements).
struct ElementMesh {
    Mesh mesh;
    std::vector<int> element_of_face;
    int num_elements = 0;
};

/// The parts one after another in one mesh; part k becomes element k (its faces keep their order).
ElementMesh concatenate(const std::vector<const Mesh*>& parts);
ElementMesh concatenate(const std::vector<Mesh>& parts);

}  // namespace meshquilt
