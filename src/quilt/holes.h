// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Beyond the paper: small holes in the base (a scan's missing triangles) are filled on the
// synthesis's copy. A patch must be a topological disc, so every hole smaller than a patch cut the
// patches around it short: the bunny with 3% of its faces removed took 4,462 shrunk patches and
// 16 minutes for rivets instead of 1.5.

#include "meshquilt/mesh.h"

namespace meshquilt::quilt {

/// What fill_small_holes did.
struct HoleFilling {
    int loops = 0;       ///< boundary loops of the mesh
    int filled = 0;      ///< of them, filled
    int faces = 0;       ///< faces added
    double largest = 0;  ///< the largest extent of a filled loop
};

/// Fills each boundary loop of `m` whose vertices span at most `max_extent` (the diagonal of their
/// bounding box) with triangles over the loop's own vertices (CGAL's triangulate_hole_polyline,
/// Liepa 2003: the triangulation of least area, searched among Delaunay faces first), oriented as
/// the faces around the loop. Holes that touch at a vertex (a non-manifold vertex) are loops of
/// their own; filling them joins the vertex's fans. Left open: loops longer than `max_vertices`,
/// loops through two vertices at one position (holes touching at a vertex that was split) and
/// loops CGAL cannot fill. Faces are appended (the old ones keep their indices); no vertex is
/// added. `m` must have no non-manifold edges and a consistent orientation.
HoleFilling fill_small_holes(Mesh& m, double max_extent, int max_vertices);

}  // namespace meshquilt::quilt
