// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Private worker shared by analyse() and validate(): the edge structure of a mesh, the first
// offending element of every kind of defect, and the phrases that describe them (one source for
// the messages of both, so they cannot drift apart).

#include "meshquilt/analysis.h"
#include "meshquilt/mesh.h"

#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace meshquilt::analysis_detail {

/// Union-find with path halving and union by size.
class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }
    int find(int x) {
        while (parent_[static_cast<std::size_t>(x)] != x) {
            auto& p = parent_[static_cast<std::size_t>(x)];
            p = parent_[static_cast<std::size_t>(p)];
            x = p;
        }
        return x;
    }
    void unite(int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        if (size_[static_cast<std::size_t>(a)] < size_[static_cast<std::size_t>(b)]) std::swap(a, b);
        parent_[static_cast<std::size_t>(b)] = a;
        size_[static_cast<std::size_t>(a)] += size_[static_cast<std::size_t>(b)];
    }

private:
    std::vector<int> parent_;
    std::vector<int> size_;
};

/// "1 vertex", "3 vertices".
std::string count_of(long long n, const char* singular, const char* plural);

/// A half-edge of a face without repeated indices: from faces[f][k] to faces[f][(k+1)%3],
/// `corner` = 3 f + k. `key` packs the sorted vertex pair, so equal keys = the same edge.
struct HalfEdge {
    std::uint64_t key;
    int corner;
};
inline std::uint64_t edge_key(int a, int b) {
    const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(a < b ? a : b));
    const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(a < b ? b : a));
    return lo << 32 | hi;
}
inline bool has_repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

/// Half-edges of all faces without a repeated index, sorted by edge and then by corner, so the
/// faces around one edge are adjacent and listed in face order. Indices must be in range.
std::vector<HalfEdge> sorted_half_edges(const Mesh& mesh);

/// Faces with an index outside [0, num_vertices).
struct RangeCheck {
    int count = 0;
    int first_face = -1;
    long long first_index = 0;
    [[nodiscard]] std::string phrase(std::size_t num_vertices) const;
};
RangeCheck check_indices(const Mesh& mesh);

/// Vertices with NaN or infinite coordinates, split by whether a face uses them.
struct NonFiniteCheck {
    int referenced = 0, unreferenced = 0;
    int first = -1;  // lowest index over both
    [[nodiscard]] int count() const { return referenced + unreferenced; }
    [[nodiscard]] std::string phrase() const;
};
NonFiniteCheck check_finite(const Mesh& mesh, const std::vector<char>& referenced);

/// Which vertices faces use (indices out of range are ignored).
std::vector<char> referenced_vertices(const Mesh& mesh);

/// Faces with a repeated index or an area at most 1e-14 (bounding-box diagonal)^2.
struct DegenerateCheck {
    std::vector<char> is_degenerate;
    int count = 0;
    int first = -1;
    bool first_repeated = false;  // else: zero area
    [[nodiscard]] std::string phrase() const;
};
inline constexpr double kDegenerateAreaFactor = 1e-14;
DegenerateCheck find_degenerate_faces(const Mesh& mesh);

/// Referenced vertices at exactly the position of a lower-numbered referenced vertex.
struct DuplicateCheck {
    std::vector<int> representative;  ///< per vertex: the lowest vertex at its position (itself if unique)
    int count = 0;
    int first = -1, first_of = -1;
    [[nodiscard]] std::string phrase() const;
};
DuplicateCheck find_duplicate_vertices(const Mesh& mesh);

/// An edge named by its vertices, `from` -> `to` as the first face traverses it.
struct EdgeName {
    int from = -1, to = -1;
    int faces = 0;
};

/// Everything that needs the edge structure.
struct Topology {
    std::vector<int> component_of_face;
    std::vector<ElementInfo> elements;
    int boundary_edges = 0;
    int non_manifold_edges = 0;
    int inconsistent_edges = 0;
    int non_manifold_vertices = 0;
    EdgeName first_non_manifold_edge, first_inconsistent_edge;
    int first_non_manifold_vertex = -1;
    int fans_at_first_non_manifold_vertex = 0;
    /// Per corner (3 * face + k): a label shared by the corners of one fan of faces around its
    /// vertex (faces joined across edges at that vertex); -1 for faces that repeat a vertex.
    std::vector<int> fan_of_corner;

    [[nodiscard]] std::string non_manifold_edges_phrase() const;
    [[nodiscard]] std::string non_manifold_vertices_phrase() const;
    [[nodiscard]] std::string inconsistent_phrase() const;
    /// Closed elements with negative volume, in element order.
    [[nodiscard]] std::vector<int> inside_out_elements() const;
    [[nodiscard]] std::string inside_out_phrase() const;
};
/// Indices must be in range.
Topology compute_topology(const Mesh& mesh);

std::string unreferenced_phrase(int count, int first);
std::string thin_axis_phrase(const Box3& box);

}  // namespace meshquilt::analysis_detail
