// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Private pieces of the print export: measurements on closed bodies (thickness, clearance) and
// the OpenVDB solid. Nothing here is public API.

#include "meshquilt/mesh.h"
#include "meshquilt/print.h"
#include "meshquilt/reporter.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace meshquilt::print_detail {

/// Enclosed volume of a closed mesh (positive when outward-oriented): the divergence theorem.
inline double signed_volume(const Mesh& m) {
    double v = 0.0;
    for (const Tri& t : m.faces) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
    return v / 6.0;
}

/// The elements of `model` as separate meshes (vertices renumbered; a vertex shared by two
/// elements is copied into each). \throw InvalidInput element ids or face indices out of range
std::vector<Mesh> split_elements(const ElementMesh& model);

/// Thickness under every face of a closed, outward-oriented body: the distance from the face's
/// centroid, along its inward normal, to the first other face the ray meets (CGAL AABB tree).
/// +infinity for degenerate faces and rays that leave without a hit (an open body).
std::vector<double> face_thickness(const Mesh& body);

/// The thinnest place of each element of `model` (faces grouped by `element_of_face`), in
/// parallel over elements. `min_of_element[e]` is +infinity for an element without a hit.
struct ElementThickness {
    std::vector<double> min_of_element;
    std::vector<Vec3> at_of_element;
    /// Thickness of every face of every element (for percentiles), in the model's face order.
    std::vector<double> of_face;
};
ElementThickness element_thickness(const ElementMesh& model);

/// Smallest distance between faces of different elements, exact for the double coordinates
/// (CGAL triangle-triangle squared distance behind a box-intersection broad phase whose boxes are
/// padded by half the search radius). Every element pair closer than `threshold` is listed with
/// its closest place; the global minimum is found by widening the search until a pair is seen.
struct Clearances {
    double min = -1.0;                 ///< -1 with fewer than two elements
    Vec3 at = Vec3::Zero();
    int a = -1, b = -1;
    int intersecting_pairs = 0;        ///< element pairs at distance 0 (touching or cutting)
    std::vector<PrintViolation> below; ///< element pairs closer than `threshold`, worst first
};
Clearances clearances(const ElementMesh& model, double threshold);

/// Narrow-band voxels (active) that a level set of a surface of `area` needs at `voxel`, with
/// `band_voxels` voxels across the band.
std::uint64_t estimate_band_voxels(double area, double voxel, double band_voxels);

/// The union of closed bodies, closed base bodies grown by `attach` (so elements that nearly
/// touch the base join it) and (optionally) a sheet `sheet_thickness` thick centred on an open
/// surface, as one closed, outward-oriented triangle mesh (OpenVDB meshToLevelSet,
/// csgUnion, volumeToMesh with `adaptivity`; quads split along the shorter diagonal; points at
/// the same place welded). Enclosed voids are filled (their inward surfaces dropped).
struct VoxelSolid {
    Mesh mesh;
    std::uint64_t active_voxels = 0;
    double seconds_voxelise = 0.0;
    double seconds_mesh = 0.0;
    int voids_filled = 0;
    int scraps_dropped = 0;  ///< closed parts of (nearly) no volume left by adaptive meshing
};
struct VoxelInput {
    std::vector<const Mesh*> closed;       ///< elements
    std::vector<const Mesh*> closed_base;  ///< grown by `attach`
    const Mesh* sheet = nullptr;           ///< an open base
    double sheet_thickness = 0.0;
    double attach = 0.0;
    double voxel = 0.1;
    double adaptivity = 0.0;
};
VoxelSolid voxel_union(const VoxelInput& in, const Reporter& reporter);

}  // namespace meshquilt::print_detail
