// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Beyond the paper: trimmed threads. On a doubly curved base a new thread of a weave often meets
// old threads from another patch's lattice at a small angle or offset; the whole thread then
// collides and was dropped, leaving a bald strip a swatch long. Cutting the thread where it
// collides keeps the rest, closed by flat caps as the swatch's own threads end at its border.

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt::quilt {

/// How a thread is cut (lengths in the thread's frame units).
struct ThreadCut {
    double margin = 0.0;      ///< kept clear of the flagged faces along the thread, on each side
    double min_length = 0.0;  ///< shorter pieces are dropped
};

/// The pieces of closed thread `m` that keep clear of its faces flagged in `bad` (one flag per
/// face): the thread runs along its bounding box's longer side in xy (x or y); each flagged face
/// blocks the span it covers along that axis, widened by `cut.margin`; each free span of at least
/// `cut.min_length` becomes a closed piece, cut by planes across the axis (placed midway between
/// the nearest vertices, so no sliver faces) and capped flat (CGAL::Polygon_mesh_processing::clip
/// with clip_volume). A span that cuts a bent thread into several parts gives each as a piece.
/// Pieces that do not come out closed, oriented and free of self-intersections, or whose longer
/// side in xy is below `cut.min_length`, are left out. Without any flagged face the result is `m`
/// itself.
std::vector<Mesh> thread_pieces(const Mesh& m, const std::vector<char>& bad, const ThreadCut& cut);

/// The longest span along the axis of thread `m` that its faces flagged in `bad`, widened by
/// `margin`, leave free (as thread_pieces measures spans): no piece can be longer. The whole
/// length without flags; 0 for an empty mesh.
double longest_free_span(const Mesh& m, const std::vector<char>& bad, double margin);

}  // namespace meshquilt::quilt
