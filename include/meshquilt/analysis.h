// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file analysis.h
/// Topology and geometry facts about a mesh: elements (connected components), closedness, genus,
/// boundary loops, thin axis; and validation with clear errors or reported repairs.

#include "meshquilt/mesh.h"

#include <string>
#include <vector>

namespace meshquilt {

/// Connected components by shared vertices. Returns the component id of every face, numbered in
/// order of each component's first face; `count` receives the number of components. O(F α(V)).
/// \throw InvalidInput a face index is outside [0, num_vertices)
std::vector<int> connected_components(const Mesh& mesh, int* count = nullptr);

/// The thinnest axis of a box and whether it is thin enough to be a swatch's height axis: the
/// smallest extent must be at most `kThinRatio` times the middle one.
struct ThinAxis {
    int axis = 2;            ///< 0 = x, 1 = y, 2 = z
    double thickness = 0.0;  ///< extent along `axis`
    bool is_thin = false;
};
inline constexpr double kThinRatio = 0.5;
ThinAxis thin_axis_of(const Box3& box);

struct ElementInfo {
    int faces = 0;
    int vertices = 0;
    bool closed = false;        ///< every edge has exactly two faces, consistently oriented
    bool edge_manifold = true;  ///< no edge has more than two faces
    int boundary_loops = 0;     ///< boundary edges joined where they share a vertex and a fan of faces
    int genus = 0;              ///< (2 - b - chi) / 2, chi = V - E + F; meaningful for manifold elements (>= 0)
    double area = 0.0;
    double volume = 0.0;        ///< signed enclosed volume (positive when outward-oriented); closed only
    Box3 box;
};

struct MeshAnalysis {
    int faces = 0;
    int vertices = 0;               ///< referenced by a face
    int unreferenced_vertices = 0;
    Box3 box;
    ThinAxis thin;
    std::vector<ElementInfo> elements;  ///< one per connected component, in `connected_components` order
    int genus = 0;                  ///< summed over components
    int boundary_loops = 0;
    int boundary_edges = 0;
    int non_manifold_edges = 0;     ///< edges with more than two faces
    int non_manifold_vertices = 0;  ///< vertices whose faces form more than one fan
    int inconsistent_edges = 0;     ///< interior edges traversed twice in the same direction
    int degenerate_faces = 0;       ///< repeated index or (near) zero area
    int duplicate_vertices = 0;     ///< vertices at exactly the same position as an earlier one
    double area = 0.0;
    std::vector<std::string> problems;  ///< human-readable, first offending element named
    [[nodiscard]] int closed_elements() const;
};

/// Facts about any mesh, however broken: defects are counted and described in `problems`, not
/// thrown. Faces with a repeated index are left out of the edge structure (they count as degenerate).
/// O(F log F).
/// \throw InvalidInput a face index is outside [0, num_vertices) (read_mesh never returns such a mesh)
MeshAnalysis analyse(const Mesh& mesh);

struct ValidationOptions {
    /// Drop degenerate faces, merge duplicate vertices, split non-manifold vertices (one copy of
    /// the vertex per fan of faces around it), make face orientation consistent within each
    /// element (when it is orientable), flip inside-out closed elements, drop unreferenced
    /// vertices; each repair is reported in ValidationResult::repairs. Non-manifold edges stay
    /// errors: no repair of them is safe.
    bool repair = false;
    /// Make face orientation consistent even without `repair` (a base: the decoration goes on a
    /// copy), with a warning instead of an error; a non-orientable mesh stays an error. Inside-out
    /// closed pieces are then not warned about: the surface stage flips them and says so.
    bool reorient = false;
    bool require_thin_axis = false;  ///< a swatch must have one
};

struct ValidationResult {
    Mesh mesh;                          ///< the input, or the repaired mesh
    std::vector<std::string> repairs;   ///< what was repaired, in words (empty without repair)
    std::vector<std::string> warnings;
};

/// Checks a mesh that a user gave us. `name` (usually the file path) starts every message.
/// Errors (InvalidInput): empty mesh, non-finite coordinates, indices out of range, degenerate faces,
/// non-manifold edges or vertices, inconsistent orientation, no thin axis (when required). Each
/// message names the first offending element, e.g.
/// "swatch.obj: 3 non-manifold edges (first between vertices 12 and 57); repair the mesh".
/// With `repair`, the safe repairs are made and reported instead of the matching errors.
/// Not errors: duplicate vertices and inside-out closed elements (a warning each, unless repaired)
/// and unreferenced vertices. Messages name vertices by their index in the input mesh.
ValidationResult validate(const Mesh& mesh, const std::string& name, const ValidationOptions& options = {});

/// Gives each fan of faces around a non-manifold vertex, beyond the first, a copy of the vertex of
/// its own at the same position (the surface then touches itself there instead of sharing a
/// vertex); faces keep their order. Returns the number of vertices added. Needs indices in range;
/// non-manifold edges are left as they are. O(F log F).
int split_non_manifold_vertices(Mesh& mesh);

}  // namespace meshquilt
