// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// The mesh-quilting kernel of Zhou et al. 2006, Sections 2.5-2.7, for one patch placement:
// element correspondences, element deformation, element merging (graph cut + stitching).
// It works in a local frame where x, y span the texture plane and z is the height, and knows
// nothing about whether that plane is the planar output or a flattened surface patch: the caller
// gives it the old elements near the patch, the newly placed swatch elements and the overlap region.

#include "core/triangle_index.h"
#include "meshquilt/mesh.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace meshquilt::quilt {

struct KernelParams {
    MatchMetric metric;        ///< Eq. 1 (unit = the swatch's mean edge length)
    double mu = 1.0;           ///< Eq. 5-6
    double prune_factor = 6.0; ///< pairs farther than this many local mean edge lengths are dismissed (Section 2.5)
    double anchor_reach = 3.0; ///< faces farther than this many mean edge lengths from the partner element must be kept
    int smoothing_rings = 2;   ///< rings around a stitch seam relaxed after joining
    /// Beyond the paper: clearance a blob (closed genus-0 compact element) keeps when it is squeezed
    /// clear of the partner that won the merge (see plan_patch). 0: losers are dropped, as in the paper.
    double blob_gap = 0.0;
    /// Beyond the paper: when of two threads that could not be stitched the new one loses, it is
    /// still handed back as an addition (a remnant: it overlaps the winner), for a caller that cuts
    /// threads where they collide (the surface stage, quilt/trim.h). Off: the loser is dropped.
    bool thread_remnants = false;
    /// Beyond the paper: of two strands that could not be stitched, the loser is handed back whole
    /// as an addition (after the squeezed blobs), for a caller that cuts strands where they collide
    /// (quilt::strand_pieces). Off: the loser is dropped.
    bool strand_losers = false;
    /// Per swatch element, is it a strand (SwatchData::element_strand)? An element of a known
    /// source is judged by it (a deformed copy keeps its kind, and no raster is drawn), one of no
    /// known source by is_strand, unless no swatch element is a strand; all of them by is_strand
    /// when this is empty.
    std::vector<char> strands;
    /// Beyond the paper, off by default: two threads deform with whole cross-sections first
    /// (whole_section_targets; the paper's targets when that stitch fails or crosses an old
    /// element), and a thread's seam is relaxed by Taubin's shrinking and inflating steps, so
    /// threads keep their width where patches meet. It costs more than the planar and surface
    /// speed targets allow (docs/planar.md, element deformation). (Flat threads get the Taubin
    /// steps either way: flat_thread.)
    bool keep_thread_widths = false;
    /// Beyond the paper: the swatch is layered (SwatchData::layered: overlapping scales). A stitch of
    /// two compact elements must then not reach beyond both halves' elements by more than
    /// kMaxStitchReach (partners offset by a row would join into one long scale).
    bool layered = false;
    /// Beyond the paper: in a layered swatch, the clearance (3D) a merge's losing blob keeps from the
    /// winner to be kept whole beside it (see plan_patch). 0: losers are dropped.
    double layer_gap = 0.0;
};

/// An element already in the output, in the kernel's frame. `id` is the caller's handle.
struct OldElement {
    int id = -1;
    Mesh mesh;
    int source = -1;  ///< its swatch element (-1: unknown; such an element is never squeezed, see plan_patch)
};

/// An element of the newly placed swatch, in the kernel's frame. `source` is its swatch element.
struct NewElement {
    int source = -1;
    Mesh mesh;
};

/// The overlapping region (Section 2.5), seen from each side. Old geometry is contested where the new
/// patch covers it; new geometry is contested where the output already has been synthesised.
struct Overlap {
    std::function<bool(double, double)> old_side;  ///< is a point of an old element covered by the new patch?
    std::function<bool(double, double)> new_side;  ///< is a point of a new element on already synthesised ground?
};

