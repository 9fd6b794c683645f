// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Beyond the paper: bald spots. After the last placement, an output can hold bare spots where new
// elements collided with the old ones around them or lost their merges (the paper never refuses an
// element, so it has none; it has intersections instead). A bare spot is measured as the largest
// empty disc in the xy projection, and compared with the swatch's own largest one.

#include "meshquilt/mesh.h"

#include <cmath>
#include <functional>
#include <vector>

namespace meshquilt::quilt {

struct SwatchData;

// A blob put into a bald spot is squeezed by at most kFillPush of its width at a time and is tried
// at full size and at kFillScale; a spot counts when the disc of kFillWindow blob half-diagonals
// around it is sparser than the swatch (FillSetup::sparse).
inline constexpr double kFillPush = 0.45;
inline constexpr double kFillScale = 0.8;
inline constexpr double kFillWindow = 3.0;

/// Exact squared Euclidean distance transform (Felzenszwalb and Huttenlocher 2012) of a w x h raster
/// stored row by row: on entry 0 at the pixels distances are measured to and infinity elsewhere; on
/// return each pixel's squared distance, in pixels, to the nearest of them (infinity when none).
void squared_distance_transform(std::vector<double>& sq, int w, int h);

/// What the xy projections of meshes cover, on a raster of square pixels over a rectangle.
class Coverage {
public:
    /// With `projected`, area_density counts each face's area projected onto xy, so that an element
    /// flattened in height (the surface stage's lowered shell) counts as its footprint does, not less.
    Coverage(double x0, double y0, double x1, double y1, double pixel, bool projected = false);

    /// Marks the pixels whose centres the projection of a face of `m` covers (a face smaller than
    /// a pixel marks the pixel of its centroid; vertical faces cover nothing), and adds each face's
    /// area to the pixel of its centroid.
    void add(const Mesh& m);
    /// `add` of each of `meshes`, in order: the same raster (each mesh is rasterised on its own, in
    /// parallel, and the face areas are summed in the same order).
    void add(const std::vector<const Mesh*>& meshes);

    /// Marks every pixel that `mask` (a raster of the same rectangle and pixel) does not cover, so
    /// that distances end there (ground beyond a surface patch holds elements the frame cannot show).
    void cover_outside(const Coverage& mask);

    /// Per pixel, the distance from its centre to the nearest covered pixel centre (0 on covered
    /// pixels; a huge value when nothing is covered). Exact Euclidean distance transform (Felzenszwalb
    /// and Huttenlocher 2012), linear in the number of pixels.
    [[nodiscard]] std::vector<double> empty_distance() const;
    /// The same within pixels [i0, i1] x [j0, j1] only (covered pixels outside are not seen), row
    /// major over the window.
    [[nodiscard]] std::vector<double> empty_distance(int i0, int j0, int i1, int j1) const;

    /// Share of the pixels with centres in the disc (`c`, `radius`) that are covered (0 without any).
    [[nodiscard]] double covered_share(const Vec2& c, double radius) const;
    /// Face area (by centroid, see add) per unit area of the pixels with centres in the disc; with
    /// `mask` (a raster of the same rectangle and pixel), of those pixels that it covers.
    [[nodiscard]] double area_density(const Vec2& c, double radius, const Coverage* mask = nullptr) const;

    [[nodiscard]] int nx() const { return nx_; }
    [[nodiscard]] int ny() const { return ny_; }
    [[nodiscard]] double pixel() const { return pixel_; }
    /// Pixel index of a coordinate (may lie outside [0, nx) x [0, ny)).
    [[nodiscard]] int column(double x) const { return static_cast<int>(std::floor((x - x0_) / pixel_)); }
    [[nodiscard]] int row(double y) const { return static_cast<int>(std::floor((y - y0_) / pixel_)); }
    [[nodiscard]] Vec2 centre(int i, int j) const { return {x0_ + (i + 0.5) * pixel_, y0_ + (j + 0.5) * pixel_}; }
    [[nodiscard]] bool covered(int i, int j) const { return covered_[static_cast<std::size_t>(j) * nx_ + i] != 0; }

private:
    /// Calls cover(pixel) for each pixel a face of `m` covers and add_area(pixel, area) for each face
    /// (see add), face by face.
    template <class Cover, class Area>
    void rasterise(const Mesh& m, Cover&& cover, Area&& add_area) const;

