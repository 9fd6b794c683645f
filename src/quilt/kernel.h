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
};

/// An element already in the output, in the kernel's frame. `id` is the caller's handle.
struct OldElement {
    int id = -1;
    Mesh mesh;
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
        /// Tried when `mesh` collides with the output: the partner whole (empty: keep the old element).
        Mesh fallback;
    };
    /// Old elements deformed in place, replaced by their partner, or stitched with it; and new
    /// elements without partner. Applied in this order.
    std::vector<Change> changes;
    int stitch_failures = 0;
    int crowding = 0;         ///< new elements without partner left out: mostly on old ground, an old element at about the same place
    int correspondences = 0;  ///< corresponding element pairs
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

/// A long element (a thread): its xy box more than 3 times longer than wide.
bool is_elongated(const Mesh& m);

/// The smallest distance, capped at `cap`, between vertices of `a` (with bounding box `a_box`) and
/// of `b` (looked at only within `cap` of that box; elements of more than about 2,000 vertices are
/// sampled with a stride). Plain loops: the result does not depend on any tree's build order.
double element_gap(const Mesh& a, const Box3& a_box, const Mesh& b, double cap);

/// True when every edge has exactly two faces with opposite orientation (a closed, oriented,
/// edge-manifold surface).
bool is_closed_oriented(const Mesh& mesh);

}  // namespace meshquilt::quilt