/// What to do with the output after one placement. The caller applies it (checking collisions).
struct PatchPlan {
    struct Change {
        int old_id = -1;   ///< old element affected (-1: none)
        int source = -1;   ///< swatch element of the result
        Mesh mesh;         ///< the resulting element
        enum Kind { Deformed, Replaced, Stitched, Added } kind = Added;
        /// Tried when `mesh` collides with the output: the partner whole (empty: keep the old element);
        /// for an addition, the element squeezed clear of the output (see squeeze_clear).
        Mesh fallback;
    };
    /// Old elements deformed in place, replaced by their partner, or stitched with it; and new
    /// elements without partner. Applied in this order.
    std::vector<Change> changes;
    int stitch_failures = 0;
    int crowding = 0;         ///< new elements without partner left out: mostly on old ground, an old element at about the same place
    int correspondences = 0;  ///< corresponding element pairs
    /// Losers of a merge kept, squeezed clear of the winner (or, for a layered swatch, whole beside
    /// it): the additions changes[squeezed_from, squeezed_from + squeezed). Thread remnants follow them.
    int squeezed = 0;
    std::size_t squeezed_from = 0;
    std::map<std::string, int> failure_reasons;  ///< why stitches failed, counted
};

/// Plans the merge of `fresh` into the output around `old` (Sections 2.5-2.7).
/// `obstacles` are old elements the caller cannot hand over whole (on a surface: elements reaching
/// beyond the flattened patch); they take part only in the crowding test.
PatchPlan plan_patch(const std::vector<OldElement>& old, const std::vector<NewElement>& fresh, const Overlap& overlap,
                     const KernelParams& params, const std::vector<Mesh>& obstacles = {});

/// Merges two corresponding elements (Section 2.7, exposed for tests). An old element lying entirely
/// where the new one is gets replaced (outcome UseNew); a new one lying entirely where the old one is
/// is dropped (KeepOld). Otherwise both are cut (graph cuts with Eq. 7 weights: each keeps what only
/// it provides, yields where only its partner does), the boundary loops are paired, averaged boundary
/// points constrain Eq. 5, the loops are joined by a triangle strip and the seam relaxed (Stitched).
/// Returns false (and leaves `result` untouched) when no closed, manifold element results.
enum class StitchOutcome { Stitched, UseNew, KeepOld };
/// Area of the faces each element must keep (only it provides them), filled on every return.
struct OwnAreas {
    double old_part = 0.0;
    double new_part = 0.0;
};
bool stitch_elements(const Mesh& c_out, const Mesh& c_in, const Overlap& overlap, const KernelParams& params, Mesh* result,
                     std::string* why = nullptr, StitchOutcome* outcome = nullptr, OwnAreas* own = nullptr);

/// Beyond the paper: squeezes `m` along one axis of the plane at a time, with a smooth monotone map
/// that leaves its far side in place, until its xy convex hull keeps `gap` from the hull of each of
/// `others` (separating-axis test over the hulls' edge normals, deepest penetration first). The map
/// is a bijection of the plane with a positive Jacobian, so a closed, embedded element stays one.
/// False (and `m` unspecified) when a push would exceed `max_push` (< 1/2) of the element's width
/// along the axis, the hull would keep less than `min_area` of its area, or 8 pushes do not clear it.
bool squeeze_clear(Mesh& m, const std::vector<const Mesh*>& others, double gap, double min_area, double max_push);
/// The same against hulls computed once (xy_hull), for many tries among the same elements.
bool squeeze_clear(Mesh& m, const std::vector<std::vector<Vec2>>& other_hulls, double gap, double min_area, double max_push);

/// Moves the side of `m` at `lo` along unit `axis` (xy) by `depth` (positive: inwards, a squeeze;
/// negative: outwards, a growth), with the smooth monotone map of squeeze_clear; the side at `hi`
/// stays. `lo` and `hi` bound `m` along the axis; |depth| < (hi - lo) / 2.
void push_side(Mesh& m, const Vec2& axis, double lo, double hi, double depth);

/// The share of the xy projection of `a` that the projection of `b` covers, counted on a grid of
/// `resolution` pixels along the longer side of a's box (0 when their boxes are apart).
double projected_overlap_share(const Mesh& a, const Mesh& b, int resolution = 96);

/// Area of a simple polygon.
double polygon_area(const std::vector<Vec2>& polygon);