    double x0_, y0_, pixel_;
    int nx_, ny_;
    std::vector<char> covered_;
    std::vector<double> area_;
    bool projected_ = false;
};

/// Is swatch element `source` a blob: closed, genus 0, neither a thread nor a strand (a pebble, a
/// stone, a rivet head; not a ring, not knot work)? False for -1 (no swatch element).
bool is_blob_source(const SwatchData& swatch, int source);

/// Is swatch element `source` a strand (SwatchData::element_strand)? False for -1.
bool is_strand_source(const SwatchData& swatch, int source);

/// What the bald-spot filler needs of a swatch, in the swatch's units.
struct FillSetup {
    struct Shape {
        int source = -1;  ///< swatch element
        Mesh mesh;        ///< centred on its area centroid in xy, possibly scaled by `scale` in xy
        double area = 0.0;
        double scale = 1.0;
        double swatch_area = 0.0;  ///< of the swatch element at full size
        bool whole = false;        ///< a strand (SwatchData::element_strand): goes in unsqueezed or not at all
    };
    /// The swatch's blobs and open compact sheets (a cap, a leaf: one rim, no handles) at full size
    /// and at kFillScale, and its strands no longer than most (half
    /// their diagonal at most the median strand's or the largest blob's) at full size only, largest
    /// first.
    std::vector<Shape> shapes;
    double pixel = 0.0;         ///< raster pixel: half the swatch's clearance
    double reach = 0.0;         ///< the largest blob's half diagonal
    double swatch_density = 0.0;  ///< element area per footprint area in the swatch's inset window
    double smallest_spot = 0.0; ///< a spot narrower than this (empty-disc radius) is never filled
    double gap = 0.0;           ///< clearance a filled blob keeps (the swatch's near_gap)
    /// A spot is filled when the ground around it holds less than this share of the swatch's density
    /// (planar and surface 0.9; filling up to the swatch's density made pebbles, already denser than
    /// the swatch on average, 7-20% denser still).
    double sparse = 0.9;
    /// A filled blob keeps at least this share of its swatch element's footprint and of its area
    /// (planar 0.4; the surface stage 0.5, which keeps it within its size bound of a factor 1.5).
    double min_area = 0.4;
    /// A filled blob keeps at least this area (0: no floor). The surface stage sets the swatch's
    /// smallest blob's, so fills do not widen the spread of element sizes below the swatch's own.
    double area_floor = 0.0;
    double smallest_blob_area = 0.0;  ///< of the swatch's blobs
    /// Densities by projected area (see Coverage), the swatch's too: the surface stage, whose lowered
    /// shell flattens elements.
    bool projected = false;
    /// The swatch is layered (SwatchData::layered): a shape goes in as it is, without a squeeze by
    /// footprints, when `fits` (the 3D test) takes it.
    bool layered = false;
};

/// Empty (no shapes) when the swatch has no blob (closed, genus 0, not a thread) nor open compact
/// sheet, or its elements intersect (a layered swatch's shapes go in without squeezes:
/// FillSetup::layered); `min_pixel` bounds the raster's size for large outputs, `sparse`,
/// `min_area` and `projected` see FillSetup.
FillSetup prepare_fill(const SwatchData& swatch, double min_pixel, double sparse, double min_area, bool projected = false);

/// The filling loop (see FillSetup): while the widest empty disc of `cov` centred where `may_centre`
/// allows is wider than `setup.smallest_spot` and `density` (element area per ground area in a disc)
/// says the ground around it is sparser than the swatch, the shape that covers most there after squeezing
/// clear of the hulls `around` gives (squeeze_clear) and that `fits` (collision tests) accepts goes
/// in through `add` (both get the element in the raster's frame and its swatch element). `fits`
/// may cut the element to what fits (a strand's pieces, quilt::strand_pieces): it then replaces it
/// with the pieces, as one mesh of several components, which `add` gets and which counts by its
/// area. A spot nothing fits is left. Distances are updated in a window around each new element.
/// Returns the number added (a cut element counts once).
int fill_spots(Coverage& cov, const FillSetup& setup, const std::function<bool(const Vec2&)>& may_centre,
               const std::function<double(const Vec2&, double)>& density,
               const std::function<std::vector<std::vector<Vec2>>(const Vec2&, double)>& around,
               const std::function<bool(Mesh&, int)>& fits, const std::function<void(const Mesh&, int)>& add);

/// The sides of a convex polygon (counter-clockwise, as xy_hull gives it) worth measuring: edges of at
/// least 5% of its perimeter (a rounded corner is many short edges, not a side).
std::vector<std::size_t> hull_sides(const std::vector<Vec2>& hull);

/// How far side `edge` of `hull` (edge from vertex `edge` to the next) can move along its outward
/// normal before it meets one of `others` (convex polygons): the least distance along rays from
/// five points of the side's middle 80%. `limit` when no ray meets anything within it.
double side_clearance(const std::vector<Vec2>& hull, std::size_t edge, const std::vector<std::vector<Vec2>>& others, double limit);

/// Beyond the paper: joints. Where the stones of two placements meet, a paving (cobbles, tiles,
/// flagstones) shows joints wider than its own; a stone's side facing such a joint grows into it.
/// What that needs of a swatch, in the swatch's units.
struct JointSetup {
    bool paving = false;   ///< the median joint is narrower than kPavingJoint of the median blob's size
    double typical = 0.0;  ///< median joint (side clearance) between the swatch's blobs
    double wide = 0.0;     ///< 90th percentile: narrower joints are left alone
    double limit = 0.0;    ///< kJointReach * wide: farther neighbours are open ground, not a joint
    double reach = 0.0;    ///< the largest blob's half diagonal
};

/// A side facing a joint up to kJointReach times the swatch's 90th percentile grows; an element
/// grows to at most kMaxGrowth of its swatch element's area. A swatch is a paving when its median
/// joint is below kPavingJoint of its median blob's size (the square root of its footprint's area):
/// cobbles 0.09, pebbles 0.5, rivets 0.4.
inline constexpr double kJointReach = 4.0;
inline constexpr double kPavingJoint = 0.2;
inline constexpr double kMaxGrowth = 1.3;

/// Not a paving (nothing to close) unless the swatch's elements are disjoint blobs with at least 8
/// measured sides, and not layered (SwatchData::layered: overlapping scales have no joints).
JointSetup prepare_joints(const SwatchData& swatch);

/// Grows the sides of blob `m` (xy hull) that face joints wider than `setup.wide` and narrower than
/// `setup.limit` against the hulls `around`, towards the typical joint: by the whole excess, else by
/// half, else a quarter (push_side, at most 30% of the element's extent each), keeping the area within
/// kMaxGrowth of `source_area`. The first growth that `accept` takes is returned in `grown`; false
/// when no side faces a wide joint or none was accepted.
bool grow_into_joints(const Mesh& m, const std::vector<std::vector<Vec2>>& around, const JointSetup& setup, double source_area,
                      const std::function<bool(const Mesh&)>& accept, Mesh* grown);

/// Beyond the paper: gaps. Where three or more stones of different placements meet, the hole between
/// them has no side to push (grow_into_joints moves straight sides across straight joints); so after
/// the last placement each stone also grows radially. Seen from its hull's centre, in kGapDirections
/// directions, the hull's boundary point moves outward by its distance to the nearest other hull less
/// the swatch's typical joint (never by more than kGapRadialShare of its radius, and not at all where
/// that distance is a narrow joint, at most setup.wide, or where neither the ray nor rays
/// kGapConeHalfAngle either side of it meet a hull within setup.reach: open ground, such as the
/// base's boundary, is no gap; a single ray, passing through a joint beyond the hole, would find
/// too many holes open: spot with cobbles 0.806 against 0.814 in its lowest region). The
/// moves are eroded over the neighbouring directions, then applied by a radial map (a vertex at
/// relative radius s moves by s^2 of its direction's move: the centre stays, each ray keeps its order,
/// so nothing folds) at full, three quarters, half and a quarter, until `accept` takes one within
/// kMaxGrowth of `source_area`. A stone whose moves add less than kMinGapGain of its hull's area is
/// left alone. Returns false when nothing was grown.
inline constexpr int kGapDirections = 96;
inline constexpr double kGapRadialShare = 0.35;
inline constexpr double kMinGapGain = 0.02;
inline constexpr double kGapConeHalfAngle = 0.5236;  // 30 degrees
bool grow_into_gaps(const Mesh& m, const std::vector<std::vector<Vec2>>& around, const JointSetup& setup, double source_area,
                    const std::function<bool(const Mesh&)>& accept, Mesh* grown);

/// The radius of the largest empty disc centred in [x0, x1] x [y0, y1] among the elements of `m`
/// (xy projection, pixel resolution), with geometry anywhere in `m` counting.
double largest_empty_radius(const Mesh& m, double x0, double y0, double x1, double y1, double pixel);

}  // namespace meshquilt::quilt
