// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// What the planar and the surface stage share about a swatch and one placement: the swatch split
// into elements in its own frame, helpers on element meshes, and the translation refinement.

#include "core/triangle_index.h"
#include "meshquilt/mesh.h"
#include "quilt/kernel.h"
#include "quilt/match.h"

#include <chrono>
#include <random>
#include <string>
#include <vector>

namespace meshquilt::quilt {

/// The swatch split into elements, in its own frame (see normalize_swatch).
struct SwatchData {
    Mesh mesh;
    std::vector<Mesh> elements;
    std::vector<char> element_closed;
    double mean_edge = 0.0;
    double area = 0.0;
    Box3 box;
    bool elements_disjoint = true;  ///< no two swatch elements intersect (then none may in the output)
    /// The 5th percentile, over the swatch's elements, of the distance from each to its nearest
    /// neighbour (vertex to vertex, looked for up to the median element's diagonal): how close the
    /// swatch lets its elements come. 0 when elements intersect or there is only one.
    double near_gap = 0.0;
    /// The swatch's blobs overlap one another in xy projection, as scales and shingles do (each
    /// laid partly over its neighbour): at least kLayeredShare of its blobs (closed genus-0 elements
    /// that are not threads) have kLayeredOverlap or more of their projection under another
    /// element's. Rules that judge clearance by xy footprints (squeezing a blob clear of others,
    /// growing blobs into joints, filling bald spots by footprints) do not hold for such a
    /// swatch: its elements keep apart in 3D only.
    bool layered = false;
    /// Genus of each element (closed elements; 0 for open ones): a ring (genus >= 1) can interlock
    /// with its neighbours, a blob cannot.
    std::vector<int> element_genus;
    /// Each element a strand (quilt::is_strand: a slender closed genus-0 element that is not a
    /// thread), which is never squeezed or shrunk to fit, only cut clear where it lost a merge.
    std::vector<char> element_strand;
    /// The largest element's xy bounding box over the swatch's: near 1 for a swatch that is one
    /// connected net or lattice (a grid of bars), about a thread's width over the swatch's for a
    /// weave. Such an element can only be placed whole (where two placements overlap, the cuts
    /// through its many bars do not pair up), so a smaller scale does not cover more.
    double largest_element_cover = 0.0;
    bool spans_swatch() const { return largest_element_cover >= kSpanningCover; }
    /// The in-plane turn (radians, about z) applied after normalize_swatch so that the swatch's
    /// threads run along x and y (see kAlignedAgreement); 0 for most swatches.
    double turn = 0.0;
    /// The warning both stages give for a turned swatch (empty when it was not turned).
    std::string turn_warning() const;
    /// Beyond the paper: threads modelled as open sheets (ribbons) are quilted as closed strips,
    /// kSolidifyShare of their width thick (the sheet offset by half of it to either side): an open
    /// element is never stitched (its cut parts hold its rim among their boundary loops), so
    /// ribbons stayed as short as a patch's piece of them, and on a surface their trimmed pieces
    /// were dropped. The count of such threads (0: none) and the thickest strip (swatch units).
    int solidified = 0;
    double solidify_thickness = 0.0;
    /// The warning both stages give for a swatch with such threads (empty when none).
    std::string solidify_warning() const;
    /// Pairs of the input swatch's elements that intersect or touch (linked rings of a wire too
    /// thick for their spacing, pebbles modelled touching): counted up to kMaxCountedPairs.
    int intersecting_pairs = 0;
    /// Beyond the paper: a swatch whose elements intersect is quilted thinned. Every element's
    /// vertices were moved inwards along their normals by this much (swatch units): the least that
    /// parts every pair and then enough to put them kThinGap of the median element's xy diagonal
    /// apart (less where an element would keep under kMinThinVolume of its volume), at most
    /// kMaxThinning of the smallest element's smallest extent. The box stays the input's. Both
    /// stages thicken their output back (thicken_output), so its elements meet where the
    /// swatch's do. 0: not thinned (the elements are disjoint, or no such thinning parts them: then
    /// a new element that meets an old one is left out, as for any swatch, and the output is
    /// sparse).
    double thinned = 0.0;
    /// Thinned although no two elements intersect: a chain mail whose rings stand closer than
    /// kThinGap (thin_tight_rings in swatch.cpp). Its output must stay disjoint, so an output ring
    /// that would meet another once thickened back is thickened less (thicken_output).
    bool tight = false;
    /// The warning both stages give for a swatch whose elements intersect or that is tight (empty
    /// when neither).
    std::string intersect_warning() const;
    static constexpr int kMaxCountedPairs = 1000;
    static constexpr double kThinGap = 0.04;
    static constexpr double kMinThinVolume = 0.4;
    static constexpr double kMaxThinning = 0.25;
    static constexpr double kSpanningCover = 0.5;
    static constexpr double kSolidifyShare = 0.05;
};

/// A swatch whose threads run at an angle to its axes is turned in its plane when its threads'
/// directions (modulo 90 degrees, weighted by length) agree this well (resultant over total)...
inline constexpr double kAlignedAgreement = 0.9;
/// ... and the turn shrinks its footprint (xy bounding box) to this share or less.
inline constexpr double kAlignedFootprint = 0.9;

inline constexpr double kLayeredOverlap = 0.05;
inline constexpr double kLayeredShare = 0.25;

SwatchData prepare_swatch(const Mesh& input);

/// Moves each element of `mesh` outwards (by its own orientation) along its vertex normals by
/// `offset[element]`: undoes SwatchData::thinned on an output. Elements must not share vertices.
void thicken_elements(Mesh* mesh, const std::vector<int>& element_of_face, const std::vector<double>& offset);

/// A thinned swatch's output (`offset[e]`: the thinning at element e's scale) thickened back in
/// full, except for a tight swatch (SwatchData::tight), whose output must stay disjoint as the
/// swatch is: there the elements of every pair that meets once thickened lose a quarter of their
/// thickening, round by round, until none meet (at worst they stay as thin as they were quilted).
/// Returns how many elements were thickened less than `offset`.
int thicken_output(const SwatchData& sw, Mesh* mesh, const std::vector<int>& element_of_face, std::vector<double> offset);

/// A number for messages: 6 significant digits, no trailing zeros.
std::string num(double v);
/// A point for messages: "x, y, z", 4 significant digits each.
std::string num(const Vec3& p);

/// Largest output either stage attempts, in faces (about 2-3 GB of memory and some minutes).
inline constexpr double kMaxOutputFaces = 20e6;

/// Inset of the density window, as a fraction of the swatch's sides (the swatch's margins are
/// ragged).
inline constexpr double kDensityInset = 0.15;

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double mesh_area(const Mesh& m);
/// Area-weighted centroid of the faces (the box corner for a mesh without area).
Vec3 area_centroid(const Mesh& m);
Mesh translated(const Mesh& m, const Vec3& t);

/// Area of the faces whose centroid lies in [x0, x1] x [y0, y1], per unit area of that window.
double window_density(const Mesh& m, double x0, double y0, double x1, double y1);

/// Beyond the paper: the best whole-cell translation is refined by translation-only ICP over the
/// sub-patch samples (moving at most `max_offset`), so that lattice-like swatches (chain mail) line
/// up exactly instead of within half a cell; element deformation then has less to correct. Point
/// to point first; then, where the samples are a copy of the swatch (the median within 1e-3 mean
/// edges of it once polished), polished by point-to-plane steps to within rounding, so that a
/// lattice's copies keep its gaps (keeps_gap).
Vec2 refine_translation(const TriangleIndex& swatch, const MatchMetric& metric, const std::vector<Sample>& samples,
                        const Vec2& start, double max_offset);

/// One placement of the swatch around a seed, in a frame where the output's grid cells have side
/// `cell` (Section 2.4): the sub-patch P_out is the k x k cells from cell (pi0, pj0); every whole-cell
/// translation whose footprint covers it is a candidate; the chosen one is refined by ICP.
struct Placement {
    int ti = 0, tj = 0;                     ///< the whole-cell translation chosen, in cells
    Vec2 translation = Vec2::Zero();        ///< after refinement
    std::vector<NewElement> fresh;          ///< swatch elements (centroid inside the footprint) moved there
};
Placement place_swatch(const SwatchData& swatch, const TriangleIndex& index, const MatchMetric& metric,
                       const std::vector<Sample>& samples, int pi0, int pj0, int k, int sx, int sy, double cell, double tolerance,
                       std::mt19937_64& rng);

/// Beyond the paper: a swatch's ring lattice, which mending continues on the surface (chain mail).
struct RingLattice {
    /// A ring's lattice neighbour: swatch element `source` moved by `shift` in the swatch's plane.
    struct Neighbour {
        int source = -1;
        Vec2 shift = Vec2::Zero();
    };
    std::vector<Vec2> centre;                  ///< each element's area centroid (xy)
    double spacing = 0.0;                      ///< median distance from a ring to its nearest ring (0: fewer than two rings)
    std::vector<int> kind;                     ///< each ring's kind (rings that are translates of one another share it); -1 for other elements
    std::vector<std::vector<Neighbour>> next;  ///< each ring's lattice neighbours (none for other elements)
};

/// The lattice of the elements flagged in `is_ring`: each ring's neighbours are the rings within
/// 1.5 spacings of it. Rings that are translates of one another (the same vertices up to a shift in
/// the plane, within a thousandth of the spacing, in any vertex and face order) are of one kind and
/// share their neighbours: a ring on the swatch's border also gets those an interior ring of its
/// kind has beyond that border (another ring of the right kind, shifted there), so the lattice goes
/// on past the swatch's edge. Rings of no repeated kind keep the neighbours the swatch has.
RingLattice ring_lattice(const SwatchData& swatch, const std::vector<char>& is_ring);

/// The elements to remove so that no two of `elements` intersect (exact tests): of each
/// intersecting pair, the one with fewer faces (unless one of the pair is already removed).
std::vector<char> intersecting_to_remove(const std::vector<const Mesh*>& elements);

}  // namespace meshquilt::quilt