/// Convex hull of the xy projection of the vertices that faces use, counter-clockwise (CGAL).
std::vector<Vec2> xy_hull(const Mesh& m);

/// A long element (a thread): its xy box more than 3 times longer than wide, and not a closed
/// surface with a handle. A ring standing on edge (a chain mail's connecting ring, Japanese
/// 4-in-1) or a long oval link is as long in xy, but cutting or stitching it would open a loop
/// that must stay closed: it is a ring (genus >= 1), not a thread. The genus test is Euler's
/// formula for a closed triangle mesh (V - F/2 = 2 - 2g, so 2V <= F means g >= 1); a mesh with a
/// boundary or unused vertices gives a larger V - F/2 and stays a thread.
bool is_elongated(const Mesh& m);

/// A thread's width: its area over twice its length along its principal xy axis (a flat tube's
/// cross-section is about twice as long as it is wide; an open sheet's width is twice this).
double thread_width(const Mesh& m);

/// Beyond the paper: a closed thread much wider than thick (a tape, a ribbon quilted as a strip):
/// its half perimeter (thread_width) times its area over twice its volume, the square of the
/// cross-section's half perimeter over its area, is at least kFlatThread (kernel.cpp). The seam
/// of a stitch of such threads is relaxed by Taubin's steps (relax_seam): plain Laplacian steps
/// drew a strip's sides together at every seam (diamond-shaped pinches in a ribbon weave's renders).
bool flat_thread(const Mesh& m);

/// Beyond the paper: a closed genus-0 element that is not a thread (is_elongated) is a strand, not a
/// blob, when its footprint is at least this many times longer than wide (slenderness): knot work,
/// a winding cord, a snowflake's arms. A strand squeezed or shrunk to fit comes out thinner than its
/// kind, which shows; a blob squeezed is a smaller pebble. A disc gives 0.79, a square 1, a 2:1
/// ellipse 1.6; the bundled pebbles 0.94-1.24, rivets 0.89, cobbles 1.01-2.16, scales 1.60.
inline constexpr double kSlender = 2.5;
/// Raster of slenderness: pixels along the footprint's longer side.
inline constexpr int kSlenderPixels = 64;

/// How many times longer than wide `m`'s footprint (xy projection) is: its area over the square of
/// its width, the diameter of the widest disc inside it (an exact distance transform on a raster of
/// kSlenderPixels along the longer side). A strand w wide and L long, bent or not, gives about L / w
/// (a strand a few pixels wide less: 16% less at 6 pixels). 0 for an empty or flat footprint.
double slenderness(const Mesh& m);

/// A strand: closed, genus 0, not a thread (is_elongated), slenderness at least kSlender.
bool is_strand(const Mesh& m);

/// The smallest distance, capped at `cap`, between vertices of `a` (with bounding box `a_box`) and
/// of `b` (looked at only within `cap` of that box; elements of more than about 2,000 vertices are
/// sampled with a stride). Plain loops: the result does not depend on any tree's build order.
double element_gap(const Mesh& a, const Box3& a_box, const Mesh& b, double cap);

/// Clearance tests allow this share below the swatch's clearance (SwatchData::near_gap): where the
/// swatch's elements stand on a lattice, every gap between them is the clearance itself, and a copy
/// placed a whole lattice step away measures a hair closer (rounding of the translated
/// coordinates, the sub-cell refinement of matching). Held to the exact value, about half of a
/// lattice's new elements were refused at random (a 5 x 5 grid of domes: 127 of 225 in the plane).
constexpr double kGapSlack = 1e-4;

/// Does an element whose element_gap to another is `measured` keep clearance `gap` from it?
inline bool keeps_gap(double measured, double gap) { return measured >= (1.0 - kGapSlack) * gap; }

/// True when every edge has exactly two faces with opposite orientation (a closed, oriented,
/// edge-manifold surface).
bool is_closed_oriented(const Mesh& mesh);

/// Boundary loops of `m`, each in the direction its faces traverse it, appended to `loops`. False
/// when a vertex has several outgoing boundary edges (the boundary is not a set of simple loops).
bool boundary_loops(const Mesh& m, std::vector<std::vector<int>>* loops);

}  // namespace meshquilt::quilt
