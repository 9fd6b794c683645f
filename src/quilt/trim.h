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
    double min_girths = 0.0;  ///< strand_pieces: pieces shorter than this many of the strand's girths are dropped too
};

/// The pieces of closed thread `m` that keep clear of its faces flagged in `bad` (one flag per
/// face): the thread runs along its bounding box's longer side in xy (x or y); each flagged face
/// blocks the span it covers along that axis, widened by `cut.margin`; each free span of at least
/// `cut.min_length` becomes a closed piece, cut by planes across the axis (placed midway between
/// the nearest vertices, so no sliver faces) and capped flat (CGAL::Polygon_mesh_processing::clip
/// with clip_volume). A span that cuts a bent thread into several parts gives each as a piece.
/// Pieces that do not come out closed, oriented and free of self-intersections, or whose longer
/// side in xy is below `cut.min_length`, are left out; a thread that intersects itself (outside
/// the clip's precondition) gives none. Without any flagged face the result is `m` itself.
std::vector<Mesh> thread_pieces(const Mesh& m, const std::vector<char>& bad, const ThreadCut& cut);

/// Beyond the paper: the pieces of closed genus-0 strand `m` (a winding element, quilt::is_strand,
/// or any tube-like element with two ends) that keep clear of its faces flagged in `bad`, cut
/// across the strand itself rather than across an axis of the plane, as an under-crossing of knot
/// work stops short of the strand over it. Position along the strand is a harmonic function (0 at
/// one end, 1 at the other, clamped cotangent weights), whose level sets on a tube are its
/// cross-sections; its values are turned into lengths along the strand's centre line (the
/// centroids of the vertices between levels). Each flagged face blocks the length it covers,
/// widened by `cut.margin` on each side; each free length of at least `cut.min_length` becomes a
/// piece (and at least `cut.min_girths` girths long: a strand's girth is its area over twice its
/// end-to-end length, half its cross-section's perimeter, width plus height for a flat strand), cut
/// at the level in the widest gap between vertex levels within a quarter of a girth of the cut (so a cut passes between two rings of a swept tube's vertices, not
/// through one) and capped by a fan from the cut loop's centroid. Pieces that are not closed,
/// oriented and free of self-intersections are left out. Without any flagged face the result is
/// `m` itself; an element without two distinct ends (both ends' neighbourhoods meet), or one that
/// branches (a band of levels reaching twice as far from its centroid as the median band: a star,
/// a snowflake), gives none.
std::vector<Mesh> strand_pieces(const Mesh& m, const std::vector<char>& bad, const ThreadCut& cut);

/// The connected components of `m` (by faces), each with its own vertices, in the order of
/// meshquilt::connected_components.
std::vector<Mesh> split_components(const Mesh& m);

/// `parts` in one mesh, in order (the inverse of split_components).
Mesh join_meshes(const std::vector<Mesh>& parts);

/// Per face of `m`: 1 when one of its vertices lies closer than `gap` to a vertex of one of `others`.
std::vector<char> faces_near(const Mesh& m, const std::vector<const Mesh*>& others, double gap);

/// The area of the faces of `m` not flagged in `flags` (one per face).
double unflagged_area(const Mesh& m, const std::vector<char>& flags);

/// Beyond the paper: a strand's piece (strand_pieces) shorter than this many of its girths (width
/// plus height: 0.54 for the bundled knots, so 1.08, over three of their widths) is left out (a
/// stub that short reads as debris, not as an under-crossing).
inline constexpr double kStrandPieceGirths = 2.0;
/// Beyond the paper: a strand that does not fit a bald spot whole fills it with its pieces that do
/// (strand_pieces) when they keep at least this share of its area.
inline constexpr double kFillPieceShare = 0.5;

/// The longest span along the axis of thread `m` that its faces flagged in `bad`, widened by
/// `margin`, leave free (as thread_pieces measures spans): no piece can be longer. The whole
/// length without flags; 0 for an empty mesh.
double longest_free_span(const Mesh& m, const std::vector<char>& bad, double margin);

/// Beyond the paper: a thread squashed where it passes a crossing thread keeps at least this share
/// of its thickness (woven).
inline constexpr double kMinSquash = 0.5;
/// ... and fills this share of the room it is squashed into, leaving the rest as clearance.
inline constexpr double kSquashFill = 0.9;

/// Beyond the paper: thread `m` (running along axis `along`, 0 for x or 1 for y, `width` wide)
/// woven through the `crossing` threads, whose over and under need not follow the thread's own
/// period (another patch's lattice): the height of its centre line (the middle of its vertices'
/// heights in each cell a quarter `width` long) is moved, keeping its cross-sections, so that it
/// passes each crossing thread it meets (a run of cells where crossing vertices lie within
/// `width` / 2 of its axis) above or below it, on the side with the more room at the run's
/// narrowest cell, in the middle of that room cell by cell (a crossing thread met at an angle
/// rises and falls along the run), within [zmin, zmax]. Where the room is less than the thread's
/// median thickness the thread is squashed in height about its centre line to kSquashFill of the
/// room, to kMinSquash of its thickness at most, easing back to its whole thickness over a `width` (real threads
/// flatten where they are pressed together). It eases between the knots along a half cosine and
/// stays level beyond the first and last. Without crossings, `m` itself. A crossing thread that
/// leaves less than kMinSquash of the thickness (met halfway up its own slope) still blocks it: the
/// caller's collision test cuts there.
Mesh woven(const Mesh& m, int along, const std::vector<const Mesh*>& crossing, double width, double zmin, double zmax);

}  // namespace meshquilt::quilt
