// SPDX-License-Identifier: AGPL-3.0-or-later
// Surface mesh quilting, Zhou et al. 2006 Section 3.1: the base mesh's triangles are the cells;
// each step flattens a disc around the most constrained unprocessed triangle with LSCM, runs the
// planar kernel (matching, correspondences, deformation, merging) in that plane, oriented by a
// direction field, and stores the resulting vertices relative to the base.

#include "core/intersect.h"
#include "core/links.h"
#include "core/triangle_index.h"
#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/surface.h"
#include "quilt/field.h"
#include "quilt/fill.h"
#include "quilt/holes.h"
#include "quilt/kernel.h"
#include "quilt/match.h"
#include "quilt/patch.h"
#include "quilt/solid_grid.h"
#include "quilt/swatch.h"
#include "quilt/trim.h"
#include "shellmap/visibility.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <deque>
#include <functional>
#include <map>
#include <queue>
#include <random>
#include <set>
#include <unordered_map>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace meshquilt {

namespace {

using quilt::area_centroid;
using quilt::mesh_area;
using quilt::Clock;
using quilt::kDensityInset;
using quilt::kMaxOutputFaces;
using quilt::num;
using quilt::seconds_since;

constexpr double kMaxBaseFaces = 4e6;
/// Local/global iterations of the rigid flattening of a free-element swatch's patches
/// (prepare_rigid_frames, quilt::flatten_arap). Not tuned: 10 take a hemisphere's area distortion
/// from LSCM's 3.80 to 1.84 (tests, Flattening); CGAL's default is 50, at 5 times the cost.
constexpr int kRigidIterations = 10;

/// Patches whose LSCM map distorts area by more than this (98th over 2nd percentile) shrink. The
/// paper allows 4; elements then vary in size by up to 2x, so we hold the map to 2.
constexpr double kMaxDistortion = 2.0;
/// New elements whose embedded area differs from their swatch element's (scaled) by more than this
/// factor are rescaled.
constexpr double kMaxSizeDrift = 1.02;
/// ... and elements of a lattice (keeps_lattice) by more than this: their patch's frame is scaled
/// for their size at its seed, and resizing one moves it against its neighbours.
constexpr double kLatticeSizeDrift = 1.3;

/// A bald spot is filled where the ground around it holds less than this share of the swatch's
/// density (fill_patch; quilt/fill.h), the standing elements claiming ground as claimed_ground
/// widens them. 0.85 (the 15% the stage allows) while they claimed their frame copies only, which
/// on thin parts read sparse: at 0.9 pebbles grew denser there still. With the claims, 0.9 keeps
/// rivets' sparsest region in the bar (the camelhead 0.833 -> 0.903 by count) and pebbles' densest
/// too (fertility 1.134 -> 1.101; docs/surface.md, step 8, "Fills counted on the base").
constexpr double kFillSparse = 0.9;
/// Dense spots after the last patch (thin_dense_spots): a free element's window (a ball holding
/// kThinWindow footprints of base area) with more than kThinCap of the swatch's density per base
/// area gives up its most crowded element, unless a window that element stands in would fall
/// below kThinFloor. The floor at 1.0 left the eight's densest regions by count at 1.107-1.160
/// over seeds 1-3; at 0.95, 1.064-1.119 (the tests' regions lowest 0.910).
constexpr double kThinWindow = 2.0;
constexpr double kThinCap = 1.08;
constexpr double kThinFloor = 0.95;
/// The rasters of a patch's footprint (bald spots, thread gaps) have at most about this many
/// pixels: their pixel follows the swatch's gaps, and the public snowflake swatch (elements 0.04
/// apart in a footprint 145 wide) asked for 37 million per patch, which took over ten minutes on
/// spot at scale 0.3.
constexpr double kMaxRasterPixels = 250000.0;
/// ... with a blob that keeps at least this share of its footprint and area (its size, the square
/// root of the area, stays within the factor 1.5 the stage promises).
constexpr double kFillMinArea = 0.5;
/// ... and only where at least this share of the density window lies on the patch.
constexpr double kFillOnPatch = 0.8;
/// The shell's widening under a standing blob (its middle surface's area over its base's) that
/// its claim on the ground of a patch frame follows, at most this factor either way (claimed_ground).
constexpr double kClaimWidening = 2.0;
/// A lattice slot is empty (mend_rings) when no element's centre lies within this share of the
/// swatch's ring spacing.
constexpr double kMendEmpty = 0.6;
/// A ring is mended (a lattice slot or a hole) only where the rings around it, the new one
/// counted, stay within this share of the swatch's rings per area of the surface (ring_crowd;
/// per area of the lattice's own spacing until session 49, below). Session 48, seed
/// 1: a rectangular 4-in-1 mail on an icosphere 1.121-1.165 -> 1.028-1.062, a loose one on the
/// eight 1.096-1.191 -> 1.089-1.158; the bundled mail's lowest regions on the shared meshes move
/// by -0.015 to +0.011 (fandisk 0.794 -> 0.805, the bunny 0.870 -> 0.855). At 1.25 the
/// rectangular mail keeps 1.073-1.119 in the test's regions (docs/surface.md step 10). Session
/// 49, counted on the surface at 1.15 (it was 1.1 in the lattice's spacing): the most rings per
/// base area in a region (region_count_density_max) on the shared meshes at most 1.134 (1.180
/// before), on the tests' eight at scale 0.2 1.126 (1.188), the loose mail there 1.112 (1.173).
/// At 1.1 the lowest regions fell by 0.012 on average (fandisk 0.836 -> 0.808), at 1.2 the
/// eight's densest region read 1.148 ...
constexpr double kRingCrowd = 1.15;
/// ... counted within this many ring spacings, each weighted by (1 - (d / r)^2)^2.
constexpr double kRingCrowdReach = 2.0;
/// A ring hole (fill_ring_holes) is a point of a mending frame farther than this many ring
/// spacings from every element's centre (a square lattice's widest is 0.71, the bundled chain mail's
/// 0.64 in the plane),
constexpr double kHoleEmpty = 0.75;
/// ... offered the kHoleSlots slots nearest to it of each of the nearest kHoleLattices rings' lattices,
constexpr int kHoleLattices = 2;
constexpr int kHoleSlots = 1;
/// ... moved to it and to points around it at these distances (spacings; 8 directions each),
constexpr std::array<double, 2> kHoleShifts{0.2, 0.4};
/// ... turned by up to this much either way (radians) in this many steps each side.
constexpr double kHoleTurn = 0.3;
constexpr int kHoleTurnSteps = 3;
/// ... at these shares of its size, in turn; a lattice slot (mend_slot without a hole's screen)
/// tries all but the last. Shrunk, a ring collides less; enlarged, last, one that fits a wide hole
/// but links with nothing around it reaches its neighbours (on spot 3,047 of the 10,495 untilted
/// tries embedded failed for want of a link alone). Session 40, chain mail at the default scale,
/// seed 1, lowest region: the eight 0.866 -> 0.891, fandisk 0.793 -> 0.817, spot 0.839 -> 0.847,
/// igea 0.848 -> 0.852, fertility 0.886 -> 0.874 (docs/surface.md step 10). Not for a thinned
/// swatch: its enlarged rings stood too close once thickened back (two below the size floor and
/// a region at 1.158 on the eight).
constexpr std::array<double, 4> kRingSizes{1.0, 0.92, 0.85, 1.1};
/// mend_slot tests this many poses per core at once, once the map's scale for the ring is known
/// (most slots refuse all their poses: on spot with chain mail 4,613 of 5,031 lattice slots tried
/// all ten).
constexpr int kMendBatch = 2;
/// ... and, when no pose of the swatch's ring fits, tilted by this much (radians) either way about
/// the swatch's x and y axes (ring_variant: kHoleVariants poses in all, the untilted first, each
/// lifted so it stays above the base). A ring between two lattices that meet at an angle sits
/// between their tilts. Tilted tries have their own budget (tilt_budget), kHoleTiltFree per ring
/// standing and kHoleTriesPerRing per tilted ring put in: on the armadillo, where few fit, they
/// stop early. A tilted ring, like every mended one, must keep kMendMinWidth of its swatch ring's
/// diameter once embedded (the shell flattens a ring that rises far above the slab), and a thinned
/// swatch (a tight mail) tries none: its tilted rings stood closer to their neighbours and were
/// thickened back less (0.69 of their size, and a region at 1.156 on the eight).
constexpr double kHoleTilt = 0.15;
constexpr int kHoleVariants = 5;
constexpr double kHoleTiltFree = 1.0;
/// A try with this many vertices inside a standing ring's solid, or of the ring's vertices in
/// the try's (SolidGrid: a swatch element's, kSolidCells along its longest side), is refused
/// before it is embedded ...
constexpr int kHoleClash = 2;
constexpr int kSolidCells = 64;
constexpr int kFrameSolidCells = 32;
/// ... against the standing rings whose centres lie within this many spacings of the hole (their
/// parts on the frame, kFrameSolidCells along the longest side).
constexpr double kHoleReach = 2.0;
/// A lattice slot blocked by at most this many standing rings may take their place (swap_blocker).
/// Session 50, fandisk's chain mail at the default scale, seed 1: with one, 117 swaps, 7,910 ->
/// 7,942 rings, lowest region by count 0.814 -> 0.852, mending 42 -> 44 s; with two, 168 swaps and
/// 7,970 rings, but the lowest region 0.836 and mending 75 s (beside another run).
constexpr std::size_t kSwapMost = 1;
/// ... with rings of its lattice within this many ring spacings of where the blockers stood.
constexpr double kSwapReach = 1.0;
/// A hole's tries ask first the vertices inside that refused its last tries (fill_ring_holes), at
/// most this many: a shortcut to the same answer (the eight's chain mail at scale 0.2: 3.0 million
/// tries screened, 2.8 million of them refused so).
constexpr std::size_t kClashMemory = 32;
/// Tries embedded for ring holes, at most, per ring standing when mending starts,
constexpr double kHoleBudget = 20.0;
/// ... and at most this many per ring standing (and 1,000) plus this many per ring put into a
/// hole (hole_budget): holes are tried while at least one try in kHoleTriesPerRing fits. (Chain
/// mail at the default scale, seed 1: with 1 and 50 the budget ran out on the armadillo after 17
/// holes had rings, 5,569 tries, with most of its seams not reached; with these 596 holes take
/// rings in 57,325 tries, the budget never binding, and its mean density rises from 0.865 to
/// 0.934, the thinnest region's from 0.714 to 0.772; the camelhead 25 -> 413 rings, 0.884 ->
/// 0.926 and 0.731 -> 0.782.)
constexpr double kHoleTriesFree = 4.0;
constexpr long kHoleTriesPerRing = 200;
/// A boundary loop of the base that spans at most this share of the footprint's longer side is a
/// hole to fill on the synthesis's copy (quilt/holes.h), if it has at most kFillHoleVertices
/// vertices: a scan's missing triangles, not a tube's open end.
constexpr double kFillHoleExtent = 0.25;
constexpr int kFillHoleVertices = 100;
/// A mended ring may link with the rings whose centres lie within this many spacings of its own.
constexpr double kMendLinkReach = 1.6;
/// A mended ring keeps at least this share of its swatch element's size (square root of area).
constexpr double kMendMinSize = 0.75;
/// ... and this much of its swatch ring's diameter (mend_slot).
constexpr double kMendMinWidth = 0.75;
/// An element the patch places keeps at least this share of its swatch element's size (the square
/// root of the area, a lowered shell's flattening included): the stage promises a factor 1.5
/// (0.667), and 0.7 leaves a margin.
constexpr double kMinElementSize = 0.7;
/// ... and at most this many times it (the promise of 1.5 with a margin): an element the map
/// stretches over a sharp tip (the armadillo's claws: a scale 1.59 times its size) is refused.
constexpr double kMaxElementSize = 1.4;
/// ... and one below it is first enlarged in the frame to this share of its size.
constexpr double kGrowBackSize = 0.85;
/// The report counts elements whose size is off their swatch element's by more than this factor
/// (issue 3's acceptance: within 1.5).
constexpr double kReportedSizeFactor = 1.5;
/// Below this share of the swatch's density in some region, the result carries a warning.
constexpr double kSparseWarning = 0.5;
/// warp_to_old_rings: an old ring pairs with a new ring of its kind within this many spacings,
constexpr double kWarpReach = 0.5;
/// ... turned by less than this against it (radians),
constexpr double kWarpMaxTurn = 0.35;
/// ... and its offset spreads with a Gaussian this many spacings wide, against this weight for staying.
constexpr double kWarpSigma = 1.5;
constexpr double kWarpStay = 0.05;
/// Mending passes at most (each over the faces near the rings the last one added).
constexpr int kMendPasses = 6;
/// Thread mending passes at most (mend_threads; on the eight at scale 0.2 a second pass added 3
/// threads to the first's 23, for as much time).
constexpr int kThreadMendPasses = 1;
/// Joint mending passes at most (mend_joints; with cobbles at the default scale, seed 1, before the
/// open-ground rays of grow_into_gaps, lowest region and mean density: spot one pass 0.799 and 0.916,
/// two 0.806 and 0.925; the bunny 0.837 and 0.903, 0.848 and 0.911; the second pass costs about as
/// much as the first).
constexpr int kJointMendPasses = 2;
/// ... then, where a mending frame's map distorted area by more than kMaxDistortion, frames of this
/// share of the size tile that ground once more.
constexpr double kThreadMendSmall = 0.35;
// A new thread that collides is cut kTrimMargin of its width clear of what it meets; pieces
// shorter than kTrimMinLength widths are dropped (a thread is more than 3 times longer than wide).
constexpr double kTrimMargin = 0.1;
/// A thread's face stretched by its embedding to more than this many times its area, against the
/// median face's growth, is where the embedding tore it (stretched_faces). (Bunny + Weave: at 4,
/// 129 threads torn, lowest region 0.755 -> 0.658, the fans having counted as cover; at 8, 50
/// and 0.725, but the eight's test region fell to 0.840; at 16 faces of 4.7 times the swatch's
/// largest were left.)
constexpr double kMaxFaceStretch = 4.0;
/// An element (not a thread or strand) with a face larger than this many times the swatch's
/// largest face, on the surface at the run's scale, is torn (torn): the bound the surface tests hold
/// every output to.
constexpr double kTornFace = 4.0;
constexpr double kTrimMinLength = 3.2;
// A new thread reaching off its patch is cut kTrimEdgeMargin of its width inside the patch.
constexpr double kTrimEdgeMargin = 0.25;
/// A gap between the threads that run one way (fill_threads_patch) is a missing thread when its
/// empty disc is wider in radius than this share of the swatch's spacing of those threads (a plain
/// weave's own gaps: about 0.3, one thread missing: about 0.7).
constexpr double kThreadGap = 0.55;
/// Gaps tried per direction and patch at most (fill_threads_patch; 16 is more than any patch of
/// the eight, spot or bunny had).
constexpr int kThreadFillTries = 16;
/// Beyond the paper: a thread (new, stitched or deformed) that grazes another element with a few
/// faces (a stitch's deformation moved it a hair; a tight weave's threads are a tenth of their
/// width apart where they cross) is dented clear of it, as a real thread flattens where it is
/// pressed (dent_clear): the vertices of its colliding faces move inward along their normals by
/// kDentStep of its thickness per try (their neighbours by half, the next ring by a quarter), at
/// most kDentTries times, and only while the colliding faces are at most kDentMaxShare of its faces.
constexpr double kDentStep = 0.06;
constexpr int kDentTries = 3;
constexpr double kDentMaxShare = 0.02;
/// A gap whose neighbouring threads of the same direction turn from the frame's axis by at least
/// this much (radians, 3 degrees; parallel_angle) gets a thread turned with them when one along
/// the axis does not fit.
constexpr double kThreadTurnMin = 3.0 * M_PI / 180.0;
/// A thread laid into a gap is tried on kThreadLines lines an eighth of a spacing apart across
/// it, centred on the gap's knot line, at kThreadShifts shifts along itself over two spacings
/// (where its ends and its waviness fall), woven through the crossing threads (quilt::woven)...
constexpr int kThreadLines = 5;
constexpr int kThreadShifts = 4;
/// ... of which those whose longest run clear of the crossing threads in the frame (free_run) is at
/// least this share of kTrimMinLength widths, and at most kThreadShiftsEmbedded of them (the
/// longest runs), are embedded and tested.
constexpr double kThreadFreeRun = 0.5;
constexpr std::size_t kThreadShiftsEmbedded = 4;

/// The faces whose corners are all `ok`, with only the vertices they use (an element partly off a
/// patch: its other vertices have no place in the frame, and a test reading every vertex, such as
/// element_gap or xy_hull, must not see them).
Mesh mapped_part(const std::vector<Vec3>& vertices, const std::vector<Tri>& faces, const std::vector<char>& ok) {
    Mesh part;
    std::vector<int> slot(vertices.size(), -1);
    for (const Tri& t : faces) {
        if (!ok[static_cast<std::size_t>(t[0])] || !ok[static_cast<std::size_t>(t[1])] || !ok[static_cast<std::size_t>(t[2])]) continue;
        Tri u;
        for (int k = 0; k < 3; ++k) {
            int& id = slot[static_cast<std::size_t>(t[k])];
            if (id < 0) {
                id = static_cast<int>(part.vertices.size());
                part.vertices.push_back(vertices[static_cast<std::size_t>(t[k])]);
            }
            u[k] = id;
        }
        part.faces.push_back(u);
    }
    return part;
}

/// Faces of `embedded` (an element on the surface, face for face `frame`, its mesh in a patch frame)
/// that the embedding stretched: whose area grew more than kMaxFaceStretch times as much as the
/// element's faces did at the median, among faces larger than the median embedded face (a sliver
/// in the frame may well grow). Empty when none is.
std::vector<char> stretched_faces(const Mesh& frame, const Mesh& embedded) {
    const std::size_t n = std::min(frame.faces.size(), embedded.faces.size());
    auto area = [](const Mesh& m, std::size_t f) {
        const Tri& t = m.faces[f];
        const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
        return 0.5 * (m.vertices[static_cast<std::size_t>(t[1])] - a).cross(m.vertices[static_cast<std::size_t>(t[2])] - a).norm();
    };
    std::vector<double> before(n), after(n), ratio, sizes;
    for (std::size_t f = 0; f < n; ++f) {
        before[f] = area(frame, f);
        after[f] = area(embedded, f);
        sizes.push_back(after[f]);
        if (before[f] > 0.0) ratio.push_back(after[f] / before[f]);
    }
    if (ratio.empty()) return {};
    auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    const double grow = median(ratio), typical = median(sizes);
    std::vector<char> out(embedded.faces.size(), 0);
    bool any = false;
    for (std::size_t f = 0; f < n; ++f)
        if (after[f] > typical && after[f] > kMaxFaceStretch * grow * before[f]) out[f] = 1, any = true;
    if (!any) return {};
    return out;
}

/// The base as the synthesis uses it: exact duplicate vertices welded, closed inside-out components
/// flipped, long edges split.
struct Base {
    Mesh mesh;
    std::vector<std::array<int, 3>> nb;
    std::vector<Vec3> normal;    ///< per vertex (area weighted)
    std::vector<Vec3> centroid;  ///< per face
    std::vector<double> area;    ///< per face
    std::vector<std::vector<int>> vertex_faces;
    double total_area = 0.0;
};

Mesh weld(const Mesh& in) {
    Mesh out;
    std::map<std::array<double, 3>, int> index;
    std::vector<int> remap(in.vertices.size(), -1);
    for (const Tri& t : in.faces)
        for (int k = 0; k < 3; ++k) {
            const int v = t[k];
            if (remap[static_cast<std::size_t>(v)] >= 0) continue;
            const Vec3& p = in.vertices[static_cast<std::size_t>(v)];
            auto [it, fresh] = index.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(out.vertices.size()));
            if (fresh) out.vertices.push_back(p);
            remap[static_cast<std::size_t>(v)] = it->second;
        }
    for (const Tri& t : in.faces)
        out.faces.emplace_back(remap[static_cast<std::size_t>(t[0])], remap[static_cast<std::size_t>(t[1])], remap[static_cast<std::size_t>(t[2])]);
    return out;
}

struct SurfElement {
    std::vector<SurfacePoint> anchors;
    std::vector<Tri> faces;
    int source = -1;
    bool alive = false;
    int collider_id = -1;
    std::vector<int> base_faces;  ///< distinct base faces its vertices lie on
    Mesh embedded;
    std::vector<Vec3> centerline;  ///< rings (is_ring_source): the embedded ring's centre line (core/links.h)
    bool cut = false;              ///< a strand cut (quilt::strand_pieces) or stitched to another length: its size is not measured
};

class SurfaceQuilter {
public:
    SurfaceQuilter(const Mesh& base, const Mesh& swatch, const SurfaceQuiltOptions& o) : opt_(o) {
        auto t0 = Clock::now();
        validate_options();
        if (base.faces.empty()) throw InvalidInput("base has no faces");
        if (swatch.faces.empty()) throw InvalidInput("swatch has no faces");
        if (!thin_axis_of(bounding_box(swatch)).is_thin)
            throw InvalidInput("swatch has no thin axis: its smallest extent is more than half the middle one; a swatch must be a slab");
        sw_ = quilt::prepare_swatch(swatch);
        if (const std::string turned = sw_.turn_warning(); !turned.empty()) warnings_.push_back(turned);
        if (const std::string w = sw_.solidify_warning(); !w.empty()) warnings_.push_back(w);
        if (const std::string w = sw_.intersect_warning(); !w.empty()) warnings_.push_back(w);
        for (std::size_t e = 0; e < sw_.elements.size(); ++e) rings_ = rings_ || is_ring_source(static_cast<int>(e));
        interlocked_ = rings_ && swatch_rings_interlock();
        prepare_ring_kinds();
        prepare_ring_need();
        fill_ = quilt::prepare_fill(sw_, min_raster_pixel(), kFillSparse, kFillMinArea, true);
        joints_ = quilt::prepare_joints(sw_);
        prepare_thread_sets();
        prepare_lattice_probe();
        prepare_rigid_frames();
        fill_.area_floor = fill_.smallest_blob_area;
        index_ = TriangleIndex(sw_.mesh);
        const double lx = sw_.box.max.x(), ly = sw_.box.max.y();
        cell_ = std::max(lx, ly) / 24.0;
        sx_ = static_cast<int>(std::floor(lx / cell_ + 1e-9));
        sy_ = static_cast<int>(std::floor(ly / cell_ + 1e-9));
        k_ = std::max(2, static_cast<int>(std::lround(std::min(sx_, sy_) / 3.0)));
        k_ = std::min({k_, sx_, sy_});
        for (const Mesh& e : sw_.elements) {
            const Box3 b = bounding_box(e);
            element_diag_ = std::max(element_diag_, std::hypot(b.size().x(), b.size().y()));
            for (std::size_t f = 0; f < e.faces.size(); ++f) largest_face_ = std::max(largest_face_, face_area(e, f));
        }
        params_.metric.lambda = opt_.lambda;
        params_.metric.unit = sw_.mean_edge;
        params_.mu = opt_.mu;
        params_.thread_remnants = true;
        params_.layered = sw_.layered;
        params_.layer_gap = sw_.elements_disjoint && sw_.layered ? sw_.near_gap : 0.0;
        params_.strands = sw_.element_strand;
        params_.strand_losers = std::any_of(sw_.element_strand.begin(), sw_.element_strand.end(), [](char c) { return c != 0; });
        rng_.seed(opt_.seed);
        stage_seconds_["prepare swatch"] += seconds_since(t0);
        t0 = Clock::now();
        prepare_base(base);
        stage_seconds_["prepare base"] += seconds_since(t0);
        build_shell();
        const std::vector<double> mid = middle_areas();
        widening_.resize(mid.size());
        for (std::size_t f = 0; f < mid.size(); ++f) widening_[f] = base_.area[f] > 0.0 && mid[f] > 0.0 ? mid[f] / base_.area[f] : 1.0;
    }

    SurfaceQuiltResult run() {
        const std::size_t F = base_.mesh.faces.size();
        processed_.assign(F, 0);
        score_.assign(F, 0);
        elems_on_face_.assign(F, {});
        face_slot_.assign(F, -1);
        frame_dir_.assign(F, Vec3::Zero());
        std::size_t done = 0;
        const std::size_t max_steps = 4 * F + 16;
        for (std::size_t step = 0; step < max_steps && done < F; ++step) {
            const int seed = find_seed();
            done += place_patch(seed);
            opt_.reporter.report("quilting", static_cast<double>(done) / static_cast<double>(F));
        }
        if (done < F) throw Error(ErrorCode::Internal, "surface quilting did not reach every base triangle");
        auto t0 = Clock::now();
        if (rings_) {
            // Beyond the paper: in an interlocking swatch (chain mail) a ring that holds on to no
            // other is loose in the fabric (it would fall out of a print); it goes, and mending may
            // put a linked ring in its slot.
            // A connecting ring (one that joins exactly two rings in the swatch, as the small rings
            // of a Japanese 4-in-1 do) that holds on to one joins nothing: it goes too. Removing it
            // may loosen another ring, so this repeats until nothing goes.
            for (bool removed = interlocked_; removed;) {
                removed = false;
                for (const auto& [id, n] : ring_links())
                    if (n < ring_need_[static_cast<std::size_t>(elems_[static_cast<std::size_t>(id)].source)]) {
                        remove_element(id);
                        ++surface_.rings_unlinked_removed;
                        removed = true;
                    }
            }
            mend_rings();
        } else if (sw_.layered) {
            mend_rings();
        }
        stage_seconds_["mending"] += seconds_since(t0);
        t0 = Clock::now();
        if (!thread_sets_[0].ids.empty() || !thread_sets_[1].ids.empty()) {
            const int before = surface_.threads_filled;
            mend_threads();
            surface_.threads_mended = surface_.threads_filled - before;
        }
        stage_seconds_["thread gaps"] += seconds_since(t0);
        t0 = Clock::now();
        mend_joints();
        stage_seconds_["joints"] += seconds_since(t0);
        t0 = Clock::now();
        thin_dense_spots();
        stage_seconds_["dense spots"] += seconds_since(t0);
        SurfaceQuiltResult result;
        finish(result);
        return result;
    }

private:
    void validate_options() const {
        auto bad = [](double v) { return !std::isfinite(v); };
        if (opt_.scale && (bad(*opt_.scale) || *opt_.scale <= 0.0 || *opt_.scale > 2.0))
            throw InvalidInput("scale must be in (0, 2] (a fraction of the base's bounding-box diagonal), got " + num(*opt_.scale));
        if (bad(opt_.default_face_budget) || opt_.default_face_budget < 0.0)
            throw InvalidInput("the default face budget must be positive or 0, got " + num(opt_.default_face_budget));
        if (bad(opt_.swatch_size) || opt_.swatch_size < 0.0) throw InvalidInput("swatch size must be positive, got " + num(opt_.swatch_size));
        if (bad(opt_.height) || opt_.height < 0.0) throw InvalidInput("height must be positive, got " + num(opt_.height));
        if (!(opt_.symmetry == 0 || opt_.symmetry == 1 || opt_.symmetry == 2 || opt_.symmetry == 4 || opt_.symmetry == 6))
            throw InvalidInput("symmetry must be 1, 2, 4 or 6 (or 0 to detect it), got " + std::to_string(opt_.symmetry));
        if (bad(opt_.lambda) || opt_.lambda <= 0) throw InvalidInput("lambda must be positive");
        if (bad(opt_.mu) || opt_.mu <= 0) throw InvalidInput("mu must be positive");
        if (bad(opt_.tolerance) || opt_.tolerance < 0) throw InvalidInput("tolerance must be >= 0");
    }

    void prepare_base(const Mesh& input) {
        Mesh m = weld(input);
        const MeshAnalysis an = analyse(m);
        // Components that face inwards are flipped (the decoration grows along the normals). Closed
        // ones by the sign of their volume; open ones (a scan with holes) only when they clearly
        // enclose space: the signed volume of the cones from their centroid is negative and at least
        // a tenth of what a sphere of the same area holds. An open sheet is left as it is.
        const std::vector<int> comp = connected_components(m);
        const std::size_t ncomp = an.elements.size();
        std::vector<Vec3> centre(ncomp, Vec3::Zero());
        std::vector<double> area(ncomp, 0.0), cone(ncomp, 0.0);
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            const double a = face_area(m, f);
            centre[static_cast<std::size_t>(comp[f])] += a * face_centroid(m, f);
            area[static_cast<std::size_t>(comp[f])] += a;
        }
        for (std::size_t e = 0; e < ncomp; ++e)
            if (area[e] > 0) centre[e] /= area[e];
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            const auto e = static_cast<std::size_t>(comp[f]);
            const Tri& t = m.faces[f];
            const Vec3 a = m.vertices[static_cast<std::size_t>(t[0])] - centre[e], b = m.vertices[static_cast<std::size_t>(t[1])] - centre[e],
                       c = m.vertices[static_cast<std::size_t>(t[2])] - centre[e];
            cone[e] += a.dot(b.cross(c)) / 6.0;
        }
        std::vector<char> flip(ncomp, 0);
        int open_flipped = 0;
        for (std::size_t e = 0; e < ncomp; ++e) {
            const bool closed = an.elements[e].closed;
            const double sphere = std::pow(area[e], 1.5) / (6.0 * std::sqrt(M_PI));
            if ((closed && an.elements[e].volume < 0) || (!closed && cone[e] < -0.1 * sphere)) {
                flip[e] = 1;
                ++surface_.base_flipped_components;
                if (!closed) ++open_flipped;
            }
        }
        if (surface_.base_flipped_components > 0) {
            for (std::size_t f = 0; f < m.faces.size(); ++f)
                if (flip[static_cast<std::size_t>(comp[f])]) std::swap(m.faces[f][1], m.faces[f][2]);
            warnings_.push_back("the base has " + std::to_string(surface_.base_flipped_components) + " component(s) facing inwards (" +
                                std::to_string(open_flipped) + " of them open); they were flipped so the decoration grows outwards");
        }
        // Non-manifold vertices are split below, once small holes are filled (two holes touching
        // at a vertex are filled as two, which makes the vertex manifold again).
        if (an.non_manifold_edges > 0)
            throw InvalidInput("base is not manifold (" + std::to_string(an.non_manifold_edges) + " non-manifold edges); repair it first");
        const Box3 box = bounding_box(m);
        diagonal_ = box.size().norm();
        if (!(diagonal_ > 0)) throw InvalidInput("base has zero extent");
        double fp = opt_.swatch_size > 0 ? opt_.swatch_size : opt_.scale.value_or(kDefaultScale) * diagonal_;
        // Beyond the paper: the default scale suits swatches of a few dozen elements; a dense one
        // (hundreds of elements, or many faces each) would make tens of millions of faces there. Left
        // to the default, the footprint grows until the estimated output fits the budget.
        const double swatch_faces = static_cast<double>(sw_.mesh.faces.size());
        const double swatch_xy = sw_.box.size().x() * sw_.box.size().y() / std::pow(std::max(sw_.box.size().x(), sw_.box.size().y()), 2);
        auto faces_at = [&](double footprint) { return an.area / (swatch_xy * footprint * footprint) * swatch_faces; };
        if (!opt_.scale && !(opt_.swatch_size > 0) && opt_.default_face_budget > 0 && faces_at(fp) > opt_.default_face_budget) {
            const double before = faces_at(fp);
            fp *= std::sqrt(before / opt_.default_face_budget);
            warnings_.push_back("the swatch has " + std::to_string(sw_.mesh.faces.size()) + " faces: at the default scale " + num(kDefaultScale) +
                                " the output would hold about " + num(std::round(before / 1e5) / 10.0) + " million faces, so the scale was raised to " +
                                num(fp / diagonal_) + " (about " + num(std::round(faces_at(fp) / 1e5) / 10.0) +
                                " million); pass --scale or --swatch-size to choose");
        }
        surface_.scale = fp / diagonal_;
        scale_ = fp / std::max(sw_.box.size().x(), sw_.box.size().y());  // base units per swatch unit
        const double thickness = sw_.box.size().z();
        height_scale_ = opt_.height > 0 ? opt_.height / std::max(thickness, 1e-300) : 0.0;
        const double shell = opt_.height > 0 ? opt_.height : thickness * scale_;
        if (shell > 0.25 * diagonal_)
            throw InvalidInput("the shell height " + num(shell) + " is more than a quarter of the base's diagonal " + num(diagonal_) +
                               ": the swatch is too thick for this base at this scale; choose a smaller --scale or --height");
        // Absurd scales: too many footprints, output or refined faces.
        const double fp_area = sw_.box.size().x() * sw_.box.size().y() * scale_ * scale_;
        const double footprints = an.area / fp_area;
        const double est_faces = footprints * static_cast<double>(sw_.mesh.faces.size());
        if (est_faces > kMaxOutputFaces)
            throw InvalidInput("at this scale the base holds about " + std::to_string(static_cast<long long>(footprints)) +
                               " swatch footprints, about " + std::to_string(static_cast<long long>(est_faces / 1e6)) +
                               " million output faces (limit " + std::to_string(static_cast<long long>(kMaxOutputFaces / 1e6)) +
                               " million): choose a larger --scale or --swatch-size");

        // Small holes (a scan's missing triangles) are filled on our copy: a patch must be a disc,
        // and each hole smaller than a patch cut the patches around it short (quilt/holes.h).
        // Filled faces are appended and no vertex is added, so a user field's indices still hold.
        const quilt::HoleFilling holes = quilt::fill_small_holes(m, kFillHoleExtent * fp, kFillHoleVertices);
        surface_.base_holes_filled = holes.filled;
        if (holes.filled > 0)
            warnings_.push_back("the base has " + std::to_string(holes.loops) + " holes; the " + std::to_string(holes.filled) +
                                " smaller than " + num(kFillHoleExtent) + " of the swatch footprint (at most " + num(holes.largest) +
                                " across) were filled on the synthesis's copy, so the decoration runs across them");
        // Welding can join fans of faces that the input kept apart (an STL soup of two solids that
        // touch at a corner, or a base whose non-manifold vertices --repair split): where filling
        // did not join them, each fan gets a vertex of its own again (the synthesis's copy only).
        if (const int n = analyse(m).non_manifold_vertices; n > 0) {
            split_non_manifold_vertices(m);
            warnings_.push_back("the base touches itself at " + std::to_string(n) + (n == 1 ? " non-manifold vertex" : " non-manifold vertices") +
                                " (separate fans of faces meet there); each fan is decorated on its own");
        }

        // Field on the welded base, before refinement (user indices refer to it).
        symmetry_ = opt_.symmetry > 0 ? opt_.symmetry : quilt::detect_symmetry(sw_);
        const auto nb0 = quilt::face_neighbours(m);
        const quilt::DirectionField field = quilt::compute_field(m, nb0, symmetry_, opt_.field, "field");
        min_field_scale_ = *std::min_element(field.scale.begin(), field.scale.end());

        // Cells finer than a sixth of the (smallest local) footprint.
        const double max_edge = fp * min_field_scale_ / 6.0;
        const double est_refined = an.area / (0.4 * max_edge * max_edge) + static_cast<double>(m.faces.size());
        if (est_refined > kMaxBaseFaces)
            throw InvalidInput("the swatch footprint " + num(fp * min_field_scale_) + " is too small for this base (diagonal " + num(diagonal_) +
                               "): it would take about " + std::to_string(static_cast<long long>(est_refined)) +
                               " base triangles; choose a larger --scale or --swatch-size");
        std::vector<int> parent;
        base_.mesh = quilt::refine_long_edges(m, max_edge, &parent, &surface_.base_thin_faces_remeshed);
        if (opt_.embedding == Embedding::Shell) {
            // Folds (a scan's crumpled slivers, where no direction sees every face around a vertex
            // from outside) would leave shell prisms inverted: such vertices of our copy move to
            // their neighbours' mean.
            surface_.base_fold_vertices_smoothed = shell::smooth_folds(base_.mesh, shell::kMinSeeingCos);
            if (surface_.base_fold_vertices_smoothed > 0)
                warnings_.push_back("the base folds onto itself at " + std::to_string(surface_.base_fold_vertices_smoothed) +
                                    " vertices; they were smoothed (on the synthesis's copy) so the shell can be built there");
        }
        const std::size_t F = base_.mesh.faces.size();
        base_.nb = quilt::face_neighbours(base_.mesh);
        base_.normal = vertex_normals(base_.mesh);
        base_.centroid.resize(F);
        base_.area.resize(F);
        base_.vertex_faces.assign(base_.mesh.vertices.size(), {});
        for (std::size_t f = 0; f < F; ++f) {
            base_.centroid[f] = face_centroid(base_.mesh, f);
            base_.total_area += (base_.area[f] = face_area(base_.mesh, f));
            for (int k = 0; k < 3; ++k) base_.vertex_faces[static_cast<std::size_t>(base_.mesh.faces[f][k])].push_back(static_cast<int>(f));
        }
        direction_.resize(F);
        local_scale_.resize(F);
        for (std::size_t f = 0; f < F; ++f) {
            const int p = parent[f] >= 0 ? parent[f] : 0;
            direction_[f] = field.direction[static_cast<std::size_t>(p)];
            local_scale_[f] = field.scale[static_cast<std::size_t>(p)];
        }
        surface_.base_faces = static_cast<int>(F);
        surface_.symmetry = symmetry_;
        surface_.base_scale = scale_;
        surface_.embedding = opt_.embedding;
        // The shell holds the tallest elements: the field's largest scale sets its height.
        const double max_local = *std::max_element(local_scale_.begin(), local_scale_.end());
        surface_.shell_height = opt_.height > 0 ? opt_.height : thickness * scale_ * max_local;
    }

    /// Section 3.2: the shell map over the base as used, tall enough for the tallest elements.
    void build_shell() {
        if (opt_.embedding != Embedding::Shell) return;
        auto t0 = Clock::now();
        ShellOptions so;
        so.reporter = opt_.reporter;
        so.height = surface_.shell_height;
        so.optimise = opt_.optimise_shell;
        so.seed = opt_.seed;
        // Thread swatches: charts with slits, as their patch discs (make_frame).
        so.close_chart_slits = !has_threads_;
        shell_ = std::make_shared<const ShellMap>(base_.mesh, so);
        surface_.shell = shell_->statistics();
        stage_seconds_["shell map"] += seconds_since(t0);
        if (surface_.shell.height_limited_vertices > 0)
            warnings_.push_back("the shell height was lowered at " + std::to_string(surface_.shell.height_limited_vertices) + " base vertices (" +
                                num(100.0 * surface_.shell.limited_area_fraction) + "% of the area, down to " +
                                num(100.0 * surface_.shell.min_height_ratio) +
                                "% of the height) where the base is concave or narrow; the decoration is flattened there");
        if (surface_.shell.inverted_world > 0 || surface_.shell.offset_intersections > 0)
            warnings_.push_back("the shell could not be made valid everywhere (" + std::to_string(surface_.shell.inverted_world) +
                                " inverted tetrahedra, " + std::to_string(surface_.shell.offset_intersections) +
                                " places where the offset surface or another part of the base still meets the shell): the base is crumpled there");
    }

    /// The unprocessed face with the most processed faces around its corners; ties at random.
    int find_seed() {
        int best = -1;
        std::vector<int> ties;
        for (std::size_t f = 0; f < processed_.size(); ++f) {
            if (processed_[f]) continue;
            if (score_[f] > best) {
                best = score_[f];
                ties.clear();
            }
            if (score_[f] == best) ties.push_back(static_cast<int>(f));
        }
        std::uniform_int_distribution<std::size_t> pick(0, ties.size() - 1);
        return ties[pick(rng_)];
    }

    void mark_processed(int f) {
        if (processed_[static_cast<std::size_t>(f)]) return;
        processed_[static_cast<std::size_t>(f)] = 1;
        std::vector<int> around;
        for (int k = 0; k < 3; ++k)
            for (int g : base_.vertex_faces[static_cast<std::size_t>(base_.mesh.faces[static_cast<std::size_t>(f)][k])]) around.push_back(g);
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
        for (int g : around)
            if (g != f) ++score_[static_cast<std::size_t>(g)];
    }

    double height_scale(double local) const { return height_scale_ > 0 ? height_scale_ : scale_ * local; }

    /// The shell's height over a surface point as a fraction of the full height (1 without a shell):
    /// where the shell was lowered, texture height h lands about h times this above the base.
    double shell_ratio(const SurfacePoint& sp) const {
        if (!shell_) return 1.0;
        const std::vector<double>& h = shell_->heights();
        const Tri& t = base_.mesh.faces[static_cast<std::size_t>(sp.face)];
        double r = 0.0;
        for (int k = 0; k < 3; ++k) r += sp.bary[k] * h[static_cast<std::size_t>(t[k])];
        return std::clamp(r / surface_.shell_height, 1e-6, 1.0);
    }

    Vec3 embed(const SurfacePoint& sp) const {
        if (shell_) return shell_->map(sp);
        const Tri& t = base_.mesh.faces[static_cast<std::size_t>(sp.face)];
        Vec3 p = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(t[k]);
            p += sp.bary[k] * (base_.mesh.vertices[v] + sp.height * base_.normal[v]);
        }
        return p;
    }

    /// A tangent vector on base face `flat.faces[lf]` in the patch's flat coordinates (through the
    /// face's affine map).
    Vec2 to_flat(const quilt::FlatPatch& flat, std::size_t lf, const Vec3& v) const {
        const Tri& t = base_.mesh.faces[static_cast<std::size_t>(flat.faces[lf])];
        const Tri& lt = flat.local[lf];
        Eigen::Matrix<double, 3, 2> E;
        E << base_.mesh.vertices[static_cast<std::size_t>(t[1])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])],
            base_.mesh.vertices[static_cast<std::size_t>(t[2])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])];
        const Eigen::Vector2d ab = E.colPivHouseholderQr().solve(v);
        return ab[0] * (flat.uv[static_cast<std::size_t>(lt[1])] - flat.uv[static_cast<std::size_t>(lt[0])]) +
               ab[1] * (flat.uv[static_cast<std::size_t>(lt[2])] - flat.uv[static_cast<std::size_t>(lt[0])]);
    }

    /// The 3D direction of the patch frame's +x axis on base face `flat.faces[lf]`.
    Vec3 frame_x_on(const quilt::FlatPatch& flat, std::size_t lf) const {
        const Tri& t = base_.mesh.faces[static_cast<std::size_t>(flat.faces[lf])];
        const Tri& lt = flat.local[lf];
        Eigen::Matrix2d U;
        U << flat.uv[static_cast<std::size_t>(lt[1])] - flat.uv[static_cast<std::size_t>(lt[0])],
            flat.uv[static_cast<std::size_t>(lt[2])] - flat.uv[static_cast<std::size_t>(lt[0])];
        const Eigen::Vector2d ab = U.colPivHouseholderQr().solve(Eigen::Vector2d(1.0, 0.0));
        const Vec3 d = ab[0] * (base_.mesh.vertices[static_cast<std::size_t>(t[1])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])]) +
                       ab[1] * (base_.mesh.vertices[static_cast<std::size_t>(t[2])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])]);
        return d.allFinite() && d.norm() > 0 ? Vec3(d.normalized()) : Vec3::Zero();
    }

    /// Patch frame: flat coordinates (swatch units, seed centroid at the origin, field along +x).
    struct Frame {
        quilt::FlatPatch flat;  ///< uv already in the patch frame
        double local = 1.0;     ///< field scale at the seed
    };

    /// Grows and flattens the patch around `seed`, shrinking it while LSCM distorts area too much,
    /// but not below the size of the swatch's largest element (a smaller patch could hold none).
    /// (Tried and dropped: keeping the disc large for mapping old elements and shrinking only a
    /// "core" for new ones; the large disc's map distorts the core more, and runs got slower
    /// without denser results.)
    bool make_frame(int seed, Frame* frame) {
        const double local = local_scale_[static_cast<std::size_t>(seed)];
        const double diag = std::hypot(sx_ * cell_, sy_ * cell_) * scale_ * local;
        double min_radius = std::min(1.25 * diag, 1.2 * element_diag_ * scale_ * local);
        // Seeds move along the synthesis front, so the radius that passed last time is a good start
        // (each try costs a disc and an LSCM solve); it may grow back by 1.3 per patch.
        double max_radius = 1.25 * diag;
        if (frame_cap_ > 0.0) {
            max_radius *= frame_cap_;
            min_radius = std::min(min_radius, max_radius);
        }
        double radius = last_radius_ > 0 ? std::clamp(1.3 * last_radius_ * local, min_radius, max_radius) : max_radius;
        quilt::FlatPatch flat;
        bool ok = false;
        for (int attempt = 0; attempt < 8; ++attempt) {
            // Thread swatches grow their discs as before session 56, with slits (docs/surface.md
            // step 4, "Thin parts were slow": whole discs cost the armadillo's weave 0.856 -> 0.644
            // in its lowest region at seed 1, 889 -> 351 patches; with slits again 0.869, 915).
            const std::vector<int> faces = quilt::grow_disc(base_.mesh, base_.nb, base_.centroid, seed, radius, !has_threads_);
            ok = quilt::flatten_lscm(base_.mesh, faces, &flat);
            if (ok && (faces.size() <= 1 || radius <= min_radius || quilt::area_distortion(base_.mesh, flat) <= kMaxDistortion)) break;
            if (!ok && radius <= min_radius) break;
            radius = std::max(min_radius, 0.7 * radius);
            if (attempt == 0) ++surface_.patches_shrunk;
        }
        // A free-element swatch's disc is flattened again, as rigid as possible (prepare_rigid_frames).
        if (ok && rigid_frames_ && flat.faces.size() > 1) {
            quilt::FlatPatch rigid;
            if (quilt::flatten_arap(base_.mesh, flat.faces, &rigid, kRigidIterations)) {
                flat = std::move(rigid);
                ++surface_.patches_rigid;
            }
        }
        last_radius_ = radius / local;
        if (!ok && !quilt::flatten_lscm(base_.mesh, {seed}, &flat)) return false;  // the seed alone is always flat
        const Vec3 c0 = base_.centroid[static_cast<std::size_t>(seed)];
        // Orientation: the N-th power average of the field over faces near the seed, in flat
        // coordinates, goes to +x. Of its N directions we take the one closest to the frames of the
        // patches already placed around (recorded per face): a swatch is rarely truly N-symmetric
        // (chain mail rows have a direction), and a frame turned by 360/N degrees against its
        // neighbours would not match their lattice. Origin: the seed's centroid.
        const int N = symmetry_;
        std::complex<double> sum = 0.0, previous = 0.0;
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            const auto f = static_cast<std::size_t>(flat.faces[lf]);
            const bool near_seed = (base_.centroid[f] - c0).norm() <= 0.35 * diag || static_cast<int>(f) == seed;
            if (!near_seed && frame_dir_[f].squaredNorm() == 0.0) continue;
            if (near_seed) {
                const Vec2 d = to_flat(flat, lf, direction_[f]);
                if (d.norm() > 0.0 && d.allFinite()) sum += base_.area[f] * std::polar(1.0, N * std::atan2(d.y(), d.x()));
            }
            if (frame_dir_[f].squaredNorm() > 0.0) {
                const Vec2 d = to_flat(flat, lf, frame_dir_[f]);
                if (d.norm() > 0.0 && d.allFinite()) previous += base_.area[f] * std::polar(1.0, std::atan2(d.y(), d.x()));
            }
        }
        double angle = std::abs(sum) > 0 ? std::arg(sum) / N : 0.0;
        if (std::abs(previous) > 0) {
            const double ref = std::arg(previous);
            double best = angle, best_gap = 1e300;
            for (int k = 0; k < N; ++k) {
                const double a = angle + 2.0 * M_PI * k / N;
                const double gap = std::fabs(std::remainder(a - ref, 2.0 * M_PI));
                if (gap < best_gap) {
                    best_gap = gap;
                    best = a;
                }
            }
            angle = best;
        }
        // Scale: flat area equals 3D area near the seed, where the swatch goes (LSCM is conformal,
        // so the scale varies over the patch; matching it at the centre keeps elements true to size).
        double flat_area = 0.0, true_area = 0.0;
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            const auto f = static_cast<std::size_t>(flat.faces[lf]);
            if ((base_.centroid[f] - c0).norm() > 0.5 * diag && static_cast<int>(f) != seed) continue;
            const Tri& lt = flat.local[lf];
            const Vec2 a = flat.uv[static_cast<std::size_t>(lt[1])] - flat.uv[static_cast<std::size_t>(lt[0])];
            const Vec2 b = flat.uv[static_cast<std::size_t>(lt[2])] - flat.uv[static_cast<std::size_t>(lt[0])];
            flat_area += 0.5 * std::fabs(a.x() * b.y() - a.y() * b.x());
            true_area += base_.area[f];
        }
        const double conformal = (flat_area > 0 && true_area > 0) ? std::sqrt(true_area / flat_area) : 1.0;
        // Seed centroid in flat coordinates.
        Vec2 origin = Vec2::Zero();
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf)
            if (flat.faces[lf] == seed)
                for (int k = 0; k < 3; ++k) origin += flat.uv[static_cast<std::size_t>(flat.local[lf][k])] / 3.0;
        const double c = std::cos(-angle), s = std::sin(-angle), inv = conformal / (scale_ * local);
        for (Vec2& q : flat.uv) {
            const Vec2 d = q - origin;
            q = Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y()) * inv;
        }
        frame->flat = std::move(flat);
        frame->local = local;
        return true;
    }

    /// A surface point in the frame of the current patch (`face_slot_` set); false off the patch.
    bool map_to_frame(const quilt::FlatPatch& flat, double hs, const SurfacePoint& sp, Vec3* out) const {
        const int slot = face_slot_[static_cast<std::size_t>(sp.face)];
        if (slot < 0) return false;
        const Tri& lt = flat.local[static_cast<std::size_t>(slot)];
        const Vec2 q = sp.bary[0] * flat.uv[static_cast<std::size_t>(lt[0])] + sp.bary[1] * flat.uv[static_cast<std::size_t>(lt[1])] +
                       sp.bary[2] * flat.uv[static_cast<std::size_t>(lt[2])];
        *out = Vec3(q.x(), q.y(), sp.height / hs);
        return true;
    }

    /// A standing element's pose in a patch frame: the similarity x -> A x + t (A a rotation times
    /// a scale) that best carries its swatch element's vertices onto its frame copy, in xy (2D
    /// Procrustes), and the rms distance left.
    struct Pose {
        int source = -1;
        Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
        Vec2 t = Vec2::Zero();
        double residual = 0.0;
    };
    /// The pose of `e` in the frame of `flat`; false when the element is not wholly on the patch or
    /// no longer has its swatch element's vertices (a stitched thread).
    bool element_pose(const SurfElement& e, const quilt::FlatPatch& flat, double hs, Pose* pose) const {
        if (e.source < 0) return false;
        const Mesh& src = sw_.elements[static_cast<std::size_t>(e.source)];
        const std::size_t n = e.anchors.size();
        if (src.vertices.size() != n || n == 0) return false;
        std::vector<Vec2> at(n);
        for (std::size_t v = 0; v < n; ++v) {
            Vec3 q;
            if (!map_to_frame(flat, hs, e.anchors[v], &q)) return false;
            at[v] = q.head<2>();
        }
        Vec2 ps = Vec2::Zero(), qs = Vec2::Zero();
        for (std::size_t v = 0; v < n; ++v) {
            ps += src.vertices[v].head<2>();
            qs += at[v];
        }
        ps /= static_cast<double>(n);
        qs /= static_cast<double>(n);
        double a = 0.0, b = 0.0, pp = 0.0;
        for (std::size_t v = 0; v < n; ++v) {
            const Vec2 p = src.vertices[v].head<2>() - ps, q = at[v] - qs;
            a += p.dot(q);
            b += p.x() * q.y() - p.y() * q.x();
            pp += p.squaredNorm();
        }
        if (!(pp > 0.0)) return false;
        pose->source = e.source;
        pose->A << a / pp, -b / pp, b / pp, a / pp;
        pose->t = qs - pose->A * ps;
        double err = 0.0;
        for (std::size_t v = 0; v < n; ++v) err += (pose->A * src.vertices[v].head<2>() + pose->t - at[v]).squaredNorm();
        pose->residual = std::sqrt(err / static_cast<double>(n));
        return pose->A.allFinite() && pose->t.allFinite();
    }

    /// The turn of the old rings near the seed against the frame: of the rings' poses
    /// (element_pose), the angle most of them agree on (within a few degrees), each weighted by its
    /// closeness to the seed; 0 without rings or beyond 60 degrees (a frame the field turned by one
    /// of its symmetries). The frame's N-symmetric field gives each patch its orientation; on a
    /// doubly curved base neighbouring patches' lattices then meet at 10-20 degrees (eight, scale
    /// 0.2: median 9.7 degrees between a new frame and the old rings in it), and interlocked rings
    /// collide along the seam. Turned by this, the new lattice continues the old one at the seed.
    double lattice_turn(const quilt::FlatPatch& flat, double hs) const {
        std::vector<std::pair<double, double>> votes;  // angle, weight
        const double R = 0.5 * std::hypot(sx_, sy_) * cell_;
        Pose pose;
        for (int id : near_elements(flat)) {
            const SurfElement& e = elems_[static_cast<std::size_t>(id)];
            if (!is_ring_source(e.source) || !element_pose(e, flat, hs, &pose)) continue;
            const Vec2 centre = pose.A * area_centroid(sw_.elements[static_cast<std::size_t>(e.source)]).head<2>() + pose.t;
            votes.emplace_back(std::atan2(pose.A(1, 0), pose.A(0, 0)), std::exp(-centre.squaredNorm() / (R * R)));
        }
        double best = 0.0, best_score = 0.0;
        constexpr double kSigma = 3.0 * M_PI / 180.0;
        for (const auto& [t, unused] : votes) {
            double score = 0.0;
            for (const auto& [u, w] : votes) {
                const double d = std::remainder(u - t, 2.0 * M_PI);
                score += w * std::exp(-d * d / (2.0 * kSigma * kSigma));
            }
            if (score > best_score) {
                best_score = score;
                best = t;
            }
        }
        return std::fabs(best) <= M_PI / 3.0 ? best : 0.0;
    }

    /// Beyond the paper: the new rings are moved onto the old lattice around them. lattice_turn
    /// continues the old rings at the seed, but a patch is a footprint wide, and on a doubly curved
    /// base the old lattice (from other charts) drifts against the new one away from the seed, so
    /// interlocked rings at the patch's far side collide where they should link. Each old ring wholly
    /// on the patch is paired with the nearest new ring of its kind (the same swatch ring up to a
    /// lattice shift) within kWarpReach spacings; their offset and turn spread over the new rings
    /// with Gaussian weights (kWarpSigma spacings) against a weight for staying (kWarpStay), and
    /// each new ring is moved rigidly by its share: a smooth warp that bends the new lattice into
    /// the old one where they meet and leaves it alone away from old rings.
    void warp_to_old_rings(std::vector<quilt::NewElement>* fresh, const std::vector<quilt::OldElement>& old, const quilt::FlatPatch& flat,
                           double hs) const {
        if (!interlocked_ || ring_spacing_ <= 0.0) return;
        struct Pin {
            Vec2 at, offset;
            double turn;
        };
        std::vector<Vec2> centre(fresh->size());
        for (std::size_t j = 0; j < fresh->size(); ++j) centre[j] = area_centroid((*fresh)[j].mesh).head<2>();
        std::vector<Pin> pins;
        Pose pose;
        for (const quilt::OldElement& o : old) {
            const SurfElement& e = elems_[static_cast<std::size_t>(o.id)];
            if (!is_ring_source(e.source) || !element_pose(e, flat, hs, &pose)) continue;
            const Vec2 c = pose.A * ring_centre_[static_cast<std::size_t>(e.source)] + pose.t;
            const int kind = ring_kind_[static_cast<std::size_t>(e.source)];
            double best = kWarpReach * ring_spacing_;
            int partner = -1;
            for (std::size_t j = 0; j < fresh->size(); ++j) {
                const int s = (*fresh)[j].source;
                if (s < 0 || ring_kind_[static_cast<std::size_t>(s)] != kind) continue;
                const double d = (centre[j] - c).norm();
                if (d < best) {
                    best = d;
                    partner = static_cast<int>(j);
                }
            }
            const double turn = std::atan2(pose.A(1, 0), pose.A(0, 0));
            if (partner >= 0 && std::fabs(turn) < kWarpMaxTurn) pins.push_back({centre[static_cast<std::size_t>(partner)], c - centre[static_cast<std::size_t>(partner)], turn});
        }
        if (pins.empty()) return;
        const double sigma2 = kWarpSigma * kWarpSigma * ring_spacing_ * ring_spacing_;
        for (std::size_t j = 0; j < fresh->size(); ++j) {
            quilt::NewElement& ne = (*fresh)[j];
            if (!is_ring_source(ne.source)) continue;
            double w = kWarpStay, turn = 0.0;
            Vec2 offset = Vec2::Zero();
            for (const Pin& p : pins) {
                const double wi = std::exp(-(p.at - centre[j]).squaredNorm() / sigma2);
                w += wi;
                offset += wi * p.offset;
                turn += wi * p.turn;
            }
            offset /= w;
            turn /= w;
            const double c = std::cos(turn), s = std::sin(turn);
            for (Vec3& v : ne.mesh.vertices) {
                const Vec2 d = v.head<2>() - centre[j];
                v.head<2>() = centre[j] + offset + Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y());
            }
        }
    }

    /// Ring kinds and spacing for warp_to_old_rings (quilt::ring_lattice: rings that are translates
    /// of one another are of one kind).
    void prepare_ring_kinds() {
        const std::size_t n = sw_.elements.size();
        ring_kind_.assign(n, -1);
        ring_centre_.assign(n, Vec2::Zero());
        std::vector<char> is_ring(n, 0);
        for (std::size_t s = 0; s < n; ++s) {
            is_ring[s] = is_ring_source(static_cast<int>(s));
            ring_centre_[s] = area_centroid(sw_.elements[s]).head<2>();
        }
        if (!interlocked_) return;
        const quilt::RingLattice lattice = quilt::ring_lattice(sw_, is_ring);
        ring_spacing_ = lattice.spacing;
        if (lattice.kind.size() == n) ring_kind_ = lattice.kind;
    }

    /// The smallest pixel of a footprint raster (kMaxRasterPixels).
    double min_raster_pixel() const { return std::sqrt(sw_.box.size().x() * sw_.box.size().y() / kMaxRasterPixels); }

    /// Rings: closed elements of genus >= 1 that are not threads (they interlock on a lattice).
    bool is_ring_source(int s) const {
        return s >= 0 && sw_.element_genus[static_cast<std::size_t>(s)] > 0 && !quilt::is_elongated(sw_.elements[static_cast<std::size_t>(s)]);
    }
    /// Elements whose empty lattice slots are mended after the last patch (mend_rings): rings, and
    /// a layered swatch's blobs (scales lie in rows, each over the next, and a missing scale leaves a
    /// slot that no bald-spot disc measures: its neighbours overlap it).
    bool is_lattice_source(int s) const { return is_ring_source(s) || (sw_.layered && quilt::is_blob_source(sw_, s)); }

    /// Beyond the paper: elements that hold on to their neighbours where the swatch has them, the
    /// rings of a chain mail (interlocked_) and the threads of a weave (both directions), are
    /// resized one by one (embed_sized) only beyond kLatticeSizeDrift. Resizing about each
    /// element's own centre, in xy only, moved every ring against the lattice its neighbours were
    /// placed on, tilted it, and broke the tight links of a chain mail (a ring and the one it links
    /// with are 0.12 of the spacing apart in the swatch): of 225 lattice slots tried next to one
    /// patch's rings on the eight, every one collided, nearly all in the frame already. Their
    /// patch's frame is scaled instead (fit_lattice_scale).
    bool keeps_lattice(int s) const {
        if (s < 0) return false;
        if (interlocked_ && is_ring_source(s)) return true;
        return woven_ && quilt::is_elongated(sw_.elements[static_cast<std::size_t>(s)]);
    }

    /// Scales a lattice swatch's patch frame (keeps_lattice) so that the swatch's middle, placed at
    /// the seed, comes out at its size on the surface: the one scale that embed_sized would give
    /// each element there, given to the frame as a whole, so the lattice stays a lattice (an xy
    /// scale of the frame carries disjoint elements to disjoint ones) while the map's scale still
    /// varies over the patch (within kMaxDistortion).
    void fit_lattice_scale(Frame* fr, double hs) const {
        if (lattice_probe_.faces.empty() || height_scale_ > 0) return;
        const quilt::PatchLocator probe(fr->flat);
        std::vector<SurfacePoint> anchors;
        if (!to_surface(lattice_probe_, fr->flat, probe, hs, &anchors)) return;
        const double ratio = size_ratio(lattice_probe_, anchors, embed_element(anchors, lattice_probe_.faces), fr->local);
        if (!(ratio > 0.25 && ratio < 4.0)) return;
        const double g = std::sqrt(ratio);
        for (Vec2& q : fr->flat.uv) q *= g;
    }

    /// Beyond the paper: a swatch of free elements (no rings, threads or strands: pebbles, rivets,
    /// cobbles, scales) has its patches flattened again as rigid as possible (ARAP from LSCM's map,
    /// on the disc the shrinking loop of make_frame chose). The kernel lays the swatch's spacing out
    /// in the frame and each element gets its size on the surface, not its place, so where LSCM
    /// shrinks area the elements stand closer (on the armadillo's hands half the pebbles stood
    /// where their patch's map shrank area by over 1.2 against its seed, up to 7, and the hands
    /// were 1.19-1.21 times the swatch's count at seeds 1-3; with ARAP the densest regions anywhere
    /// are 1.12-1.13). ARAP keeps area as well as angles allow.
    /// Lattice swatches keep LSCM: a ring's or thread's neighbours are bound to its angles, and on
    /// the eight at scale 0.2, ARAP frames gave chain mail 5% fewer rings (session 52).
    void prepare_rigid_frames() {
        has_threads_ = !thread_sets_[0].ids.empty() || !thread_sets_[1].ids.empty();
        rigid_frames_ = !rings_ && !has_threads_;
        for (std::size_t s = 0; s < sw_.elements.size() && rigid_frames_; ++s)
            if (quilt::is_strand_source(sw_, static_cast<int>(s))) rigid_frames_ = false;
    }

    /// The probe of fit_lattice_scale: the swatch's faces within a quarter of its smaller side of its
    /// middle (xy), moved so that the middle is at the origin; empty for other swatches.
    void prepare_lattice_probe() {
        woven_ = !thread_sets_[0].ids.empty() && !thread_sets_[1].ids.empty();
        lattice_probe_ = Mesh();
        if (!interlocked_ && !woven_) return;
        const Vec2 mid = 0.5 * (sw_.box.min + sw_.box.max).head<2>();
        const double r = 0.25 * std::min(sw_.box.size().x(), sw_.box.size().y());
        for (std::size_t e = 0; e < sw_.elements.size(); ++e) {
            if (!keeps_lattice(static_cast<int>(e))) continue;
            const Mesh& m = sw_.elements[e];
            std::vector<char> in(m.vertices.size());
            std::vector<Vec3> at(m.vertices.size());
            for (std::size_t v = 0; v < m.vertices.size(); ++v) {
                in[v] = (m.vertices[v].head<2>() - mid).norm() <= r;
                at[v] = Vec3(m.vertices[v].x() - mid.x(), m.vertices[v].y() - mid.y(), m.vertices[v].z());
            }
            const Mesh part = mapped_part(at, m.faces, in);
            const int base = static_cast<int>(lattice_probe_.vertices.size());
            lattice_probe_.vertices.insert(lattice_probe_.vertices.end(), part.vertices.begin(), part.vertices.end());
            for (const Tri& t : part.faces) lattice_probe_.faces.push_back({t[0] + base, t[1] + base, t[2] + base});
        }
    }

    /// Thread `m` (a frame mesh) on the patch: itself when it lies wholly on it, else its parts on
    /// it, cut kTrimEdgeMargin of its width inside (quilt/trim.h) and at least kTrimMinLength widths
    /// long (`cut` set). With `within`, parts outside that rectangle (xy) are cut off too.
    static std::vector<Mesh> on_patch(const Mesh& m, const quilt::PatchLocator& locator, bool* cut, const Box3* within = nullptr) {
        std::vector<char> off(m.vertices.size(), 0);
        for (std::size_t v = 0; v < m.vertices.size(); ++v) {
            const Vec3& p = m.vertices[v];
            off[v] = static_cast<char>(!locator.locate(p.head<2>(), 0.0).inside ||
                                       (within && (p.x() < within->min.x() || p.y() < within->min.y() || p.x() > within->max.x() || p.y() > within->max.y())));
        }
        *cut = std::find(off.begin(), off.end(), 1) != off.end();
        if (!*cut) return {m};
        std::vector<char> bad(m.faces.size(), 0);
        for (std::size_t f = 0; f < m.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) bad[f] = static_cast<char>(bad[f] | off[static_cast<std::size_t>(m.faces[f][k])]);
        const Vec3 size = bounding_box(m).size();
        const double width = std::min(size.x(), size.y());
        std::vector<Mesh> out;
        for (Mesh& piece : quilt::thread_pieces(m, bad, {kTrimEdgeMargin * width, kTrimMinLength * width}))
            if (std::all_of(piece.vertices.begin(), piece.vertices.end(), [&](const Vec3& v) { return locator.locate(v.head<2>(), 0.0).inside; }))
                out.push_back(std::move(piece));
        return out;
    }

    /// Returns the number of faces newly processed.
    std::size_t place_patch(int seed) {
        auto t0 = Clock::now();
        Frame fr;
        if (!make_frame(seed, &fr)) {
            mark_processed(seed);
            return 1;
        }
        const quilt::FlatPatch& flat = fr.flat;
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) face_slot_[static_cast<std::size_t>(flat.faces[lf])] = static_cast<int>(lf);
        const double hs = height_scale(fr.local);
        if (rings_) {
            // Beyond the paper: a ring lattice is turned to continue the old one (lattice_turn).
            const double turn = lattice_turn(flat, hs);
            if (turn != 0.0) {
                const double c = std::cos(-turn), s = std::sin(-turn);
                for (Vec2& q : fr.flat.uv) q = Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y());
            }
        }
        fit_lattice_scale(&fr, hs);
        const quilt::PatchLocator locator(flat);
        stage_seconds_["patches"] += seconds_since(t0);
        t0 = Clock::now();

        // Old elements in the patch frame: whole ones for the kernel, partial ones as obstacles.
        const std::vector<int> near = near_elements(flat);
        auto map_point = [&](const SurfacePoint& sp, Vec3* out) { return map_to_frame(flat, hs, sp, out); };
        std::vector<quilt::OldElement> old;
        std::vector<Mesh> obstacles;  // mappable triangles of partial elements
        reach_.clear();
        // Each old element is mapped on its own (map_to_frame and extend_thread are const), in
        // parallel, then taken in order.
        struct Seen {
            enum class As { whole, extended, obstacle } as = As::obstacle;
            Mesh mesh;
            Reach reach;
        };
        std::vector<Seen> seen(near.size());
        tbb::parallel_for(std::size_t{0}, near.size(), [&](std::size_t i) {
            const SurfElement& e = elems_[static_cast<std::size_t>(near[i])];
            Seen& s = seen[i];
            Mesh& m = s.mesh;
            m.vertices.assign(e.anchors.size(), Vec3::Zero());
            std::vector<char> ok(e.anchors.size(), 0);
            bool whole = true;
            for (std::size_t v = 0; v < e.anchors.size(); ++v) {
                ok[v] = map_point(e.anchors[v], &m.vertices[v]);
                whole = whole && ok[v];
            }
            if (whole) {
                m.faces = e.faces;
                s.as = Seen::As::whole;
            } else if (extend_thread(e, ok, flat, hs, &m, &s.reach)) {
                s.as = Seen::As::extended;
            } else {
                m = mapped_part(m.vertices, e.faces, ok);
            }
        });
        for (std::size_t i = 0; i < near.size(); ++i) {
            Seen& s = seen[i];
            switch (s.as) {
            case Seen::As::whole: old.push_back({near[i], std::move(s.mesh)}); break;
            case Seen::As::extended:
                // Beyond the paper: a thread reaching beyond the patch still takes part, with its far
                // vertices carried into the frame along its own edges (see extend_thread). The kernel
                // leaves a thread's part off the contested ground exactly where it was, so those
                // vertices go back to their own anchors (apply).
                ++surface_.threads_extended;
                reach_[near[i]] = std::move(s.reach);
                old.push_back({near[i], std::move(s.mesh)});
                break;
            case Seen::As::obstacle:
                ++surface_.frozen_elements_seen;
                obstacles.push_back(std::move(s.mesh));
                break;
            }
        }
        // Occupancy raster in the patch frame (cells of the swatch grid).
        Occupancy occ;
        occ.init(flat, cell_);
        for (const auto& o : old) occ.add(o.mesh);
        for (const auto& m : obstacles) occ.add(m);

        // Matching (Section 2.4) over whole-cell translations covering P_out around the seed.
        const int pi0 = -k_ / 2, pj0 = -k_ / 2;
        const double px0 = pi0 * cell_, py0 = pj0 * cell_, px1 = (pi0 + k_) * cell_, py1 = (pj0 + k_) * cell_;
        std::vector<quilt::Sample> samples;
        auto add_samples = [&](const Mesh& m) {
            if (m.faces.empty()) return;
            const std::vector<Vec3> n = vertex_normals(m);
            for (std::size_t v = 0; v < m.vertices.size(); ++v) {
                const Vec3& p = m.vertices[v];
                if (n[v].squaredNorm() > 0 && p.x() >= px0 && p.x() < px1 && p.y() >= py0 && p.y() < py1) samples.push_back({p, n[v]});
            }
        };
        for (const auto& o : old) add_samples(o.mesh);
        for (const auto& m : obstacles) add_samples(m);
        quilt::Placement pl = quilt::place_swatch(sw_, index_, params_.metric, samples, pi0, pj0, k_, sx_, sy_, cell_, opt_.tolerance, rng_);
        warp_to_old_rings(&pl.fresh, old, flat, hs);
        const int ti = pl.ti, tj = pl.tj;
        stage_seconds_["matching"] += seconds_since(t0);
        t0 = Clock::now();

        // The placed swatch: elements that land wholly on the flattened patch.
        const double fx0 = ti * cell_, fy0 = tj * cell_, fx1 = (ti + sx_) * cell_, fy1 = (tj + sy_) * cell_;
        // Each element on its own, in parallel, then taken in order.
        std::vector<std::vector<Mesh>> kept(pl.fresh.size());
        std::vector<char> kept_cut(pl.fresh.size(), 0);
        tbb::parallel_for(std::size_t{0}, pl.fresh.size(), [&](std::size_t i) {
            Mesh& m = pl.fresh[i].mesh;
            if (!quilt::is_elongated(m)) {
                if (std::all_of(m.vertices.begin(), m.vertices.end(), [&](const Vec3& v) { return locator.locate(v.head<2>(), 0.0).inside; }))
                    kept[i].push_back(std::move(m));
                return;
            }
            // Beyond the paper: a thread reaching off the patch keeps its parts on it (quilt/trim.h).
            bool cut = false;
            kept[i] = on_patch(m, locator, &cut);
            kept_cut[i] = static_cast<char>(cut);
        });
        std::vector<quilt::NewElement> fresh;
        for (std::size_t i = 0; i < pl.fresh.size(); ++i)
            for (Mesh& piece : kept[i]) {
                if (kept_cut[i]) ++surface_.threads_cut_at_patch;
                fresh.push_back({pl.fresh[i].source, std::move(piece)});
            }
        quilt::Overlap overlap;
        overlap.old_side = [fx0, fy0, fx1, fy1](double x, double y) { return x >= fx0 && x < fx1 && y >= fy0 && y < fy1; };
        overlap.new_side = [&occ](double x, double y) { return occ.occupied(x, y); };
        const quilt::PatchPlan plan = quilt::plan_patch(old, fresh, overlap, params_, obstacles);
        report_.stitch_failures += plan.stitch_failures;
        report_.elements_crowded_out += plan.crowding;
        stage_seconds_["merging"] += seconds_since(t0);
        t0 = Clock::now();

        apply(plan, flat, locator, hs, fr.local, old, obstacles);
        stage_seconds_["collisions"] += seconds_since(t0);
        t0 = Clock::now();
        fill_patch(flat, locator, hs, fr.local, fx0, fy0, fx1, fy1);
        stage_seconds_["bald spots"] += seconds_since(t0);
        t0 = Clock::now();
        fill_threads_patch(flat, locator, hs, fr.local, fx0, fy0, fx1, fy1);
        stage_seconds_["thread gaps"] += seconds_since(t0);
        t0 = Clock::now();
        close_joints_patch(flat, locator, hs, fr.local, fx0, fy0, fx1, fy1);
        stage_seconds_["joints"] += seconds_since(t0);

        // Faces under the placed footprint are processed (the seed always).
        std::size_t newly = 0;
        auto mark = [&](int f) {
            if (!processed_[static_cast<std::size_t>(f)]) {
                mark_processed(f);
                ++newly;
            }
            const int slot = face_slot_[static_cast<std::size_t>(f)];
            if (slot >= 0) frame_dir_[static_cast<std::size_t>(f)] = frame_x_on(flat, static_cast<std::size_t>(slot));
        };
        mark(seed);
        // Faces under the footprint are processed, except near the patch's cut (where the patch
        // ends but the surface goes on): elements reaching over the cut were not placed, so that
        // ground waits for a later patch. The mesh's own boundary is no cut.
        std::vector<Vec2> cut;
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            const auto f = static_cast<std::size_t>(flat.faces[lf]);
            for (int k = 0; k < 3; ++k) {
                const int g = base_.nb[f][static_cast<std::size_t>(k)];
                if (g >= 0 && face_slot_[static_cast<std::size_t>(g)] < 0) {
                    cut.push_back(flat.uv[static_cast<std::size_t>(flat.local[lf][k])]);
                    cut.push_back(0.5 * (flat.uv[static_cast<std::size_t>(flat.local[lf][k])] + flat.uv[static_cast<std::size_t>(flat.local[lf][(k + 1) % 3])]));
                }
            }
        }
        const double margin = std::min(0.5 * element_diag_, 3.0 * cell_);
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            Vec2 c = Vec2::Zero();
            for (int k = 0; k < 3; ++k) c += flat.uv[static_cast<std::size_t>(flat.local[lf][k])] / 3.0;
            if (c.x() < fx0 || c.x() >= fx1 || c.y() < fy0 || c.y() >= fy1) continue;
            bool near_cut = false;
            for (const Vec2& q : cut)
                if ((q - c).squaredNorm() < margin * margin) {
                    near_cut = true;
                    break;
                }
            if (!near_cut) mark(flat.faces[lf]);
        }
        for (int f : flat.faces) face_slot_[static_cast<std::size_t>(f)] = -1;
        ++report_.patches;
        ++phase_count_[{((ti % sx_) + sx_) % sx_, ((tj % sy_) + sy_) % sy_}];
        return newly;
    }

    /// Which cells of the patch frame hold old geometry (Section 2.5's "already synthesised").
    struct Occupancy {
        Vec2 lo;
        double cell = 1.0;
        int nx = 0, ny = 0;
        std::vector<char> on;
        void init(const quilt::FlatPatch& flat, double c) {
            cell = c;
            Vec2 a = Vec2::Constant(std::numeric_limits<double>::infinity()), b = -a;
            for (const Vec2& q : flat.uv) {
                a = a.cwiseMin(q);
                b = b.cwiseMax(q);
            }
            lo = a - Vec2::Constant(2 * c);
            nx = static_cast<int>(std::ceil((b.x() - lo.x()) / c)) + 3;
            ny = static_cast<int>(std::ceil((b.y() - lo.y()) / c)) + 3;
            on.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
        }
        void add(const Mesh& m) {
            for (const Tri& t : m.faces) {
                Vec2 a = m.vertices[static_cast<std::size_t>(t[0])].head<2>(), b = a;
                for (int k = 1; k < 3; ++k) {
                    a = a.cwiseMin(m.vertices[static_cast<std::size_t>(t[k])].head<2>());
                    b = b.cwiseMax(m.vertices[static_cast<std::size_t>(t[k])].head<2>());
                }
                const int i0 = std::max(0, static_cast<int>(std::floor((a.x() - lo.x()) / cell)));
                const int i1 = std::min(nx - 1, static_cast<int>(std::floor((b.x() - lo.x()) / cell)));
                const int j0 = std::max(0, static_cast<int>(std::floor((a.y() - lo.y()) / cell)));
                const int j1 = std::min(ny - 1, static_cast<int>(std::floor((b.y() - lo.y()) / cell)));
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i) on[static_cast<std::size_t>(j * nx + i)] = 1;
            }
        }
        [[nodiscard]] bool occupied(double x, double y) const {
            const int i = static_cast<int>(std::floor((x - lo.x()) / cell)), j = static_cast<int>(std::floor((y - lo.y()) / cell));
            if (i < 0 || j < 0 || i >= nx || j >= ny) return false;
            return on[static_cast<std::size_t>(j * nx + i)] != 0;
        }
    };

    /// Frame positions of an old element's vertices that the patch does not cover, keyed back to
    /// their anchors (`reach_`, per old element id, for one patch).
    using Reach = std::map<std::array<double, 3>, SurfacePoint>;

    /// For an old element only partly on the patch (`mapped[v]`: vertex v has frame coordinates in
    /// `m`): when it is a thread (quilt::is_elongated), gives every other vertex frame coordinates,
    /// breadth first along the element's edges from the mapped ones: a vertex reached from w lies at
    /// w's position plus the base-point offset between the two, taken through the affine map of the
    /// patch face w was mapped by (its chart is continued flat beyond the patch). Heights are the
    /// anchors'. Fills `m` (faces included) and `reach` with the carried positions; false (nothing
    /// changed) for compact elements.
    bool extend_thread(const SurfElement& e, const std::vector<char>& mapped, const quilt::FlatPatch& flat, double hs, Mesh* m,
                       Reach* reach) const {
        // Threads come from thread swatch elements: compact ones are turned away before any work.
        if (e.source < 0 || !quilt::is_elongated(sw_.elements[static_cast<std::size_t>(e.source)])) return false;
        const std::size_t n = e.anchors.size();
        auto base_point = [&](const SurfacePoint& sp) {
            const Tri& t = base_.mesh.faces[static_cast<std::size_t>(sp.face)];
            return Vec3(sp.bary[0] * base_.mesh.vertices[static_cast<std::size_t>(t[0])] +
                        sp.bary[1] * base_.mesh.vertices[static_cast<std::size_t>(t[1])] +
                        sp.bary[2] * base_.mesh.vertices[static_cast<std::size_t>(t[2])]);
        };
        std::vector<std::vector<int>> nbr(n);
        for (const Tri& t : e.faces)
            for (int k = 0; k < 3; ++k) nbr[static_cast<std::size_t>(t[k])].push_back(t[(k + 1) % 3]);
        std::vector<int> via(n, -1);  // the patch face (local index) each vertex is mapped through
        std::vector<int> queue;
        for (std::size_t v = 0; v < n; ++v)
            if (mapped[v]) {
                via[v] = face_slot_[static_cast<std::size_t>(e.anchors[v].face)];
                queue.push_back(static_cast<int>(v));
            }
        if (queue.empty()) return false;
        Mesh out = *m;
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const auto w = static_cast<std::size_t>(queue[head]);
            for (int u : nbr[w]) {
                const auto uu = static_cast<std::size_t>(u);
                if (via[uu] >= 0) continue;
                via[uu] = via[w];
                const Vec2 d = to_flat(flat, static_cast<std::size_t>(via[w]), base_point(e.anchors[uu]) - base_point(e.anchors[w]));
                out.vertices[uu] = Vec3(out.vertices[w].x() + d.x(), out.vertices[w].y() + d.y(), e.anchors[uu].height / hs);
                queue.push_back(u);
            }
        }
        if (queue.size() != n) return false;  // vertices without faces: leave the element alone
        if (!std::all_of(out.vertices.begin(), out.vertices.end(), [](const Vec3& p) { return p.allFinite(); })) return false;
        out.faces = e.faces;
        if (!quilt::is_elongated(out)) return false;  // a remnant of a thread, shorter than wide
        reach->clear();
        for (std::size_t v = 0; v < n; ++v)
            if (!mapped[v]) (*reach)[{out.vertices[v].x(), out.vertices[v].y(), out.vertices[v].z()}] = e.anchors[v];
        *m = std::move(out);
        return true;
    }

    /// A kernel mesh (patch frame) as surface points; false when a vertex is off the patch.
    /// Vertices found in `reach` (a thread's part beyond the patch, unchanged) take their own anchors.
    bool to_surface(const Mesh& m, const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs,
                    std::vector<SurfacePoint>* out, const Reach* reach = nullptr) const {
        out->resize(m.vertices.size());
        for (std::size_t v = 0; v < m.vertices.size(); ++v) {
            const Vec3& p = m.vertices[v];
            if (reach) {
                const auto it = reach->find({p.x(), p.y(), p.z()});
                if (it != reach->end()) {
                    (*out)[v] = it->second;
                    continue;
                }
            }
            const auto hit = locator.locate(p.head<2>(), 2.0 * cell_);
            if (hit.local_face < 0) return false;
            (*out)[v] = {flat.faces[static_cast<std::size_t>(hit.local_face)], hit.bary, p.z() * hs};
        }
        // Deformation can push a bottom vertex a little below z = 0, into the base: the whole element
        // is lifted by that much (clamping single vertices would fold the element's underside).
        double lowest = 0.0;
        for (const SurfacePoint& sp : *out) lowest = std::min(lowest, sp.height);
        if (lowest < 0.0)
            for (SurfacePoint& sp : *out) sp.height -= lowest;
        // In the shell, an element that deformation (or the lift) made taller than the shell is
        // scaled down in height to fit: no vertex leaves the shell.
        if (shell_) {
            double highest = 0.0;
            for (const SurfacePoint& sp : *out) highest = std::max(highest, sp.height);
            if (highest > surface_.shell_height)
                for (SurfacePoint& sp : *out) sp.height *= surface_.shell_height / highest;
        }
        return true;
    }

    Mesh embed_element(const std::vector<SurfacePoint>& anchors, const std::vector<Tri>& faces) const {
        Mesh m;
        m.faces = faces;
        m.vertices.reserve(anchors.size());
        for (const SurfacePoint& sp : anchors) m.vertices.push_back(embed(sp));
        return m;
    }

    /// What the map does to the area of frame mesh `m` embedded (through `anchors`) as `embedded`:
    /// the embedded area over the frame area at the scale. Where the shell was lowered the map
    /// flattens the element (by design: the base leaves no room), and its area shrinks with its
    /// height; widening it for that made it larger across than its neighbours. The area is then
    /// taken with the lowering undone: a vertex over a lowered spot is put at its texture height
    /// along the base's normal from its foot. (Unchanged where the shell keeps its full height. The
    /// normal, not the vertex's offset from its foot scaled back up: the optimisation moves offset
    /// corners sideways, and where the shell is nearly flat that offset is mostly sideways.)
    double size_ratio(const Mesh& m, const std::vector<SurfacePoint>& anchors, const Mesh& embedded, double local) const {
        const double at_scale = std::max(mesh_area(m) * scale_ * scale_ * local * local, 1e-300);
        if (!shell_) return mesh_area(embedded) / at_scale;
        Mesh upright = embedded;
        bool lowered = false;
        for (std::size_t v = 0; v < anchors.size(); ++v) {
            const SurfacePoint& sp = anchors[v];
            if (shell_ratio(sp) > 1.0 - 1e-9) continue;
            lowered = true;
            const Tri& t = base_.mesh.faces[static_cast<std::size_t>(sp.face)];
            Vec3 n = Vec3::Zero();
            for (int k = 0; k < 3; ++k) n += sp.bary[k] * base_.normal[static_cast<std::size_t>(t[k])];
            if (!(n.norm() > 0)) continue;
            upright.vertices[v] = embed({sp.face, sp.bary, 0.0}) + sp.height * n.normalized();
        }
        return mesh_area(lowered ? upright : embedded) / at_scale;
    }

    /// Embeds frame mesh `m` (to_surface, embed_element). A new element (`fresh`) goes onto the
    /// surface at its swatch element's size: where the patch's map scales area, it is rescaled about
    /// its centre in the frame, once (see apply). An element of a lattice (keeps_lattice) only
    /// beyond kLatticeSizeDrift: its patch's frame was scaled for its size (fit_lattice_scale).
    bool embed_sized(const Mesh& m, int source, bool fresh, const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs,
                     double local, const Reach* reach, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize = nullptr,
                     bool* torn_seen = nullptr) const {
        if (resize) *resize = 1.0;
        if (!to_surface(m, flat, locator, hs, anchors, reach)) return false;
        *embedded = embed_element(*anchors, m.faces);
        if (!fresh || source < 0 || height_scale_ > 0) return !torn(*embedded, source, local, torn_seen);
        // What the map did to this element's area (not what deformation did: that was the kernel's
        // choice, bounded there).
        const double ratio = size_ratio(m, *anchors, *embedded, local);
        const double drift = keeps_lattice(source) ? kLatticeSizeDrift : kMaxSizeDrift;
        if (ratio < drift && ratio > 1.0 / drift) return !torn(*embedded, source, local, torn_seen);
        const double f = 1.0 / std::sqrt(ratio);
        const Mesh fixed = resized_in_frame(m, f);
        std::vector<SurfacePoint> a2;
        if (!to_surface(fixed, flat, locator, hs, &a2)) return !torn(*embedded, source, local, torn_seen);
        *anchors = std::move(a2);
        *embedded = embed_element(*anchors, m.faces);
        if (resize) *resize = f;
        return !torn(*embedded, source, local, torn_seen);
    }

    /// Beyond the paper: an element whose embedding pulled a face out to more than kTornFace times
    /// the swatch's largest face (at the run's scale and the field's local scale) was torn by the
    /// map, a face spanned across a crease or joining parts that the map puts apart; it does not go
    /// in there (embed_sized fails). Threads and strands are cut where they tear instead
    /// (stretched_faces), and a run with --height stretches every element in its thickness.
    /// With `seen`, a torn element sets it instead of being counted (mend_slot counts it once the
    /// pose is reached in order).
    bool torn(const Mesh& embedded, int source, double local, bool* seen = nullptr) const {
        if (source < 0 || height_scale_ > 0 || quilt::is_elongated(sw_.elements[static_cast<std::size_t>(source)]) ||
            quilt::is_strand_source(sw_, source))
            return false;
        const double limit = kTornFace * largest_face_ * scale_ * scale_ * local * local;
        for (std::size_t f = 0; f < embedded.faces.size(); ++f)
            if (face_area(embedded, f) > limit) {
                if (seen)
                    *seen = true;
                else
                    ++torn_tries_;  // the report's elements_torn (embed_sized runs in parallel in apply)
                return true;
            }
        return false;
    }

    /// An output element near a patch (on one of its faces) in the patch's frame: whole, or the
    /// faces whose corners lie on the patch.
    struct FrameElement {
        int id = -1;
        Mesh mesh;
        bool whole = false;
    };
    /// Ids of the output elements on the patch's faces, ascending.
    std::vector<int> near_elements(const quilt::FlatPatch& flat) const {
        std::vector<int> near;
        for (int f : flat.faces)
            for (int id : elems_on_face_[static_cast<std::size_t>(f)]) near.push_back(id);
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
        return near;
    }
    std::vector<FrameElement> frame_elements(const quilt::FlatPatch& flat, double hs) const {
        const std::vector<int> near = near_elements(flat);
        std::vector<FrameElement> out;
        for (int id : near) {
            const SurfElement& e = elems_[static_cast<std::size_t>(id)];
            std::vector<Vec3> at(e.anchors.size(), Vec3::Zero());
            std::vector<char> ok(e.anchors.size(), 0);
            for (std::size_t v = 0; v < e.anchors.size(); ++v) ok[v] = map_to_frame(flat, hs, e.anchors[v], &at[v]);
            FrameElement fe{id, mapped_part(at, e.faces, ok), std::find(ok.begin(), ok.end(), 0) == ok.end()};
            if (!fe.mesh.faces.empty()) out.push_back(std::move(fe));
        }
        return out;
    }

    /// Beyond the paper: after the bald spots, the stones of a paving that stand wholly on the patch
    /// with their centre on its footprint grow into joints wider than the swatch's, as the planar
    /// stage closes its joints (quilt/fill.h: grow_into_joints): in the frame, then embedded as they
    /// are, within kMaxGrowth of their swatch element's area on the surface too, colliding with
    /// nothing, not folding and keeping the swatch's clearance. With `gaps`, after the last patch
    /// (mend_joints), they grow radially into the holes where several stones meet instead
    /// (quilt::grow_into_gaps).
    void close_joints_patch(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, double fx0, double fy0,
                            double fx1, double fy1, bool gaps = false) {
        if (!joints_.paving) return;
        const double near = std::max(joints_.limit, gaps ? joints_.reach : 0.0);
        std::vector<FrameElement> in = frame_elements(flat, hs);
        std::vector<std::vector<Vec2>> hulls;
        std::vector<Box3> boxes;
        for (const FrameElement& fe : in) {
            hulls.push_back(quilt::xy_hull(fe.mesh));
            boxes.push_back(bounding_box(fe.mesh));
        }
        for (std::size_t k = 0; k < in.size(); ++k) {
            const SurfElement& e = elems_[static_cast<std::size_t>(in[k].id)];
            const int source = e.source;
            if (!in[k].whole || !quilt::is_blob_source(sw_, source)) continue;
            const Vec3 mid = 0.5 * (boxes[k].min + boxes[k].max);
            if (mid.x() < fx0 || mid.y() < fy0 || mid.x() >= fx1 || mid.y() >= fy1) continue;
            std::vector<std::vector<Vec2>> around;
            std::vector<const Mesh*> standing;
            for (std::size_t j = 0; j < in.size(); ++j) {
                if (j == k || !boxes[k].overlaps(boxes[j], near)) continue;
                around.push_back(hulls[j]);
                standing.push_back(&in[j].mesh);
            }
            const double source_area = mesh_area(sw_.elements[static_cast<std::size_t>(source)]);
            const double want = source_area * scale_ * scale_ * local * local;
            std::vector<SurfacePoint> anchors;
            Mesh embedded, grown;
            const int collider_id = e.collider_id;
            auto accept = [&](const Mesh& g) {
                anchors.clear();
                if (!to_surface(g, flat, locator, hs, &anchors)) return false;
                embedded = embed_element(anchors, g.faces);
                return mesh_area(embedded) <= quilt::kMaxGrowth * want && !collider_.collides(embedded, {collider_id}) &&
                       count_self_intersections(embedded, 1) == 0 && keeps_clearance(g, source, standing);
            };
            if (!(gaps ? quilt::grow_into_gaps(in[k].mesh, around, joints_, source_area, accept, &grown)
                       : quilt::grow_into_joints(in[k].mesh, around, joints_, source_area, accept, &grown)))
                continue;
            remove_element(in[k].id);
            add_element(std::move(anchors), grown.faces, std::move(embedded), source);
            hulls[k] = quilt::xy_hull(grown);
            boxes[k] = bounding_box(grown);
            in[k].mesh = std::move(grown);
            ++report_.joints_closed;
            if (gaps) ++surface_.gaps_closed;
        }
    }

    /// The swatch's threads by the axis they run along (thread_sets_). A direction with fewer than
    /// two threads, or threads closer than their width, has no lattice to fill (left empty).
    void prepare_thread_sets() {
        std::array<std::vector<double>, 2> cross, widths;
        for (std::size_t s = 0; s < sw_.elements.size(); ++s) {
            const Mesh& e = sw_.elements[s];
            if (!quilt::is_elongated(e)) continue;
            const Box3 box = bounding_box(e);
            const Vec3 size = box.size();
            const int along = size.x() >= size.y() ? 0 : 1;
            thread_sets_[static_cast<std::size_t>(along)].ids.push_back(static_cast<int>(s));
            cross[static_cast<std::size_t>(along)].push_back(0.5 * (box.min[1 - along] + box.max[1 - along]));
            widths[static_cast<std::size_t>(along)].push_back(size[1 - along]);
        }
        auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        for (std::size_t a = 0; a < 2; ++a) {
            ThreadSet& ts = thread_sets_[a];
            if (ts.ids.size() < 2) {
                ts.ids.clear();
                continue;
            }
            std::vector<double> c = cross[a], gaps;
            std::sort(c.begin(), c.end());
            for (std::size_t k = 1; k < c.size(); ++k) gaps.push_back(c[k] - c[k - 1]);
            ts.spacing = median(gaps);
            ts.width = median(widths[a]);
            if (!(ts.spacing > ts.width)) ts.ids.clear();
        }
    }

    /// The axis frame mesh `m` runs along: 0 (x) or 1 (y) by its vertices' principal direction, -1
    /// when their spread along it is within 1.5 times that across it (a stub of a thread).
    static int run_direction(const Mesh& m) {
        const XyPrincipal p = xy_principal(m, [](const Vec3&) { return true; });
        if (p.count == 0 || p.major < 2.25 * p.minor) return -1;
        return std::fabs(std::cos(p.angle)) >= std::fabs(std::sin(p.angle)) ? 0 : 1;
    }

    /// The principal axes in xy of the vertices of `m` that `keep` takes: their count, the spreads
    /// (sums of squares) along the major and the minor axis, and the major axis's angle from +x.
    struct XyPrincipal {
        long count = 0;
        double major = 0.0, minor = 0.0, angle = 0.0;
    };
    template <class Keep>
    static XyPrincipal xy_principal(const Mesh& m, const Keep& keep) {
        XyPrincipal p;
        Vec2 mean = Vec2::Zero();
        for (const Vec3& v : m.vertices)
            if (keep(v)) {
                mean += v.head<2>();
                ++p.count;
            }
        if (p.count == 0) return p;
        mean /= static_cast<double>(p.count);
        double sxx = 0.0, syy = 0.0, sxy = 0.0;
        for (const Vec3& v : m.vertices)
            if (keep(v)) {
                const Vec2 d = v.head<2>() - mean;
                sxx += d.x() * d.x();
                syy += d.y() * d.y();
                sxy += d.x() * d.y();
            }
        const double half = 0.5 * (sxx + syy), disc = std::sqrt(std::max(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy, 0.0));
        p.major = half + disc;
        p.minor = half - disc;
        p.angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
        return p;
    }

    /// Beyond the paper: weave seams. Where the lattices of two patches meet at an angle, the new
    /// threads collide with the old ones and are cut (trim_thread); what is left is often a strip
    /// without the threads of one direction, a spacing or more wide (and through it the threads of
    /// the other direction, which a raster of all elements would count as covered). After a patch,
    /// each direction's gaps on its footprint are found on a raster of the elements running that
    /// way or neither way in the frame (run_direction): an empty disc wider than kThreadGap of the
    /// swatch's spacing is a missing thread. A swatch thread is laid across it along that
    /// direction, near the line where the crossing threads are at their tops and bottoms
    /// (knot_line), at its size on the surface, and woven through the crossing threads (quilt/trim.h:
    /// over or under each, where there is more room); of kThreadLines x kThreadShifts such tries
    /// (free_run picks those worth embedding), the one whose parts on the footprint and clear of
    /// everything (clear_pieces) are longest goes in. Threads laid in the first direction are
    /// crossing threads for the second. A gap nothing fits is left; kThreadFillTries gaps per
    /// direction at most.
    void fill_threads_patch(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, double fx0, double fy0,
                            double fx1, double fy1) {
        if (thread_sets_[0].ids.empty() && thread_sets_[1].ids.empty()) return;
        const std::vector<FrameElement> near = frame_elements(flat, hs);
        std::vector<int> runs;
        for (const FrameElement& fe : near) runs.push_back(run_direction(fe.mesh));
        Mesh patch;  // the flattened patch, for the ground raster
        for (const Vec2& q : flat.uv) patch.vertices.emplace_back(q.x(), q.y(), 0.0);
        patch.faces = flat.local;
        auto embed = [&](const Mesh& m, int source, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize) {
            return embed_sized(m, source, fresh, flat, locator, hs, local, nullptr, anchors, embedded, resize);
        };
        auto place = [&](const Mesh& m, int source, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize) {
            return embed(m, source, fresh, anchors, embedded, resize) && count_self_intersections(*embedded, 1) == 0;
        };
        auto measure = [&](const Mesh& m) {  // as embed_sized would resize m, were it no lattice element
            std::vector<SurfacePoint> anchors;
            if (!to_surface(m, flat, locator, hs, &anchors)) return 1.0;
            const double ratio = size_ratio(m, anchors, embed_element(anchors, m.faces), local);
            return ratio > 0.0 && (ratio >= kMaxSizeDrift || ratio <= 1.0 / kMaxSizeDrift) ? 1.0 / std::sqrt(ratio) : 1.0;
        };
        // Laid threads stay on the footprint: the rest of the patch is later patches' ground.
        const Box3 footprint{Vec3(fx0, fy0, 0.0), Vec3(fx1, fy1, 0.0)};
        std::array<std::deque<Mesh>, 2> laid;  // frame meshes of the threads laid here, by direction
        for (int along = 0; along < 2; ++along) {
            const ThreadSet& ts = thread_sets_[static_cast<std::size_t>(along)];
            if (ts.ids.empty()) continue;
            const double r = ts.spacing, pixel = std::max(0.25 * ts.width, min_raster_pixel());  // neighbours within a spacing bound the gaps
            quilt::Coverage cov(fx0 - r, fy0 - r, fx1 + r, fy1 + r, pixel), ground(fx0 - r, fy0 - r, fx1 + r, fy1 + r, pixel);
            ground.add(patch);
            std::vector<const Mesh*> crossing;  // the elements running the other way, and those laid that way
            std::vector<const Mesh*> covering;
            for (std::size_t k = 0; k < near.size(); ++k) {
                if (runs[k] != 1 - along) covering.push_back(&near[k].mesh);
                else crossing.push_back(&near[k].mesh);
            }
            cov.add(covering);
            for (const Mesh& m : laid[static_cast<std::size_t>(1 - along)]) crossing.push_back(&m);  // laid just now
            cov.cover_outside(ground);
            std::vector<char> tried(static_cast<std::size_t>(cov.nx()) * static_cast<std::size_t>(cov.ny()), 0);
            for (int attempt = 0; attempt < kThreadFillTries; ++attempt) {
                const std::vector<double> dist = cov.empty_distance();
                double widest = 0.0;
                int bi = -1, bj = -1;
                for (int j = 0; j < cov.ny(); ++j)
                    for (int i = 0; i < cov.nx(); ++i) {
                        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(cov.nx()) + static_cast<std::size_t>(i);
                        const Vec2 c = cov.centre(i, j);
                        if (tried[k] || dist[k] <= widest || c.x() < fx0 || c.y() < fy0 || c.x() >= fx1 || c.y() >= fy1) continue;
                        widest = dist[k];
                        bi = i;
                        bj = j;
                    }
                if (bi < 0 || widest < kThreadGap * ts.spacing) break;
                const Vec2 c = cov.centre(bi, bj);
                Vec2 line = c;
                line[1 - along] = knot_line(c, along, crossing);
                std::deque<Mesh> frames;
                // Where the threads that run this way beside the gap turn from the frame's axis (a
                // neighbouring patch's lattice), a thread along the axis meets them at an angle and
                // rarely fits: one turned to run with them is tried next.
                bool laid_here = lay_thread(line, along, 0.0, crossing, locator, footprint, embed, place, measure, &frames);
                if (!laid_here)
                    if (const double turn = parallel_angle(c, along, near, runs, ts.spacing); std::fabs(turn) >= kThreadTurnMin) {
                        laid_here = lay_thread(line, along, turn, crossing, locator, footprint, embed, place, measure, &frames);
                        if (laid_here) ++surface_.threads_turned;
                    }
                if (laid_here) {
                    for (Mesh& f : frames) {
                        cov.add(f);
                        laid[static_cast<std::size_t>(along)].push_back(std::move(f));
                    }
                    ++surface_.threads_filled;
                }
                // Tried: the disc is not tried again (it may be filled in part).
                for (int j = std::max(0, cov.row(c.y() - widest)); j <= std::min(cov.ny() - 1, cov.row(c.y() + widest)); ++j)
                    for (int i = std::max(0, cov.column(c.x() - widest)); i <= std::min(cov.nx() - 1, cov.column(c.x() + widest)); ++i)
                        if ((cov.centre(i, j) - c).norm() <= widest)
                            tried[static_cast<std::size_t>(j) * static_cast<std::size_t>(cov.nx()) + static_cast<std::size_t>(i)] = 1;
            }
        }
    }

    /// The angle (radians, within 45 degrees either way) by which the elements of `near` running
    /// along axis `along` (runs) turn from that axis within 1.5 `spacing` of `c`: their vertices' principal
    /// directions there, element by element, averaged by vertex count. 0 when none comes near.
    static double parallel_angle(const Vec2& c, int along, const std::vector<FrameElement>& near, const std::vector<int>& runs, double spacing) {
        const double r = 1.5 * spacing;
        double sum = 0.0, weight = 0.0;
        for (std::size_t k = 0; k < near.size(); ++k) {
            if (runs[k] != along) continue;
            const Box3 b = bounding_box(near[k].mesh);
            if (c.x() < b.min.x() - r || c.x() > b.max.x() + r || c.y() < b.min.y() - r || c.y() > b.max.y() + r) continue;
            const XyPrincipal p = xy_principal(near[k].mesh, [&](const Vec3& v) { return (v.head<2>() - c).norm() < r; });
            if (p.count < 8) continue;
            double a = p.angle;  // principal direction, from +x
            if (along == 1) a -= 0.5 * M_PI;
            a = std::remainder(a, M_PI);
            if (std::fabs(a) > 0.25 * M_PI) continue;
            sum += static_cast<double>(p.count) * a;
            weight += static_cast<double>(p.count);
        }
        return weight > 0.0 ? sum / weight : 0.0;
    }

    /// Where across a gap (its widest point `c`) a thread laid along axis `along` meets the
    /// `crossing` threads at their tops and bottoms, not halfway between (where it would hit them
    /// whichever way its over and under fall): of nine lines within half a spacing of c, the one
    /// along which the crossing threads' vertices within 1.5 spacings of c lie farthest from the
    /// swatch's mid height on average. c's own line when no crossing thread comes near.
    double knot_line(const Vec2& c, int along, const std::vector<const Mesh*>& crossing) const {
        const ThreadSet& ts = thread_sets_[static_cast<std::size_t>(along)];
        const double s = ts.spacing;
        const double mid = 0.5 * (sw_.box.min.z() + sw_.box.max.z());
        double best = c[1 - along], best_score = -1.0;
        // The vertices some line can count (within 5/8 spacing across, kept with room to spare for
        // rounding, and 1.5 along), in their order.
        std::vector<Vec3> near;
        for (const Mesh* m : crossing)
            for (const Vec3& v : m->vertices)
                if (std::fabs(v[1 - along] - c[1 - along]) < 0.75 * s && std::fabs(v[along] - c[along]) < 1.5 * s) near.push_back(v);
        for (int k = -4; k <= 4; ++k) {
            const double y = c[1 - along] + k * s / 8.0;
            double sum = 0.0;
            long n = 0;
            for (const Vec3& v : near)
                if (std::fabs(v[1 - along] - y) < s / 8.0) {
                    sum += std::fabs(v.z() - mid);
                    ++n;
                }
            if (n > 0 && sum / static_cast<double>(n) > best_score) {
                best_score = sum / static_cast<double>(n);
                best = y;
            }
        }
        return best;
    }

    /// How long a stretch of thread `m` (a frame mesh running along axis `along`, `width` wide)
    /// passes the `crossing` threads without meeting them in the frame, at most: on a grid of cells a
    /// quarter width square over its centre line's width, a cell is blocked where the heights of
    /// `m`'s vertices in it overlap those of the crossing threads' vertices in it (a crossing at the
    /// wrong height); a stretch is blocked where any cell across it is. A quick bound: the surface,
    /// not the frame, decides (lay_thread).
    double free_run(const Mesh& m, int along, const std::vector<const Mesh*>& crossing, double width) const {
        const Box3 box = bounding_box(m);
        const double cell = 0.25 * width;
        const double t0 = box.min[along], u0 = 0.5 * (box.min[1 - along] + box.max[1 - along]) - 0.5 * width;
        const long n = static_cast<long>(std::ceil((box.max[along] - t0) / cell)) + 1, across = 4;
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> lo(static_cast<std::size_t>(n * across), inf), hi(lo.size(), -inf), cross_lo(lo.size(), inf), cross_hi(lo.size(), -inf);
        auto index = [&](const Vec3& v) {
            const auto i = static_cast<long>(std::floor((v[along] - t0) / cell)), j = static_cast<long>(std::floor((v[1 - along] - u0) / cell));
            return i < 0 || i >= n || j < 0 || j >= across ? -1L : i * across + j;
        };
        for (const Vec3& v : m.vertices)
            if (const long k = index(v); k >= 0) {
                lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], v.z());
                hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], v.z());
            }
        for (const Mesh* o : crossing)
            for (const Vec3& v : o->vertices)
                if (const long k = index(v); k >= 0) {
                    cross_lo[static_cast<std::size_t>(k)] = std::min(cross_lo[static_cast<std::size_t>(k)], v.z());
                    cross_hi[static_cast<std::size_t>(k)] = std::max(cross_hi[static_cast<std::size_t>(k)], v.z());
                }
        double longest = 0.0, run = 0.0;
        for (long i = 0; i < n; ++i) {
            bool blocked = false;
            for (long j = 0; j < across; ++j) {
                const auto k = static_cast<std::size_t>(i * across + j);
                blocked = blocked || (lo[k] <= cross_hi[k] && cross_lo[k] <= hi[k]);
            }
            run = blocked ? 0.0 : run + cell;
            longest = std::max(longest, run);
        }
        return longest;
    }

    /// Lays a swatch thread running along axis `along`, turned by `turn` radians about frame point
    /// `c`, through c (see fill_threads_patch); true when any of it went in (frame meshes, in the
    /// frame, added to `frames`). `frame_crossing` are the threads it is woven through.
    /// `frame_embed` puts a frame mesh on the surface (embed_sized), `frame_place` also refuses one
    /// that folds, `frame_measure` gives the scale in the frame that a frame mesh needs for its size
    /// on the surface.
    template <class Embed, class Place, class Measure>
    bool lay_thread(const Vec2& c, int along, double turn, const std::vector<const Mesh*>& frame_crossing, const quilt::PatchLocator& locator,
                    const Box3& footprint, const Embed& frame_embed, const Place& frame_place, const Measure& frame_measure,
                    std::deque<Mesh>* frames) {
        const ThreadSet& ts = thread_sets_[static_cast<std::size_t>(along)];
        const int source = ts.ids[ts.ids.size() / 2];
        const Mesh& src = sw_.elements[static_cast<std::size_t>(source)];
        const Box3 box = bounding_box(src);
        // A thread turned by `turn` about c is laid in a turned copy of the frame, where it runs
        // along the axis: the crossing threads near c are turned back into it, and what goes onto
        // the surface is turned forward first.
        const double ct = std::cos(turn), st = std::sin(turn);
        auto turned = [&](Mesh m, double sign) {
            if (turn == 0.0) return m;
            for (Vec3& v : m.vertices) {
                const Vec2 d = v.head<2>() - c;
                v = Vec3(c.x() + ct * d.x() - sign * st * d.y(), c.y() + sign * st * d.x() + ct * d.y(), v.z());
            }
            return m;
        };
        std::vector<Mesh> turned_crossing;
        std::vector<const Mesh*> crossing;
        if (turn == 0.0) crossing = frame_crossing;
        else {
            const double reach = std::max(box.size().x(), box.size().y()) + 4.0 * ts.spacing;
            for (const Mesh* m : frame_crossing) {
                const Box3 b = bounding_box(*m);
                if (c.x() < b.min.x() - reach || c.x() > b.max.x() + reach || c.y() < b.min.y() - reach || c.y() > b.max.y() + reach) continue;
                turned_crossing.push_back(turned(*m, -1.0));
            }
            for (const Mesh& m : turned_crossing) crossing.push_back(&m);
        }
        auto embed = [&](const Mesh& m, int of, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize) {
            return frame_embed(turned(m, 1.0), of, fresh, anchors, embedded, resize);
        };
        auto place = [&](const Mesh& m, int of, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize) {
            return frame_place(turned(m, 1.0), of, fresh, anchors, embedded, resize);
        };
        auto measure = [&](const Mesh& m) { return frame_measure(turned(m, 1.0)); };
        std::vector<PieceFit> best;
        double best_length = 0.0;
        // The swatch thread through c, shifted k / kThreadShifts of two spacings along itself and
        // `du` across.
        auto shift_of = [&](int k, double du) {
            Vec3 shift = Vec3::Zero();
            shift[along] = c[along] - 0.5 * (box.min[along] + box.max[along]) + 2.0 * k * ts.spacing / kThreadShifts;
            shift[1 - along] = c[1 - along] + du - 0.5 * (box.min[1 - along] + box.max[1 - along]);
            return shift;
        };
        auto shifted = [&](int k, double du) {
            const Vec3 shift = shift_of(k, du);
            Mesh m = src;
            for (Vec3& v : m.vertices) v += shift;
            return m;
        };
        // The part of `m` on the patch and the footprint; `kept` its faces in m.
        auto on_footprint = [&](const Mesh& m, std::vector<std::size_t>* kept) {
            std::vector<char> on(m.vertices.size(), 0);
            for (std::size_t v = 0; v < m.vertices.size(); ++v) {
                const Vec2 d = m.vertices[v].head<2>() - c;
                const Vec2 p = turn == 0.0 ? Vec2(m.vertices[v].head<2>()) : Vec2(c.x() + ct * d.x() - st * d.y(), c.y() + st * d.x() + ct * d.y());
                on[v] = static_cast<char>(p.x() >= footprint.min.x() && p.y() >= footprint.min.y() && p.x() <= footprint.max.x() &&
                                          p.y() <= footprint.max.y() && locator.locate(p, 0.0).inside);
            }
            for (std::size_t f = 0; f < m.faces.size(); ++f)
                if (on[static_cast<std::size_t>(m.faces[f][0])] && on[static_cast<std::size_t>(m.faces[f][1])] && on[static_cast<std::size_t>(m.faces[f][2])])
                    kept->push_back(f);
            return mapped_part(m.vertices, m.faces, on);
        };
        // The thread's size on the surface (embed_sized): its part through c, embedded as a new
        // element, gives the scale in the frame; every try is scaled by it about c before it is
        // woven through the crossing threads (which are where they are on the surface).
        double resize = 1.0;
        {
            std::vector<std::size_t> kept;
            const Mesh part = on_footprint(shifted(0, 0.0), &kept);
            if (!part.faces.empty()) resize = measure(part);
        }
        // The thread's width in the frame: where the map magnifies (a small dome such as spot's horns,
        // resize < 1) the thread is narrower there, and so are the runs it needs.
        const double width = resize * ts.width;
        // The tries are independent (everything they call is const): they run in parallel, and
        // are then taken in their serial order, so the outcome does not depend on the threads.
        std::vector<std::pair<double, Mesh>> all(static_cast<std::size_t>(kThreadLines * kThreadShifts));  // frame free run, thread
        // woven and free_run read only the crossing threads' vertices within a cell or two of the
        // try's box, and only their least and greatest heights per cell: the vertices within two
        // widths of the tries' boxes are gathered once, instead of all the threads read per try.
        Mesh near_crossing;
        {
            Box3 reach;  // the tries' boxes: the extreme shifts of the thread's box, scaled about c
            const double du = (kThreadLines / 2) * ts.spacing / 8.0;
            for (int k : {0, kThreadShifts - 1})
                for (double across : {-du, du})
                    for (const Vec3& corner : {box.min, box.max}) {
                        const Vec3 v = corner + shift_of(k, across);
                        reach.extend(Vec3(c.x() + resize * (v.x() - c.x()), c.y() + resize * (v.y() - c.y()), v.z()));
                    }
            const Vec3 margin(2.0 * width, 2.0 * width, 0.0);
            const Vec3 lo = reach.min - margin, hi = reach.max + margin;
            for (const Mesh* o : crossing)
                for (const Vec3& v : o->vertices)
                    if (v.x() >= lo.x() && v.x() <= hi.x() && v.y() >= lo.y() && v.y() <= hi.y()) near_crossing.vertices.push_back(v);
        }
        const std::vector<const Mesh*> gathered{&near_crossing};
        const std::vector<const Mesh*>& read = std::isfinite(width) && width > 0.0 ? gathered : crossing;
        tbb::parallel_for(std::size_t{0}, all.size(), [&](std::size_t t) {
            const int line = static_cast<int>(t) / kThreadShifts, k = static_cast<int>(t) % kThreadShifts;
            Mesh m = shifted(k, (line - kThreadLines / 2) * ts.spacing / 8.0);
            for (Vec3& v : m.vertices) v = Vec3(c.x() + resize * (v.x() - c.x()), c.y() + resize * (v.y() - c.y()), v.z());
            Mesh w = quilt::woven(m, along, read, width, sw_.box.min.z(), sw_.box.max.z());
            all[t] = {free_run(w, along, read, width), std::move(w)};
        });
        std::vector<std::pair<double, Mesh>> tries;
        for (auto& t : all)
            if (t.first >= kThreadFreeRun * kTrimMinLength * width) tries.push_back(std::move(t));
        // Embedding and testing a try costs more than all else: only the kThreadShiftsEmbedded
        // with the longest free run in the frame are.
        std::stable_sort(tries.begin(), tries.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        if (tries.size() > kThreadShiftsEmbedded) tries.resize(kThreadShiftsEmbedded);
        // Each try is embedded and tested on its own (in parallel, as above); the first longest wins.
        std::vector<std::vector<PieceFit>> fits(tries.size());
        std::vector<double> lengths(tries.size(), 0.0);
        tbb::parallel_for(std::size_t{0}, tries.size(), [&](std::size_t t) {
            const Mesh& m = tries[t].second;
            // Flagged: faces off the patch or the footprint, or that collide or fold where the
            // part on both lies on the surface.
            std::vector<std::size_t> kept;
            const Mesh part = on_footprint(m, &kept);
            std::vector<char> bad(m.faces.size(), 1);
            std::vector<SurfacePoint> anchors;
            Mesh embedded;
            if (part.faces.empty() || !embed(part, source, false, &anchors, &embedded, nullptr)) return;
            const double margin = kTrimMargin * width;
            // Most tries meet crossing threads all along: no piece is long enough. The first face
            // found to meet each element in each stretch of a quarter of the length needed tells
            // most of them (first_colliding_faces, at about the cost of `colliding`); a flag more
            // only shortens the free spans, so a try that fails on these fails on all its hits.
            std::vector<int> stretch(part.faces.size());
            for (std::size_t f = 0; f < part.faces.size(); ++f) {
                double along_at = 0.0;
                for (int k = 0; k < 3; ++k) along_at += part.vertices[static_cast<std::size_t>(part.faces[f][k])][along];
                stretch[f] = static_cast<int>(std::floor((along_at / 3.0 - c[along]) / (0.25 * kTrimMinLength * width)));
            }
            const std::vector<char> first = collider_.first_colliding_faces(embedded, stretch);
            for (std::size_t f = 0; f < kept.size(); ++f) bad[kept[f]] = first[f];
            if (quilt::longest_free_span(m, bad, margin) < kTrimMinLength * width) return;
            const std::vector<char> hit = collider_.colliding_faces(embedded);
            for (std::size_t f = 0; f < kept.size(); ++f) bad[kept[f]] = hit[f];
            // Then on all of them (checked before the dearer test for folds, which only adds flags).
            if (quilt::longest_free_span(m, bad, margin) < kTrimMinLength * width) return;
            if (count_self_intersections(embedded, 1) > 0) {
                const std::vector<char> folded = self_intersecting_faces(embedded);
                for (std::size_t f = 0; f < kept.size(); ++f) bad[kept[f]] = static_cast<char>(bad[kept[f]] | folded[f]);
            }
            if (const std::vector<char> torn = stretched_faces(part, embedded); !torn.empty())
                for (std::size_t f = 0; f < kept.size() && f < torn.size(); ++f) bad[kept[f]] = static_cast<char>(bad[kept[f]] | torn[f]);
            fits[t] = clear_pieces(m, source, bad, place);
            for (const PieceFit& f : fits[t]) lengths[t] += bounding_box(f.frame).size()[along];
        });
        for (std::size_t t = 0; t < tries.size(); ++t)
            if (lengths[t] > best_length) {
                best_length = lengths[t];
                best = std::move(fits[t]);
            }
        if (best.empty()) return false;
        for (PieceFit& f : best) f.frame = turned(std::move(f.frame), 1.0);
        add_pieces(std::move(best), source, frames);
        return true;
    }

    /// The ground standing element `fe` claims in its patch's frame, as fill_patch judges density
    /// and spots: a whole blob's frame copy widened in xy about its middle by the square root of
    /// the shell's widening under it (widening_, averaged over its vertices' faces, within
    /// kClaimWidening). A blob is embedded at its swatch size on the shell's middle surface
    /// (embed_sized); round a thin part that surface is wider than the base, so the blob covers less
    /// of the base and its frame, and fills judged by the frame copy alone made up the difference:
    /// pebbles per base area up to 1.23 times the swatch's on thin parts (the bunny's ear, the
    /// armadillo's hands, by count), 0.88-0.95 on their middle surface. Judged by the claim, fills
    /// keep the swatch's density per base area as the patches' elements do (docs/surface.md, step
    /// 8, "Fills counted on the base"). Other elements (rings, strands; cut or partly off the
    /// patch) claim their frame copy.
    Mesh claimed_ground(const FrameElement& fe) const {
        const SurfElement& e = elems_[static_cast<std::size_t>(fe.id)];
        if (!fe.whole || e.source < 0 || !quilt::is_blob_source(sw_, e.source) || e.anchors.empty()) return fe.mesh;
        double w = 0.0;
        for (const SurfacePoint& sp : e.anchors) w += widening_[static_cast<std::size_t>(sp.face)];
        const double g = std::sqrt(std::clamp(w / static_cast<double>(e.anchors.size()), 1.0 / kClaimWidening, kClaimWidening));
        Mesh claim = fe.mesh;
        const Box3 b = bounding_box(claim);
        const Vec3 c = 0.5 * (b.min + b.max);
        for (Vec3& v : claim.vertices) v = Vec3(c.x() + g * (v.x() - c.x()), c.y() + g * (v.y() - c.y()), v.z());
        return claim;
    }

    /// Beyond the paper: bald spots of the patch's footprint (where its new elements collided or
    /// lost their merges) are filled with blobs right after the patch, in its frame, as the planar
    /// stage fills its output (quilt/fill.h: fill_spots): every element near the patch is mapped into
    /// the frame (whole, or by the faces whose corners lie on the patch), spots are centred on the
    /// footprint and on the flattened patch, and the ground around a spot is judged on the patch only.
    /// A blob goes in when it lies wholly on the patch, its embedding collides with nothing and does
    /// not fold.
    void fill_patch(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, double fx0, double fy0,
                    double fx1, double fy1) {
        if (fill_.shapes.empty()) return;
        const double r = fill_.reach;
        quilt::Coverage cov(fx0 - r, fy0 - r, fx1 + r, fy1 + r, fill_.pixel, fill_.projected), ground(fx0 - r, fy0 - r, fx1 + r, fy1 + r, fill_.pixel);
        Mesh patch;  // the flattened patch, for the ground raster
        for (const Vec2& q : flat.uv) patch.vertices.emplace_back(q.x(), q.y(), 0.0);
        patch.faces = flat.local;
        ground.add(patch);
        std::vector<std::vector<Vec2>> hulls;
        std::vector<Box3> boxes;
        std::deque<Mesh> standing;  // frame meshes, for the clearance of fills (stable addresses)
        std::vector<const Mesh*> standing_ptrs;
        // `claims`: the ground the element claims, in the coverage that judges density and spots
        // (claimed_ground); the element itself is what fills keep clear of.
        auto stand = [&](const Mesh& m, const Mesh& claims) {
            if (m.faces.empty()) return;
            standing.push_back(m);
            standing_ptrs.push_back(&standing.back());
            cov.add(claims);
            hulls.push_back(quilt::xy_hull(m));
            boxes.push_back(bounding_box(m));
        };
        for (const FrameElement& fe : frame_elements(flat, hs)) stand(fe.mesh, claimed_ground(fe));
        cov.cover_outside(ground);  // distances end at the patch's border
        std::vector<SurfacePoint> anchors;
        Mesh embedded;
        // The whole element on the surface (fill_spots' `fits`).
        double whole_resize = 0.0;  // the last whole_fits' embedding's resize (0: it failed)
        auto whole_fits = [&](const Mesh& m, int source) {
            double resize = 1.0;
            whole_resize = 0.0;
            if (!embed_sized(m, source, true, flat, locator, hs, local, nullptr, &anchors, &embedded, &resize)) return false;
            whole_resize = resize;
            // Resized for the surface, it keeps the clearance at that scale (see apply).
            if (resize != 1.0 && !keeps_clearance(resized_in_frame(m, resize), source, standing_ptrs, nullptr, resize)) return false;
            // A layered swatch's shape, and a strand, come unsqueezed (FillSetup::layered,
            // Shape::whole): they keep the clearance themselves.
            if (resize == 1.0 && (fill_.layered || quilt::is_strand_source(sw_, source)) && !keeps_clearance(m, source, standing_ptrs)) return false;
            // On the surface it keeps kFillMinArea of its swatch element's area (where the map
            // shrinks ground that the rescaled element cannot fit on, embed_sized keeps it as is).
            const double want = mesh_area(sw_.elements[static_cast<std::size_t>(source)]) * scale_ * scale_ * local * local;
            const double floor = fill_.area_floor * scale_ * scale_ * local * local;
            if (mesh_area(embedded) < std::max(kFillMinArea * want, floor) || mesh_area(embedded) > kMaxElementSize * kMaxElementSize * want) return false;
            return !collider_.collides(embedded) && count_self_intersections(embedded, 1) == 0;
        };
        auto place_piece = [&](const Mesh& m, int source, bool fresh, std::vector<SurfacePoint>* a, Mesh* e, double* resize) {
            return embed_sized(m, source, fresh, flat, locator, hs, local, nullptr, a, e, resize);
        };
        std::vector<Mesh> cut_tries;  // strands `fits` cut to their pieces, told apart in `add`
        report_.bald_spots_filled += quilt::fill_spots(
            cov, fill_,
            [&](const Vec2& c) {
                return c.x() >= fx0 && c.y() >= fy0 && c.x() < fx1 && c.y() < fy1 && ground.covered(ground.column(c.x()), ground.row(c.y()));
            },
            [&](const Vec2& c, double radius) {
                // Judged on the patch only: a window mostly off it says little (and, read as sparse,
                // filled pebbles on the armadillo's small patches up to 1.28 of the swatch's density).
                if (ground.covered_share(c, radius) < kFillOnPatch) return std::numeric_limits<double>::infinity();
                return cov.area_density(c, radius, &ground);
            },
            [&](const Vec2& c, double radius) {
                std::vector<std::vector<Vec2>> out;
                Box3 at;
                at.extend(Vec3(c.x(), c.y(), 0.0));
                for (std::size_t k = 0; k < hulls.size(); ++k)
                    if (at.overlaps(Box3{Vec3(boxes[k].min.x(), boxes[k].min.y(), 0.0), Vec3(boxes[k].max.x(), boxes[k].max.y(), 0.0)}, radius))
                        out.push_back(hulls[k]);
                return out;
            },
            [&](Mesh& m, int source) {
                if (whole_fits(m, source)) return true;
                // A strand that does not fit whole may go in as its pieces that do (cut where it
                // collides, folds or comes closer than the clearance), if they keep kFillPieceShare
                // of it.
                if (!quilt::is_strand_source(sw_, source) || !(sw_.near_gap > 0.0)) return false;
                // The whole strand as it lies on the surface at its size: whole_fits' embedding
                // when it was not resized, else embedded again without resizing.
                std::vector<SurfacePoint> a;
                Mesh e;
                if (whole_resize == 1.0) e = embedded;
                else if (!embed_sized(m, source, false, flat, locator, hs, local, nullptr, &a, &e)) return false;
                std::vector<char> bad = collider_.colliding_faces(e);
                if (count_self_intersections(e, 1) > 0) {
                    const std::vector<char> folded = self_intersecting_faces(e);
                    for (std::size_t f = 0; f < folded.size() && f < bad.size(); ++f) bad[f] = static_cast<char>(bad[f] | folded[f]);
                }
                // Only the standing elements near it can flag its faces.
                std::vector<const Mesh*> near;
                const Box3 mb = bounding_box(m);
                for (std::size_t k = 0; k < boxes.size(); ++k)
                    if (mb.overlaps(boxes[k], sw_.near_gap)) near.push_back(standing_ptrs[k]);
                const std::vector<PieceFit> fits = clear_strand_pieces(m, source, std::move(bad), near, sw_.near_gap, place_piece, quilt::kFillPieceShare);
                double kept = 0.0;
                for (const PieceFit& fit : fits) kept += mesh_area(fit.frame);
                if (fits.empty() || kept < quilt::kFillPieceShare * mesh_area(m)) return false;
                std::vector<Mesh> frames;
                for (const PieceFit& fit : fits) frames.push_back(fit.frame);
                m = quilt::join_meshes(frames);
                cut_tries.push_back(m);
                return true;
            },
            [&](const Mesh& m, int source) {
                if (std::any_of(cut_tries.begin(), cut_tries.end(), [&](const Mesh& c) { return c.vertices == m.vertices; })) {
                    cut_tries.clear();
                    for (const Mesh& piece : quilt::split_components(m)) {
                        if (!embed_sized(piece, source, false, flat, locator, hs, local, nullptr, &anchors, &embedded)) continue;
                        add_element(std::move(anchors), piece.faces, std::move(embedded), source, true);
                        stand(piece, piece);
                        ++report_.strand_pieces;
                    }
                    return;
                }
                // Embedded again: the last `fits` may have been a larger shape that did not fit.
                embed_sized(m, source, true, flat, locator, hs, local, nullptr, &anchors, &embedded);
                add_element(std::move(anchors), m.faces, std::move(embedded), source);
                stand(m, m);
            });
    }

    /// How many other rings each standing ring interlocks with (|linking number of the centre lines|
    /// = 1, core/links.h), by element id; only pairs whose boxes overlap are tested.
    std::map<int, int> ring_links() const {
        std::vector<int> ids;
        std::vector<Box3> boxes;
        double cell = 0.0;
        for (std::size_t id = 0; id < elems_.size(); ++id) {
            const SurfElement& e = elems_[id];
            if (!e.alive || !is_ring_source(e.source)) continue;
            ids.push_back(static_cast<int>(id));
            boxes.push_back(bounding_box(e.embedded));
            cell = std::max(cell, boxes.back().size().maxCoeff());
        }
        std::map<int, int> links;
        if (ids.empty() || !(cell > 0.0)) return links;
        std::map<std::array<long, 3>, std::vector<std::size_t>> grid;
        auto key = [&](const Box3& b) {
            const Vec3 c = 0.5 * (b.min + b.max) / cell;
            return std::array<long, 3>{std::lround(std::floor(c.x())), std::lround(std::floor(c.y())), std::lround(std::floor(c.z()))};
        };
        for (std::size_t i = 0; i < ids.size(); ++i) grid[key(boxes[i])].push_back(i);
        auto line = [&](std::size_t i) -> const std::vector<Vec3>& { return elems_[static_cast<std::size_t>(ids[i])].centerline; };
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const auto k = key(boxes[i]);
            for (long dx = -1; dx <= 1; ++dx)
                for (long dy = -1; dy <= 1; ++dy)
                    for (long dz = -1; dz <= 1; ++dz) {
                        const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                        if (it == grid.end()) continue;
                        for (std::size_t j : it->second) {
                            if (j <= i || !boxes[i].overlaps(boxes[j])) continue;
                            if (!links_once(line(i), line(j))) continue;
                            ++links[ids[i]];
                            ++links[ids[j]];
                        }
                    }
        }
        for (int id : ids) links.emplace(id, 0);
        return links;
    }

    /// How many of the standing rings `ids` ring `m` interlocks with, counted up to `enough`.
    int links_with(const Mesh& m, const std::vector<int>& ids, int enough) const {
        const std::vector<Vec3> line = ring_centerline(m);
        if (line.size() < 3) return 0;
        const Box3 box = bounding_box(m);
        int n = 0;
        for (int id : ids) {
            const SurfElement& other = elems_[static_cast<std::size_t>(id)];
            if (box.overlaps(bounding_box(other.embedded)) && links_once(line, other.centerline) && ++n >= enough) break;
        }
        return n;
    }

    /// ring_need_: per swatch element, the links a ring of its kind must keep in the output: a
    /// connecting ring (every ring of its kind joins at most two in the swatch, and one joins two)
    /// both, any other ring one (a ring of a 4-in-1 mail at a seam holds with one or two; asking
    /// two of every ring cost a tenth of the rings on the eight, session 11).
    void prepare_ring_need() {
        const std::size_t n = sw_.elements.size();
        ring_need_.assign(n, 1);
        if (!interlocked_) return;
        std::vector<std::vector<Vec3>> lines(n);
        std::vector<Box3> boxes(n);
        for (std::size_t s = 0; s < n; ++s)
            if (is_ring_source(static_cast<int>(s))) {
                lines[s] = ring_centerline(sw_.elements[s]);
                boxes[s] = bounding_box(sw_.elements[s]);
            }
        std::vector<int> links(n, 0);
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = a + 1; b < n && lines[a].size() >= 3; ++b)
                if (lines[b].size() >= 3 && boxes[a].overlaps(boxes[b]) && links_once(lines[a], lines[b])) {
                    ++links[a];
                    ++links[b];
                }
        std::map<int, int> most;  // per ring kind
        for (std::size_t s = 0; s < n; ++s)
            if (ring_kind_[s] >= 0) most[ring_kind_[s]] = std::max(most[ring_kind_[s]], links[s]);
        for (std::size_t s = 0; s < n; ++s)
            if (ring_kind_[s] >= 0 && most[ring_kind_[s]] == 2) ring_need_[s] = 2;
    }

    /// Do the swatch's rings interlock (chain mail), rather than lie side by side? True when at
    /// least half of them link with another ring of the swatch.
    bool swatch_rings_interlock() const {
        std::vector<std::size_t> rings;
        for (std::size_t e = 0; e < sw_.elements.size(); ++e)
            if (is_ring_source(static_cast<int>(e))) rings.push_back(e);
        std::vector<std::vector<Vec3>> lines;
        std::vector<Box3> boxes;
        for (std::size_t e : rings) {
            lines.push_back(ring_centerline(sw_.elements[e]));
            boxes.push_back(bounding_box(sw_.elements[e]));
        }
        std::size_t linked = 0;
        for (std::size_t i = 0; i < rings.size(); ++i)
            for (std::size_t j = 0; j < rings.size(); ++j) {
                if (j == i || !boxes[i].overlaps(boxes[j])) continue;
                if (links_once(lines[i], lines[j])) {
                    ++linked;
                    break;
                }
            }
        return !rings.empty() && 2 * linked >= rings.size();
    }

    /// Beyond the paper: mending the seams of ring lattices. On a doubly curved base no field is
    /// parallel, so the lattices of neighbouring patches meet at small angles, and interlocked rings
    /// that the kernel put where they collide are left out (docs/surface.md: chain mail came out at
    /// 0.6-0.8 of the swatch's density on the eight). After the last patch, each empty lattice slot
    /// next to a standing ring gets the swatch ring that the swatch has there, or past the swatch's
    /// border one of the right kind shifted there (quilt::ring_lattice; a ring from the border of
    /// its patch's swatch proposed only the slots back inside it before): the ring's pose in a
    /// local frame (a similarity fitted to its swatch element's vertices) carries each of its swatch
    /// neighbours into the frame, and a slot whose centre no element occupies takes the first of a few
    /// small turns about its centre that lies on the frame's patch, collides with nothing and does not
    /// fold. A ring so placed is where the lattice on one side of the seam has it, so it links with
    /// its neighbours there. Done last, so no patch's lattice is moved by it (a filler run after each
    /// patch put 300 rings into holes, and later patches then placed 300 fewer).
    void mend_rings() {
        std::vector<char> is_ring(sw_.elements.size(), 0);
        for (std::size_t s = 0; s < is_ring.size(); ++s) is_ring[s] = is_lattice_source(static_cast<int>(s));
        const quilt::RingLattice lattice = quilt::ring_lattice(sw_, is_ring);
        if (lattice.spacing <= 0.0) return;
        const double spacing = lattice.spacing;
        // Frames tile the surface: each mends the slots within R of its seed and marks the faces
        // there as done; the next frame starts at the first face not done. A ring mended in one
        // frame can open slots in a frame already done, so passes repeat over the faces near the
        // rings the last pass added, until one adds none (at most kMendPasses; on the eight at scale
        // 0.2 the first pass added 90 rings, the next four 32, 18, 9 and 19).
        const double R = 0.5 * std::hypot(sx_, sy_) * cell_;
        mend_failed_.clear();
        mend_failed_grid_.clear();
        hole_failed_.clear();
        hole_failed_grid_.clear();
        // Ring holes embed at most kHoleBudget tries per ring standing (chain mail on spot: 1.7;
        // a swatch whose rings rarely fit, such as a Japanese mail's connectors that must link
        // two rings, would otherwise try for minutes).
        const auto standing = static_cast<double>(
            std::count_if(elems_.begin(), elems_.end(), [&](const SurfElement& e) { return e.alive && is_lattice_source(e.source); }));
        hole_tries_ = 0;
        hole_budget_ = static_cast<long>(kHoleBudget * standing);
        hole_free_ = std::max(1000L, static_cast<long>(kHoleTriesFree * standing));
        tilt_tries_ = 0;
        tilt_free_ = std::max(1000L, static_cast<long>(kHoleTiltFree * standing));
        mend_cell_ = std::max(spacing * scale_ * *std::max_element(local_scale_.begin(), local_scale_.end()), 1e-12);
        tile_frames(R, kMendPasses, "mending", [&](const Frame& fr) { mend_frame(fr.flat, fr.local, R, lattice); });
    }

    /// Beyond the paper: weave gaps left after the last patch. A thread laid into a gap right after
    /// a patch (fill_threads_patch) must stay on that patch's footprint, so a gap across a
    /// footprint's edge gets at most a short piece, and later patches cut threads again; so after
    /// the last patch, frames tile the surface (tile_frames) and each fills the gaps on its core
    /// (the square of side 2R about its origin) as a patch fills its footprint. Where a frame's map
    /// distorts area by more than kMaxDistortion, smaller frames (kThreadMendSmall) follow.
    void mend_threads() {
        const double R = 0.5 * std::hypot(sx_, sy_) * cell_;
        std::vector<char> distorted(base_.mesh.faces.size(), 0);
        tile_frames(R, kThreadMendPasses, "thread mending", [&](const Frame& fr) {
            const quilt::PatchLocator locator(fr.flat);
            fill_threads_patch(fr.flat, locator, height_scale(fr.local), fr.local, -R, -R, R, R);
            if (quilt::area_distortion(base_.mesh, fr.flat) > kMaxDistortion)
                for (int f : fr.flat.faces) distorted[static_cast<std::size_t>(f)] = 1;
        });
        // Where a frame's map distorts area (a small dome, such as spot's horns, magnified against
        // the ground around it), a thread's piece there is stretched beyond what stretched_faces
        // lets through: smaller frames, tiling only that ground, flatten it with less distortion.
        if (std::none_of(distorted.begin(), distorted.end(), [](char d) { return d != 0; })) return;
        const double r = kThreadMendSmall * R;
        frame_cap_ = kThreadMendSmall;
        const double last = last_radius_;
        last_radius_ = 0.0;
        tile_frames(r, 1, "thread mending", [&](const Frame& fr) {
            const quilt::PatchLocator locator(fr.flat);
            fill_threads_patch(fr.flat, locator, height_scale(fr.local), fr.local, -r, -r, r, r);
        }, &distorted);
        frame_cap_ = 0.0;
        last_radius_ = last;
    }

    /// Beyond the paper: a paving's gaps left after the last patch. A stone grows into joints only in
    /// the patch whose footprint holds its centre, before the next patches have laid the stones
    /// across its frontier; and the holes where three or more stones of different patches meet have
    /// no straight side to push. So after the last patch, frames tile the surface (tile_frames) and
    /// the stones on each frame's core grow radially into such holes (close_joints_patch with
    /// `gaps`); a second pass gives the stones near those grown a second chance.
    void mend_joints() {
        if (!joints_.paving) return;
        const double R = 0.5 * std::hypot(sx_, sy_) * cell_;
        tile_frames(R, kJointMendPasses, "joint mending", [&](const Frame& fr) {
            const quilt::PatchLocator locator(fr.flat);
            close_joints_patch(fr.flat, locator, height_scale(fr.local), fr.local, -R, -R, R, R, true);
        });
    }

    /// Frames that tile the surface after the last patch (mend_rings, mend_threads): each is grown
    /// and flattened at the first face no frame has covered yet, covers the faces within `R` of its
    /// origin, and is handed to `mend` (with face_slot_ set). An element added in one frame can open
    /// room in a frame already done, so passes repeat over the faces near the elements the last pass
    /// added, until one adds none (at most `passes`). `stage` names the progress. With `only`, the
    /// first pass starts frames on the faces it flags only.
    template <class Mend>
    void tile_frames(double R, int passes, const char* stage, const Mend& mend, const std::vector<char>* only = nullptr) {
        const int shrunk = surface_.patches_shrunk;  // frames are no patches
        const std::size_t F = base_.mesh.faces.size();
        std::vector<char> pending = only ? *only : std::vector<char>(F, 1);  // faces whose frames may find new slots
        for (int pass = 0; pass < passes; ++pass) {
            const std::size_t first_new = elems_.size();
            std::vector<char> visited(F, 0);
            std::size_t todo = 0, done = 0;
            for (std::size_t f = 0; f < F; ++f) {
                visited[f] = !pending[f];
                todo += pending[f];
            }
            for (std::size_t seed = 0; seed < F; ++seed) {
                if (visited[seed]) continue;
                Frame fr;
                if (!make_frame(static_cast<int>(seed), &fr)) {
                    visited[seed] = 1;
                    continue;
                }
                const quilt::FlatPatch& flat = fr.flat;
                for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
                    const auto f = static_cast<std::size_t>(flat.faces[lf]);
                    face_slot_[f] = static_cast<int>(lf);
                    Vec2 c = Vec2::Zero();
                    for (int k = 0; k < 3; ++k) c += flat.uv[static_cast<std::size_t>(flat.local[lf][k])] / 3.0;
                    if (c.norm() <= R || f == seed) {
                        done += !visited[f];
                        visited[f] = 1;
                    }
                }
                mend(fr);
                for (int f : flat.faces) face_slot_[static_cast<std::size_t>(f)] = -1;
                opt_.reporter.report(stage, (pass + static_cast<double>(done) / static_cast<double>(std::max<std::size_t>(todo, 1))) / passes);
            }
            if (elems_.size() == first_new) break;
            // Next pass: the faces within two frame cores of an element added in this one.
            pending.assign(F, 0);
            std::vector<int> queue;
            for (std::size_t id = first_new; id < elems_.size(); ++id) {
                const SurfElement& e = elems_[id];
                if (!e.alive || e.base_faces.empty()) continue;
                const Vec3 c = area_centroid(e.embedded);
                const double reach = 2.0 * R * scale_ * local_scale_[static_cast<std::size_t>(e.base_faces.front())];
                queue.assign(e.base_faces.begin(), e.base_faces.end());
                for (int f : queue) pending[static_cast<std::size_t>(f)] = 1;
                for (std::size_t head = 0; head < queue.size(); ++head)
                    for (int g : base_.nb[static_cast<std::size_t>(queue[head])])
                        if (g >= 0 && !pending[static_cast<std::size_t>(g)] && (base_.centroid[static_cast<std::size_t>(g)] - c).norm() <= reach) {
                            pending[static_cast<std::size_t>(g)] = 1;
                            queue.push_back(g);
                        }
            }
        }
        surface_.patches_shrunk = shrunk;
    }

    /// One frame of mend_rings: slots within `R` of the frame's origin, proposed by the standing
    /// rings' poses from the swatch's ring lattice (quilt::ring_lattice).
    void mend_frame(const quilt::FlatPatch& flat, double local, double R, const quilt::RingLattice& lattice) {
        const double spacing = lattice.spacing;
        const std::vector<Vec2>& centre = lattice.centre;
        const quilt::PatchLocator locator(flat);
        const double hs = height_scale(local);
        std::vector<Pose> poses;   // rings that still have their swatch element's shape (within a tenth of the spacing)
        std::vector<Vec2> filled;  // centres of the elements in the frame (whole, or the mapped part's)
        std::vector<int> filled_id;
        for (int id : near_elements(flat)) {
            const SurfElement& e = elems_[static_cast<std::size_t>(id)];
            Vec2 sum = Vec2::Zero();
            int n = 0;
            for (const SurfacePoint& sp : e.anchors)
                if (Vec3 q; map_to_frame(flat, hs, sp, &q)) {
                    sum += q.head<2>();
                    ++n;
                }
            if (n > 0) {
                filled.push_back(sum / n);
                filled_id.push_back(id);
            }
            if (Pose pose; is_lattice_source(e.source) && element_pose(e, flat, hs, &pose) && pose.residual <= 0.1 * spacing) poses.push_back(pose);
        }
        std::vector<SurfacePoint> anchors;
        Mesh embedded;
        mend_near_ = &filled_id;  // a mended blob keeps the swatch's clearance from these (mend_slot)
        for (std::size_t k = 0; k < poses.size(); ++k) {  // grows: a mended ring mends on
            const Pose pose = poses[k];
            const double unit = spacing * std::sqrt(std::fabs(pose.A.determinant()));
            const double angle = std::atan2(pose.A(1, 0), pose.A(0, 0));
            for (const quilt::RingLattice::Neighbour& next : lattice.next[static_cast<std::size_t>(pose.source)]) {
                const int j = next.source;
                const Vec2 c = pose.A * (centre[static_cast<std::size_t>(j)] + next.shift) + pose.t;
                if (c.norm() > R) continue;
                // A slot is empty when no element's centre lies within 0.6 of the spacing (at 0.5-0.6,
                // 3 of 273 tries fitted on the eight: the neighbouring lattice's ring is there).
                if (std::any_of(filled.begin(), filled.end(), [&](const Vec2& q) { return (q - c).norm() < kMendEmpty * unit; })) continue;
                if (is_ring_source(j) && ring_crowd(filled, filled_id, c, unit, lattice, flat, local) > kRingCrowd) continue;
                // A slot tried in vain stays so: mending only adds rings. Another standing ring that
                // puts the same ring there (within a tenth of the spacing and 3 degrees), in this
                // frame or any later one, is not tried again.
                Vec3 at, dir;
                double tolerance = 0.0;
                if (!slot_on_surface(flat, locator, c, angle, unit, &at, &dir, &tolerance) || mend_failed(at, dir, tolerance)) continue;
                const std::vector<int> around = rings_near(filled, filled_id, c, kMendLinkReach * unit);  // rings the new one may link with
                bool lasting = true;
                Mesh plain;  // the slot's ring as the lattice puts it, embedded (swap_blocker)
                if (Pose placed; mend_slot(flat, locator, hs, local, pose, j, next.shift, c, around, &anchors, &embedded, &placed, &lasting, nullptr, nullptr,
                                           nullptr, 1, &plain)) {
                    filled.push_back(c);
                    filled_id.push_back(static_cast<int>(elems_.size()) - 1);
                    poses.push_back(placed);
                } else if (lasting && is_ring_source(j) && swap_blocker(flat, locator, hs, local, R, lattice, pose, j, next.shift, c, unit, plain, filled, filled_id,
                                                                        poses)) {
                    // The slot's ring went in, and another, in place of the one ring that blocked it.
                } else if (lasting) {
                    mend_failed_.push_back({at, dir});
                    mend_failed_grid_[mend_key(at)].push_back(mend_failed_.size() - 1);
                }
            }
        }
        // Holes between two lattices are filled with rings only (a blob that fits one is a bald
        // spot, fill_patch's).
        std::vector<Pose> ring_poses;
        for (const Pose& p : poses)
            if (is_ring_source(p.source)) ring_poses.push_back(p);
        mend_near_ = nullptr;
        fill_ring_holes(flat, locator, hs, local, R, lattice, ring_poses, filled, filled_id, &anchors, &embedded);
    }

    /// The ring elements among a mending frame's elements (`ids`, centres `at` in the frame) whose
    /// centres lie within `reach` of `c`.
    std::vector<int> rings_near(const std::vector<Vec2>& at, const std::vector<int>& ids, const Vec2& c, double reach) const {
        std::vector<int> near;
        for (std::size_t i = 0; i < at.size(); ++i)
            if ((at[i] - c).norm() < reach && is_ring_source(elems_[static_cast<std::size_t>(ids[i])].source)) near.push_back(ids[i]);
        return near;
    }

    /// Beyond the paper: a lattice slot blocked by rings of another lattice (session 50). Where two
    /// lattices meet off step, a ring of one stands between two slots of the other, and each of
    /// those collides with it: the seam holds one ring where the lattice has two. When ring `j`'s
    /// slot (`pose`, `shift`, centre `c` in the frame; every pose of mend_slot refused) collides, as
    /// the lattice puts it, with at most kSwapMost standing rings, those rings go if the slot's ring
    /// and more rings of the same lattice, one more than went, then go in (slots the new rings or
    /// the standing rings' poses propose, within kSwapReach spacings of a ring that went, nearest
    /// first), and every ring that linked with one that went keeps the links its kind needs;
    /// otherwise everything is put back as it stood. Each swap adds one ring (`rings_swapped`, the
    /// new rings counted among `elements_mended`).
    bool swap_blocker(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, double R,
                      const quilt::RingLattice& lattice, const Pose& pose, int j, const Vec2& shift, const Vec2& c, double unit, const Mesh& plain,
                      std::vector<Vec2>& filled, std::vector<int>& filled_id, std::vector<Pose>& poses) {
        // `plain`: the slot's ring as the lattice puts it (no turn, no shrink), embedded at its size
        // on the surface by mend_slot; empty when that pose was refused before its collision test.
        if (sw_.thinned > 0.0 || plain.faces.empty()) return false;  // a thinned mail's rings are thickened back where they stand apart
        const std::vector<int> hit = collider_.colliding(plain);
        if (hit.empty() || hit.size() > kSwapMost) return false;
        std::vector<std::size_t> slot;  // the blockers' entries in filled, ascending
        for (std::size_t i = 0; i < filled_id.size(); ++i) {
            const SurfElement& e = elems_[static_cast<std::size_t>(filled_id[i])];
            if (e.alive && std::find(hit.begin(), hit.end(), e.collider_id) != hit.end()) {
                if (!is_ring_source(e.source) || e.cut) return false;
                slot.push_back(i);
            }
        }
        if (slot.size() != hit.size()) return false;  // a blocker off the frame
        std::vector<int> blockers;
        std::vector<Vec2> gone;
        for (std::size_t i : slot) {
            blockers.push_back(filled_id[i]);
            gone.push_back(filled[i]);
        }
        auto is_blocker = [&](int id) { return std::find(blockers.begin(), blockers.end(), id) != blockers.end(); };
        // The rings near them that link with one: each must keep its links once they are gone.
        std::vector<int> linked;
        if (interlocked_)
            for (std::size_t i = 0; i < filled.size(); ++i) {
                const int id = filled_id[i];
                if (is_blocker(id) || !is_ring_source(elems_[static_cast<std::size_t>(id)].source)) continue;
                for (std::size_t b = 0; b < blockers.size(); ++b)
                    if ((filled[i] - gone[b]).norm() < 2.0 * unit && links_with(elems_[static_cast<std::size_t>(blockers[b])].embedded, {id}, 1) > 0) {
                        linked.push_back(id);
                        break;
                    }
            }
        std::vector<SurfElement> saved;
        for (int id : blockers) {
            saved.push_back(elems_[static_cast<std::size_t>(id)]);
            remove_element(id);
        }
        std::vector<Vec2> room;  // the frame's centres without the blockers, with the new rings
        std::vector<int> room_id;
        for (std::size_t i = 0; i < filled.size(); ++i)
            if (!is_blocker(filled_id[i])) {
                room.push_back(filled[i]);
                room_id.push_back(filled_id[i]);
            }
        const int mended = surface_.elements_mended;
        std::vector<int> added;
        std::vector<Pose> added_pose;
        auto undo = [&] {
            for (int id : added) remove_element(id);
            surface_.elements_mended = mended;
            for (std::size_t b = 0; b < saved.size(); ++b) {
                add_element(std::move(saved[b].anchors), saved[b].faces, std::move(saved[b].embedded), saved[b].source, saved[b].cut);
                filled_id[slot[b]] = static_cast<int>(elems_.size()) - 1;
            }
            return false;
        };
        auto place = [&](const Pose& p, int ring, const Vec2& sh, const Vec2& at) {
            const std::vector<int> around = rings_near(room, room_id, at, kMendLinkReach * unit);
            std::vector<SurfacePoint> a;
            Mesh em;
            Pose placed;
            bool lasting = true;
            if (!mend_slot(flat, locator, hs, local, p, ring, sh, at, around, &a, &em, &placed, &lasting)) return false;
            added.push_back(static_cast<int>(elems_.size()) - 1);
            added_pose.push_back(placed);
            room.push_back(at);
            room_id.push_back(added.back());
            return true;
        };
        if (!place(pose, j, shift, c)) return undo();
        // More rings of the lattice: the slots the new rings and the standing rings' poses propose
        // near where the blockers stood, nearest first; each ring put in proposes its own.
        while (added.size() <= blockers.size()) {
            std::vector<std::tuple<double, Pose, const quilt::RingLattice::Neighbour*>> slots;
            auto near_gone = [&](const Vec2& at, double reach) {
                double d = std::numeric_limits<double>::infinity();
                for (const Vec2& g : gone) d = std::min(d, (at - g).norm());
                return d <= reach * unit ? d : -1.0;
            };
            std::vector<Pose> proposers = poses;
            proposers.insert(proposers.end(), added_pose.begin(), added_pose.end());
            for (const Pose& p : proposers) {
                if (near_gone(p.A * lattice.centre[static_cast<std::size_t>(p.source)] + p.t, 2.0) < 0.0) continue;
                for (const quilt::RingLattice::Neighbour& next : lattice.next[static_cast<std::size_t>(p.source)]) {
                    if (!is_ring_source(next.source)) continue;
                    const Vec2 at = p.A * (lattice.centre[static_cast<std::size_t>(next.source)] + next.shift) + p.t;
                    if (const double d = near_gone(at, kSwapReach); d >= 0.0 && at.norm() <= R) slots.emplace_back(d, p, &next);
                }
            }
            std::stable_sort(slots.begin(), slots.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
            bool more = false;
            for (std::size_t k = 0; k < slots.size() && !more; ++k) {
                const auto& [d, p, next] = slots[k];
                const Vec2 at = p.A * (lattice.centre[static_cast<std::size_t>(next->source)] + next->shift) + p.t;
                if (std::any_of(room.begin(), room.end(), [&](const Vec2& q) { return (q - at).norm() < kMendEmpty * unit; })) continue;
                if (ring_crowd(room, room_id, at, unit, lattice, flat, local) > kRingCrowd) continue;
                more = place(p, next->source, next->shift, at);
            }
            if (!more) return undo();
        }
        for (int id : linked) {
            const int need = ring_need_[static_cast<std::size_t>(elems_[static_cast<std::size_t>(id)].source)];
            const Vec2 at = room[static_cast<std::size_t>(std::find(room_id.begin(), room_id.end(), id) - room_id.begin())];
            std::vector<int> near = rings_near(room, room_id, at, 2.0 * unit);
            near.erase(std::remove(near.begin(), near.end(), id), near.end());
            if (links_with(elems_[static_cast<std::size_t>(id)].embedded, near, need) < need) return undo();
        }
        filled = std::move(room);
        filled_id = std::move(room_id);
        poses.insert(poses.end(), added_pose.begin(), added_pose.end());
        ++surface_.rings_swapped;
        return true;
    }

    /// Beyond the paper: holes at the seams of ring lattices. Where two lattices meet at an angle,
    /// each one's slot near the seam holds a ring of the other close by (not empty for mend_frame),
    /// or its ring collides there, and a hole wider than any of the swatch's own stays between them.
    /// Holes are found on a grid over the frame's core (points farther than kHoleEmpty spacings from
    /// every element's centre, widest first); each is offered the ring that the nearest standing
    /// rings' lattices have nearest to it, moved to the hole's centre and turned by up to
    /// kHoleTurn either way (a ring between two lattices follows neither), as mend_slot places it.
    void fill_ring_holes(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, double R,
                         const quilt::RingLattice& lattice, const std::vector<Pose>& poses, std::vector<Vec2>& filled, std::vector<int>& filled_id,
                         std::vector<SurfacePoint>* anchors, Mesh* embedded) {
        if (poses.empty() || hole_tries_ >= hole_budget()) return;
        const double spacing = lattice.spacing;
        std::vector<double> units;
        for (const Pose& p : poses) units.push_back(spacing * std::sqrt(std::fabs(p.A.determinant())));
        std::nth_element(units.begin(), units.begin() + static_cast<std::ptrdiff_t>(units.size() / 2), units.end());
        const double unit = units[units.size() / 2];
        if (!(unit > 0.0)) return;
        const double step = 0.25 * unit;
        const int n = static_cast<int>(std::ceil(R / step));
        auto empty_at = [&](const Vec2& q) {
            double d = std::numeric_limits<double>::infinity();
            for (const Vec2& c : filled) d = std::min(d, (c - q).squaredNorm());
            return std::sqrt(d);
        };
        std::vector<std::pair<double, Vec2>> holes;
        for (int iy = -n; iy <= n; ++iy)
            for (int ix = -n; ix <= n; ++ix) {
                const Vec2 q(ix * step, iy * step);
                if (q.norm() > R) continue;
                if (const double d = empty_at(q); d > kHoleEmpty * unit) holes.push_back({d, q});
            }
        std::sort(holes.begin(), holes.end(), [](const auto& a, const auto& b) {
            return a.first > b.first || (a.first == b.first && (a.second.x() < b.second.x() || (a.second.x() == b.second.x() && a.second.y() < b.second.y())));
        });
        if (holes.empty()) return;
        std::vector<double> turns;
        for (int k = 0; k <= kHoleTurnSteps; ++k) {
            const double t = kHoleTurn * k / kHoleTurnSteps;
            turns.push_back(t);
            if (k > 0) turns.push_back(-t);
        }
        struct StandingRing {
            Mesh mesh;  ///< in the frame (the part on it)
            Vec2 centre;
            Vec3 lo, hi;  ///< its box
            quilt::SolidGrid solid;  ///< built on first use
        };
        std::vector<StandingRing> standing;
        for (FrameElement& fe : frame_elements(flat, hs)) {
            if (!is_ring_source(elems_[static_cast<std::size_t>(fe.id)].source) || fe.mesh.vertices.empty()) continue;
            Vec2 c = Vec2::Zero();
            Vec3 lo = fe.mesh.vertices.front(), hi = lo;
            for (const Vec3& v : fe.mesh.vertices) {
                c += v.head<2>();
                lo = lo.cwiseMin(v);
                hi = hi.cwiseMax(v);
            }
            c /= static_cast<double>(fe.mesh.vertices.size());
            standing.push_back({std::move(fe.mesh), c, lo, hi, {}});
        }
        std::vector<Vec2> tried;  // one try per hole: its other grid points lie within half a spacing
        for (const auto& [d0, h] : holes) {
            if (hole_tries_ >= hole_budget()) return;
            if (empty_at(h) <= kHoleEmpty * unit) continue;  // a ring went in nearby
            if (std::any_of(tried.begin(), tried.end(), [&](const Vec2& q) { return (q - h).norm() < 0.5 * unit; })) continue;
            tried.push_back(h);
            Vec3 at, dir;
            double tolerance = 0.0;
            if (!slot_on_surface(flat, locator, h, 0.0, unit, &at, &dir, &tolerance) || hole_failed(at, 2.5 * tolerance)) continue;
            std::vector<std::pair<double, std::size_t>> near;  // standing rings by distance
            for (std::size_t k = 0; k < poses.size(); ++k) {
                const Vec2 c = poses[k].A * lattice.centre[static_cast<std::size_t>(poses[k].source)] + poses[k].t;
                near.push_back({(c - h).squaredNorm(), k});
            }
            std::sort(near.begin(), near.end());
            // Tries that reach into a standing ring (a vertex inside its solid in the frame, or
            // one of its vertices inside the try's) are refused before they are embedded: of the
            // tries embedded without this test, 99.5% collided (the eight at scale 0.2); with it,
            // 16 times fewer are embedded for as many rings.
            std::vector<std::size_t> blocking;
            for (std::size_t k = 0; k < standing.size(); ++k)
                if ((standing[k].centre - h).norm() <= kHoleReach * unit) blocking.push_back(k);
            // The vertices inside found by the last try refused (kind 0: a try's vertex in standing
            // ring k, 1: ring k's vertex in the try; ring; vertex): the hole's next try differs from
            // it by a small turn, shift or tilt, and is mostly refused by the same vertices, so they
            // are asked first. Only a shortcut: they count as the whole scan would count them (the
            // same tests), and when they do not refuse the try, the whole scan answers.
            std::vector<std::array<std::size_t, 3>> last_hits, hits;
            const Clash clash = [&](const Mesh& cand, const quilt::SolidGrid& mine, const Eigen::Matrix2d& M, const Vec2& b) {
                const Eigen::Matrix2d Minv = M.inverse();
                if (!Minv.allFinite()) return true;
                Vec3 lo = cand.vertices.front(), hi = lo;
                for (const Vec3& v : cand.vertices) {
                    lo = lo.cwiseMin(v);
                    hi = hi.cwiseMax(v);
                }
                // Vertices that no solid's inside voxel can hold are passed over unmapped (the same
                // count, sooner): a voxel is inside when its centre is, within the mesh's convex
                // hull, so a point in it lies within half a cell of the hull's box on each axis;
                // mapped by M, within half the cell times the row's absolute sum. A whole cell
                // keeps rounding clear.
                const double h = mine.cell();
                const Vec3 reach((std::fabs(M(0, 0)) + std::fabs(M(0, 1))) * h, (std::fabs(M(1, 0)) + std::fabs(M(1, 1))) * h, h);
                const Vec3 mine_lo = lo - reach, mine_hi = hi + reach;
                auto overlaps = [&](const StandingRing& o) { return !((o.lo.array() > hi.array()).any() || (o.hi.array() < lo.array()).any()); };
                auto in_ring = [&](const StandingRing& o, const Vec3& v) {
                    const Vec3 o_lo = o.lo - Vec3::Constant(o.solid.cell()), o_hi = o.hi + Vec3::Constant(o.solid.cell());
                    return (v.array() >= o_lo.array()).all() && (v.array() <= o_hi.array()).all() && o.solid.inside(v);
                };
                auto in_mine = [&](const Vec3& v) {
                    if ((v.array() < mine_lo.array()).any() || (v.array() > mine_hi.array()).any()) return false;
                    const Vec2 q = Minv * (v.head<2>() - b);
                    return mine.inside(Vec3(q.x(), q.y(), v.z()));
                };
                int inside = 0;
                for (const auto& [kind, k, v] : last_hits) {
                    const StandingRing& o = standing[k];
                    if (!overlaps(o) || o.solid.empty()) continue;
                    const bool hit = kind == 0 ? v < cand.vertices.size() && in_ring(o, cand.vertices[v]) : in_mine(o.mesh.vertices[v]);
                    if (hit && ++inside >= kHoleClash) return true;
                }
                // The whole scan; a refusal keeps its hits and the earlier ones, up to kClashMemory.
                inside = 0;
                hits.clear();
                auto refused = [&] {
                    for (const auto& x : last_hits)
                        if (hits.size() < kClashMemory && std::find(hits.begin(), hits.end(), x) == hits.end()) hits.push_back(x);
                    last_hits.swap(hits);
                    return true;
                };
                for (std::size_t k : blocking) {
                    StandingRing& o = standing[k];
                    if (!overlaps(o)) continue;
                    if (o.solid.empty()) o.solid = quilt::SolidGrid(o.mesh, kFrameSolidCells);
                    for (std::size_t v = 0; v < cand.vertices.size(); ++v)
                        if (in_ring(o, cand.vertices[v])) {
                            hits.push_back({0, k, v});
                            if (++inside >= kHoleClash) return refused();
                        }
                    for (std::size_t v = 0; v < o.mesh.vertices.size(); ++v)
                        if (in_mine(o.mesh.vertices[v])) {
                            hits.push_back({1, k, v});
                            if (++inside >= kHoleClash) return refused();
                        }
                }
                return false;
            };
            // The rings offered: of each of the nearest kHoleLattices standing rings' lattices, the
            // kHoleSlots slots nearest the hole (within a spacing), each moved to the hole.
            struct Offer {
                const Pose* pose;
                const quilt::RingLattice::Neighbour* slot;
                Vec2 centre;
            };
            std::vector<Offer> offers;
            for (std::size_t m = 0; m < near.size() && m < static_cast<std::size_t>(kHoleLattices); ++m) {
                const Pose& pose = poses[near[m].second];
                std::vector<std::pair<double, const quilt::RingLattice::Neighbour*>> slots;
                for (const quilt::RingLattice::Neighbour& next : lattice.next[static_cast<std::size_t>(pose.source)]) {
                    const Vec2 c = pose.A * (lattice.centre[static_cast<std::size_t>(next.source)] + next.shift) + pose.t;
                    if ((c - h).norm() <= unit) slots.push_back({(c - h).norm(), &next});
                }
                std::sort(slots.begin(), slots.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
                for (std::size_t k = 0; k < slots.size() && k < static_cast<std::size_t>(kHoleSlots); ++k)
                    offers.push_back({&pose, slots[k].second,
                                      pose.A * (lattice.centre[static_cast<std::size_t>(slots[k].second->source)] + slots[k].second->shift) + pose.t});
            }
            bool placed_any = false;
            double fit = 0.0;  // the map's scale at the hole, found by the first ring embedded (mend_slot)
            for (const Offer& offer : offers) {
                // The hole's centre first, then points around it on two circles (the hole's widest
                // point is rarely where a ring fits between two lattices).
                const Vec2 ax = offer.pose->A.col(0).normalized(), ay = offer.pose->A.col(1).normalized();
                std::vector<Vec2> offs{Vec2::Zero()};
                for (const double r : kHoleShifts)
                    for (const Vec2& o : {ax, Vec2(-ax), ay, Vec2(-ay), Vec2(ax + ay), Vec2(ax - ay), Vec2(-ax + ay), Vec2(-ax - ay)})
                        offs.push_back(r * unit * o.normalized());
                for (const Vec2& off : offs) {
                    const Vec2 hc = h + off;
                    if (ring_crowd(filled, filled_id, hc, unit, lattice, flat, local) > kRingCrowd) continue;
                    Pose moved = *offer.pose;
                    moved.t += hc - offer.centre;
                    const std::vector<int> around = rings_near(filled, filled_id, hc, kMendLinkReach * unit);
                    bool lasting = true;
                    Pose placed;
                    if (mend_slot(flat, locator, hs, local, moved, offer.slot->source, offer.slot->shift, hc, around, anchors, embedded, &placed, &lasting, &turns,
                                  &clash, &fit, sw_.thinned > 0.0 ? 1 : kHoleVariants)) {
                        filled.push_back(hc);
                        filled_id.push_back(static_cast<int>(elems_.size()) - 1);
                        ++surface_.ring_holes_filled;
                        placed_any = true;
                        break;
                    }
                }
                if (placed_any) break;
            }
            if (!placed_any) {  // wanting a link or room on the frame too: holes are many, and tries dear
                hole_failed_.push_back(at);
                hole_failed_grid_[mend_key(at)].push_back(hole_failed_.size() - 1);
            }
        }
    }

    /// A quick test of a ring's try in a mending frame (fill_ring_holes): its mesh in the frame,
    /// the solid of the swatch ring it was made from and the map M v + b of that ring's xy onto
    /// the frame.
    using Clash = std::function<bool(const Mesh&, const quilt::SolidGrid&, const Eigen::Matrix2d&, const Vec2&)>;

    /// Swatch ring `s` as fill_ring_holes may tilt it: variant 0 as it is, 1-4 turned by kHoleTilt
    /// either way about the swatch's x and y axes through its area centroid, and lifted so that its
    /// lowest point stays where it was; empty where it then rises above the swatch (built on first
    /// use).
    const Mesh& ring_variant(int s, int variant) {
        if (variant == 0) return sw_.elements[static_cast<std::size_t>(s)];
        auto it = variant_.find({s, variant});
        if (it != variant_.end()) return it->second;
        const Mesh& src = sw_.elements[static_cast<std::size_t>(s)];
        const Vec3 c = area_centroid(src);
        const double angle = (variant % 2 == 1 ? 1.0 : -1.0) * kHoleTilt;
        const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, variant <= 2 ? Vec3::UnitX() : Vec3::UnitY()).toRotationMatrix();
        Mesh m = src;
        double lo = std::numeric_limits<double>::infinity(), lo0 = lo;
        for (std::size_t v = 0; v < m.vertices.size(); ++v) {
            lo0 = std::min(lo0, src.vertices[v].z());
            m.vertices[v] = R * (src.vertices[v] - c) + c;
            lo = std::min(lo, m.vertices[v].z());
        }
        double hi = -std::numeric_limits<double>::infinity();
        for (Vec3& v : m.vertices) {
            v.z() += lo0 - lo;
            hi = std::max(hi, v.z());
        }
        // Tilted steeper than the swatch's slab allows, the shell would squash it in height (its
        // diameter too, for a steep ring): left out (no faces).
        return variant_.emplace(std::make_pair(s, variant), std::move(m)).first->second;
    }

    /// The largest distance between two of `m`'s vertices.
    static double vertex_diameter(const Mesh& m) {
        double d = 0.0;
        for (std::size_t a = 0; a < m.vertices.size(); ++a)
            for (std::size_t b = a + 1; b < m.vertices.size(); ++b) d = std::max(d, (m.vertices[a] - m.vertices[b]).squaredNorm());
        return std::sqrt(d);
    }

    /// Is vertex_diameter(m) < `width`? The same answer (the square root is monotone and correctly
    /// rounded, so the largest root is the root of the largest square), found at the first pair at
    /// least `width` apart: a ring that keeps its width shows one within its first vertex's pairs,
    /// where the whole diameter takes all of them (mend_slot asked it of every try).
    static bool narrower_than(const Mesh& m, double width) {
        const double w2 = width * width;
        for (std::size_t a = 0; a < m.vertices.size(); ++a)
            for (std::size_t b = a + 1; b < m.vertices.size(); ++b)
                if (const double d2 = (m.vertices[a] - m.vertices[b]).squaredNorm(); d2 >= 0.5 * w2 && std::sqrt(d2) >= width) return false;
        return true;
    }

    /// vertex_diameter of swatch ring `s`'s variant (ring_variant; computed on first use).
    double diameter_of(int s, int variant) {
        auto it = variant_diameter_.find({s, variant});
        if (it != variant_diameter_.end()) return it->second;
        return variant_diameter_.emplace(std::make_pair(s, variant), vertex_diameter(ring_variant(s, variant))).first->second;
    }

    /// The solid of swatch ring `s`'s variant (ring_variant; built on first use).
    const quilt::SolidGrid& solid_of(int s, int variant = 0) {
        auto it = variant_solid_.find({s, variant});
        if (it != variant_solid_.end()) return it->second;
        return variant_solid_.emplace(std::make_pair(s, variant), quilt::SolidGrid(ring_variant(s, variant), kSolidCells)).first->second;
    }

    /// How crowded a mending frame's rings are around `c` (frame units) once a ring goes in at `c`:
    /// the rings' weights, (1 - (d / r)^2)^2 within r = kRingCrowdReach spacings, the new ring's 1
    /// included, over the weight the swatch's own rings give a point inside it
    /// (ring_crowd_reference). Distances are taken on the surface, in the swatch's ring spacing at
    /// the run's scale: the frame's stretch around `c` (frame_stretch, over the faces within
    /// kRingCrowdReach of `unit`, the lattice's spacing there) undone. (Taken in the lattice's
    /// spacing, as in session 48, the guard let a lattice squeezed by its patch's map set the
    /// count: the bundled mail on the tests' eight at scale 0.2 held 1.19 of the swatch's rings
    /// per base area in a region.) 0 when the swatch gives none, and for a
    /// thinned swatch, whose mended rings are thickened back less where they stand close: on the
    /// tests' tight mail (SurfaceThickMail) the guard changed which rings were mended and left one
    /// at 0.68 of its size and a region at 1.153 (1.142 without it).
    double ring_crowd(const std::vector<Vec2>& filled, const std::vector<int>& filled_id, const Vec2& c, double unit, const quilt::RingLattice& lattice,
                      const quilt::FlatPatch& flat, double local) {
        if (sw_.thinned > 0.0) return 0.0;
        const double reference = ring_crowd_reference(lattice);
        if (!(reference > 0.0) || !(unit > 0.0)) return 0.0;
        unit = lattice.spacing / frame_stretch(flat, c, kRingCrowdReach * unit, local);
        const double r2 = std::pow(kRingCrowdReach * unit, 2);
        double w = 1.0;
        for (std::size_t i = 0; i < filled.size(); ++i) {
            const double t2 = (filled[i] - c).squaredNorm() / r2;
            if (t2 < 1.0 && is_ring_source(elems_[static_cast<std::size_t>(filled_id[i])].source)) w += (1.0 - t2) * (1.0 - t2);
        }
        return w / reference;
    }
    /// How much longer the surface is than frame `flat` (at local scale `local`) around `c`: the
    /// square root of the base area over the frame area of the faces whose frame centroids lie
    /// within `r` of `c`, in swatch units at the local scale (1 where the frame is true to the
    /// surface, as it is near its seed: make_frame).
    double frame_stretch(const quilt::FlatPatch& flat, const Vec2& c, double r, double local) const {
        double flat_area = 0.0, true_area = 0.0;
        for (std::size_t lf = 0; lf < flat.faces.size(); ++lf) {
            const Tri& t = flat.local[lf];
            const Vec2& a = flat.uv[static_cast<std::size_t>(t[0])];
            const Vec2& b = flat.uv[static_cast<std::size_t>(t[1])];
            const Vec2& d = flat.uv[static_cast<std::size_t>(t[2])];
            if (((a + b + d) / 3.0 - c).squaredNorm() > r * r) continue;
            flat_area += 0.5 * std::fabs((b - a).x() * (d - a).y() - (b - a).y() * (d - a).x());
            true_area += base_.area[static_cast<std::size_t>(flat.faces[lf])];
        }
        if (!(flat_area > 0.0) || !(true_area > 0.0)) return 1.0;
        return std::sqrt(true_area / flat_area) / (scale_ * local);
    }

    /// The weight ring_crowd gives a point of the swatch, from the swatch's rings, averaged over
    /// the points (a grid of an eighth of the spacing) whose whole reach lies inside the box of the
    /// rings' centres: the swatch's rings per area as the guard counts them, edge effects and all
    /// (a count in a window off the lattice's period was 6% high on a rectangular mail). A swatch
    /// too small for that takes its rings per area in the density window (kDensityInset), each ring
    /// counted by its share of area there, times the weight's integral, pi r^2 / 3.
    double ring_crowd_reference(const quilt::RingLattice& lattice) {
        if (ring_crowd_reference_ >= 0.0) return ring_crowd_reference_;
        ring_crowd_reference_ = 0.0;
        const double spacing = lattice.spacing;
        if (!(spacing > 0.0)) return 0.0;
        const double r = kRingCrowdReach * spacing;
        std::vector<Vec2> centres;
        Eigen::AlignedBox2d box;
        for (std::size_t e = 0; e < lattice.centre.size(); ++e)
            if (is_ring_source(static_cast<int>(e))) {
                centres.push_back(lattice.centre[e]);
                box.extend(lattice.centre[e]);
            }
        if (centres.empty()) return 0.0;
        const Vec2 lo = box.min() + Vec2::Constant(r), hi = box.max() - Vec2::Constant(r);
        if ((lo.array() < hi.array()).all()) {
            const double step = spacing / 8.0;
            double sum = 0.0;
            long n = 0;
            for (double y = lo.y(); y <= hi.y(); y += step)
                for (double x = lo.x(); x <= hi.x(); x += step) {
                    for (const Vec2& c : centres) {
                        const double t2 = (c - Vec2(x, y)).squaredNorm() / (r * r);
                        if (t2 < 1.0) sum += (1.0 - t2) * (1.0 - t2);
                    }
                    ++n;
                }
            ring_crowd_reference_ = sum / static_cast<double>(n);
            return ring_crowd_reference_;
        }
        const double mx = quilt::kDensityInset * sw_.box.size().x(), my = quilt::kDensityInset * sw_.box.size().y();
        const double x0 = sw_.box.min.x() + mx, x1 = sw_.box.max.x() - mx, y0 = sw_.box.min.y() + my, y1 = sw_.box.max.y() - my;
        double count = 0.0;
        for (std::size_t e = 0; e < sw_.elements.size(); ++e) {
            if (!is_ring_source(static_cast<int>(e))) continue;
            const Mesh& m = sw_.elements[e];
            double in = 0.0, all = 0.0;
            for (std::size_t f = 0; f < m.faces.size(); ++f) {
                const double a = face_area(m, f);
                const Vec3 c = (m.vertices[static_cast<std::size_t>(m.faces[f][0])] + m.vertices[static_cast<std::size_t>(m.faces[f][1])] +
                                m.vertices[static_cast<std::size_t>(m.faces[f][2])]) / 3.0;
                all += a;
                if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1) in += a;
            }
            if (all > 0.0) count += in / all;
        }
        ring_crowd_reference_ = count / std::max((x1 - x0) * (y1 - y0), 1e-300) * r * r * std::acos(-1.0) / 3.0;
        return ring_crowd_reference_;
    }
    /// Tries fill_ring_holes may still embed: kHoleBudget per ring standing when mending started,
    /// and no more than kHoleTriesFree per ring standing (at least 1,000) and kHoleTriesPerRing for
    /// each ring it put in (chain mail on spot takes 19 tries per ring put in; where rings rarely
    /// fit, tries stop early).
    long hole_budget() const {
        return std::min(hole_budget_, hole_free_ + kHoleTriesPerRing * static_cast<long>(surface_.ring_holes_filled));
    }
    /// ... and tilted tries (ring_variant) apart from those: kHoleTiltFree per ring standing (at
    /// least 1,000) and kHoleTriesPerRing for each tilted ring put in, so that where tilting rarely
    /// helps it stops early and does not spend the untilted tries' budget.
    long tilt_budget() const {
        return std::min(hole_budget_, tilt_free_ + kHoleTriesPerRing * static_cast<long>(surface_.ring_holes_tilted));
    }

    /// Was a hole tried in vain within `tolerance` of `at`?
    bool hole_failed(const Vec3& at, double tolerance) const {
        return any_in_cells(hole_failed_grid_, at, [&](std::size_t i) { return (hole_failed_[i] - at).norm() < tolerance; });
    }

    /// Does `hit` hold for an entry of `grid` (mend_key cells) in the 27 cells around `at`?
    template <class Hit>
    bool any_in_cells(const std::map<std::array<long, 3>, std::vector<std::size_t>>& grid, const Vec3& at, const Hit& hit) const {
        const auto k = mend_key(at);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == grid.end()) continue;
                    for (std::size_t i : it->second)
                        if (hit(i)) return true;
                }
        return false;
    }

    /// A frame slot on the surface: its base point and the 3D direction of the frame's angle
    /// `angle` there, and a tenth of the ring spacing `unit` (frame units) in base units.
    bool slot_on_surface(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, const Vec2& c, double angle, double unit,
                         Vec3* at, Vec3* dir, double* tolerance) const {
        const auto hit = locator.locate(c, 0.0);
        if (hit.local_face < 0) return false;
        const auto lf = static_cast<std::size_t>(hit.local_face);
        const auto f = static_cast<std::size_t>(flat.faces[lf]);
        const Tri& t = base_.mesh.faces[f];
        *at = hit.bary[0] * base_.mesh.vertices[static_cast<std::size_t>(t[0])] + hit.bary[1] * base_.mesh.vertices[static_cast<std::size_t>(t[1])] +
              hit.bary[2] * base_.mesh.vertices[static_cast<std::size_t>(t[2])];
        const Vec3 x = frame_x_on(flat, lf);
        const Vec3 n = (base_.mesh.vertices[static_cast<std::size_t>(t[1])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])])
                           .cross(base_.mesh.vertices[static_cast<std::size_t>(t[2])] - base_.mesh.vertices[static_cast<std::size_t>(t[0])]);
        if (x.squaredNorm() == 0.0 || !(n.norm() > 0.0)) return false;
        *dir = std::cos(angle) * x + std::sin(angle) * n.normalized().cross(x);
        *tolerance = 0.1 * unit * scale_ * local_scale_[f];
        return true;
    }

    std::array<long, 3> mend_key(const Vec3& p) const {
        const Vec3 q = p / mend_cell_;
        return {std::lround(std::floor(q.x())), std::lround(std::floor(q.y())), std::lround(std::floor(q.z()))};
    }

    /// Was a ring tried in vain at `at` with direction `dir` (within `tolerance` and 3 degrees)?
    bool mend_failed(const Vec3& at, const Vec3& dir, double tolerance) const {
        return any_in_cells(mend_failed_grid_, at, [&](std::size_t i) {
            return (mend_failed_[i].first - at).norm() < tolerance && mend_failed_[i].second.dot(dir) > std::cos(3.0 * M_PI / 180.0);
        });
    }

    /// Tries swatch ring `j`, shifted by `shift` in the swatch, where `pose` puts it (centre `c` in
    /// the frame): as it is, turned by up to 6 degrees either way about c, then shrunk to 0.92 and
    /// 0.85 of its size (a ring between two lattices that meet at an angle often fits only a little
    /// smaller; each shrink of the 38 rings mended on the eight, 15 were smaller), and in a hole
    /// (`clash` given) last enlarged to 1.1 (kRingSizes). The first pose
    /// that lies on the patch, collides with nothing and does not fold is added. fill_ring_holes
    /// passes its own `turns`, a quick `clash` test that refuses a pose before it is embedded,
    /// `fit_io`, the map's scale for the ring's size, found once per hole (0: not yet), and
    /// `variants`: the ring's tilted variants (ring_variant) tried in turn after it, each in every
    /// pose. `plain`, if given, receives the embedding of the ring as `pose` puts it (unturned, at
    /// its size) when that pose reaches the collision test (swap_blocker asks what it hits).
    bool mend_slot(const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local, const Pose& pose, int j,
                   const Vec2& shift, const Vec2& c, const std::vector<int>& around, std::vector<SurfacePoint>* anchors, Mesh* embedded, Pose* placed,
                   bool* lasting, const std::vector<double>* turns = nullptr, const Clash* clash = nullptr, double* fit_io = nullptr,
                   int variants = 1, Mesh* plain = nullptr) {
        static const std::vector<double> kTurns{0.0, 0.05, -0.05, 0.1, -0.1};
        *lasting = true;  // every pose collided or folded: more rings will not change that
        const double want = std::max(mesh_area(sw_.elements[static_cast<std::size_t>(j)]) * scale_ * scale_ * local * local, 1e-300);
        double fit = fit_io ? *fit_io : 0.0;  // the frame scale that gives the ring its swatch size on the surface (embed_sized)
        const std::vector<double>& turn_list = turns ? *turns : kTurns;
        // A pose's test once it is on the surface (test_mend_try) costs most of the mending: the
        // poses past the first embedding are tested in batches, in parallel, and their outcomes
        // are then taken in order as one after the other would have been, so a batch changes no
        // outcome, only tests a few poses past the first that fits (kMendBatch per core).
        const auto batch = static_cast<std::size_t>(std::max(2, kMendBatch * tbb::this_task_arena::max_concurrency()));
        for (int variant = 0; variant < variants; ++variant) {
            // Tilted tries stop with their budget before their poses are screened: past it every
            // pose that passed the screen was refused anyway, and each hole still screened its
            // four variants' poses against the standing rings' solids (the Bunny + Link benchmark
            // spent 30 s so for no ring).
            if (clash && variant > 0 && tilt_tries_ >= tilt_budget()) break;
            const Mesh& src = ring_variant(j, variant);
            if (src.faces.empty()) continue;
            const Vec3 src_centroid = area_centroid(src);
            const double src_diameter = diameter_of(j, variant);
            const quilt::SolidGrid* mine = clash ? &solid_of(j, variant) : nullptr;
            const std::size_t sizes = clash && !(sw_.thinned > 0.0) ? kRingSizes.size() : kRingSizes.size() - 1;
            long* budget_count = clash ? (variant == 0 ? &hole_tries_ : &tilt_tries_) : nullptr;
            const long budget = clash ? (variant == 0 ? hole_budget() : tilt_budget()) : 0;
            // A pose turned by `turn`: its frame mesh m = M v + b for the swatch ring's vertices v
            // (xy), resized by f about its area centroid as resized_in_frame does.
            auto pose_at = [&](double turn, double f, Mesh* m, Eigen::Matrix2d* M, Vec2* b) {
                Eigen::Matrix2d T;
                T << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn);
                const Eigen::Matrix2d M0 = T * pose.A;
                const Vec2 b0 = T * (pose.A * shift + pose.t - c) + c;
                *M = f * M0;
                *b = f * b0 + (1.0 - f) * (M0 * src_centroid.head<2>() + b0);
                if (m->vertices.size() != src.vertices.size()) *m = src;
                for (std::size_t v = 0; v < m->vertices.size(); ++v) {
                    const Vec2 q = *M * src.vertices[v].head<2>() + *b;
                    m->vertices[v] = Vec3(q.x(), q.y(), src.vertices[v].z());
                }
            };
            std::vector<std::pair<std::size_t, double>> order;  // (size, turn)
            for (std::size_t size = 0; size < sizes; ++size)
                for (const double turn : turn_list) order.push_back({size, turn});
            std::vector<MendTry> tries;
            for (std::size_t next = 0; next < order.size();) {
                tries.clear();
                if (fit == 0.0) {
                    // Until the first pose is embedded the map's scale for the ring is not known:
                    // one pose at a time.
                    const auto [size, turn] = order[next++];
                    const double shrink = kRingSizes[size];
                    Mesh m;
                    Eigen::Matrix2d M;
                    Vec2 b;
                    if (clash) {
                        // Tested quickly first, at the swatch size while the map's scale here is
                        // not known yet (embed_sized changes it only beyond kLatticeSizeDrift).
                        pose_at(turn, shrink, &m, &M, &b);
                        if ((*clash)(m, *mine, M, b)) continue;
                    }
                    if (budget_count && ++*budget_count > budget) return false;  // fill_ring_holes stops, or no more tilted tries
                    pose_at(turn, 1.0, &m, &M, &b);
                    if (!embed_sized(m, j, true, flat, locator, hs, local, nullptr, anchors, embedded, &fit)) {
                        *lasting = false;  // off this patch: another frame may hold it
                        return false;
                    }
                    if (fit_io) *fit_io = fit;
                    pose_at(turn, fit * shrink, &m, &M, &b);
                    if (clash && fit != 1.0 && (*clash)(m, *mine, M, b)) continue;
                    tries.push_back({size, turn, std::move(m)});
                }
                // The next poses up to a batch, screened (clash) and counted against the budget as
                // they would be one after the other; a pose past the budget ends the batch.
                for (long counted = 0; next < order.size() && tries.size() < batch;) {
                    const auto [size, turn] = order[next++];
                    MendTry t{size, turn, {}};
                    Eigen::Matrix2d M;
                    Vec2 b;
                    pose_at(turn, fit * kRingSizes[size], &t.m, &M, &b);
                    if (clash && (*clash)(t.m, *mine, M, b)) continue;
                    t.counted = budget_count != nullptr;
                    if (budget_count && *budget_count + ++counted > budget) {
                        t.over_budget = true;  // replayed, it ends mend_slot
                        tries.push_back(std::move(t));
                        break;
                    }
                    tries.push_back(std::move(t));
                }
                tbb::parallel_for(std::size_t{0}, tries.size(), [&](std::size_t i) {
                    if (!tries[i].over_budget) test_mend_try(tries[i], j, src_diameter, want, around, flat, locator, hs, local);
                });
                for (MendTry& t : tries) {
                    if (t.counted && ++*budget_count > budget) return false;
                    if (t.torn) ++torn_tries_;
                    *anchors = std::move(t.anchors);
                    *embedded = std::move(t.embedded);
                    switch (t.outcome) {
                        case MendTry::kOffPatch:
                            *lasting = false;
                            continue;
                        case MendTry::kTooSmall: return false;
                        case MendTry::kNarrow:
                            if (variant == 0) return false;
                            continue;
                        case MendTry::kOffSize: continue;
                        default: break;
                    }
                    if (plain && variant == 0 && t.size == 0 && t.turn == 0.0) *plain = *embedded;  // swap_blocker asks what it hits
                    if (t.outcome == MendTry::kCollides || t.outcome == MendTry::kCrowds) continue;
                    if (t.outcome == MendTry::kUnlinked) {
                        *lasting = false;  // a ring mended later may give it a link
                        continue;
                    }
                    const double shrink = kRingSizes[t.size];
                    add_element(std::move(*anchors), t.m.faces, std::move(*embedded), j);
                    ++surface_.elements_mended;  // ring_holes_filled counts the hole fillers among them
                    if (variant > 0) ++surface_.ring_holes_tilted;
                    if (shrink > 1.0) ++surface_.ring_holes_enlarged;
                    // Its lattice pose (the turn, not the shrink: its neighbours keep the spacing).
                    Eigen::Matrix2d T;
                    T << std::cos(t.turn), -std::sin(t.turn), std::sin(t.turn), std::cos(t.turn);
                    *placed = {j, T * pose.A, T * (pose.A * shift + pose.t - c) + c, 0.0};
                    return true;
                }
            }
        }
        return false;
    }

    /// A pose of mend_slot's ring (`m`, in the frame) and what became of it on the surface.
    struct MendTry {
        std::size_t size = 0;  ///< index into kRingSizes
        double turn = 0.0;
        Mesh m;
        bool counted = false;      ///< counts against fill_ring_holes' budget
        bool over_budget = false;  ///< past it: not tested, mend_slot stops here
        enum Outcome { kOffPatch, kTooSmall, kNarrow, kOffSize, kCollides, kCrowds, kUnlinked, kFits } outcome = kOffPatch;
        bool torn = false;  ///< refused as torn (counted in the report when the pose is reached)
        std::vector<SurfacePoint> anchors;
        Mesh embedded;
    };

    /// mend_slot's test of a pose of ring `j` (of diameter `src_diameter` in the swatch) on the
    /// surface; reads the standing elements only, so poses are tested in parallel.
    void test_mend_try(MendTry& t, int j, double src_diameter, double want, const std::vector<int>& around, const quilt::FlatPatch& flat,
                       const quilt::PatchLocator& locator, double hs, double local) const {
        if (!embed_sized(t.m, j, false, flat, locator, hs, local, nullptr, &t.anchors, &t.embedded, nullptr, &t.torn)) {
            t.outcome = MendTry::kOffPatch;
            return;
        }
        // Shrunk, and flattened where the shell is lowered, it keeps kMendMinSize of its swatch
        // element's size (the square root of the area; the stage promises 1.5). Turned it keeps its
        // size, and shrunk further it only loses more: the slot is given up (where the shell is
        // lowered most holes fail so, and trying every turn and shrink there spent the holes'
        // budget before the rest of the surface was reached).
        if (std::sqrt(mesh_area(t.embedded) / want) < kMendMinSize) {
            t.outcome = MendTry::kTooSmall;
            return;
        }
        // Its width too: squashed by a lowered shell a ring can keep its area and lose its
        // diameter (a steep ring, or one tilted to rise above the slab). It keeps kMendMinWidth of
        // its swatch ring's diameter.
        if (narrower_than(t.embedded, kMendMinWidth * src_diameter * scale_ * local)) {
            t.outcome = MendTry::kNarrow;
            return;
        }
        if (!is_ring_source(j) && off_size(t.embedded, j, local)) {
            t.outcome = MendTry::kOffSize;
            return;
        }
        if (collider_.collides(t.embedded) || count_self_intersections(t.embedded, 1) > 0) {
            t.outcome = MendTry::kCollides;
            return;
        }
        if (!is_ring_source(j) && !keeps_clearance_3d(t.embedded, local)) {
            t.outcome = MendTry::kCrowds;
            return;
        }
        if (interlocked_ && links_with(t.embedded, around, ring_need_[static_cast<std::size_t>(j)]) < ring_need_[static_cast<std::size_t>(j)]) {
            t.outcome = MendTry::kUnlinked;
            return;
        }
        t.outcome = MendTry::kFits;
    }

    /// Beyond the paper: thread `frame` (in the patch frame), whose embedding `embedded` collides
    /// with a few faces only, dented clear (kDentStep, kDentTries, kDentMaxShare): the
    /// vertices of the colliding faces move inward along their frame normals, their neighbours by
    /// half as much and the next ring by a quarter, and the thread is embedded again, until it
    /// collides with nothing or the tries run out. True with the dented frame mesh, its anchors and
    /// embedding when it comes out clear, not folded and not torn.
    bool dent_clear(const Mesh& frame, int source, bool fresh, const Reach* at, const std::vector<int>& ignore, const Mesh& embedded, const quilt::FlatPatch& flat,
                    const quilt::PatchLocator& locator, double hs, double local, Mesh* out_frame, std::vector<SurfacePoint>* out_anchors,
                    Mesh* out_embedded) const {
        const std::size_t F = frame.faces.size(), V = frame.vertices.size();
        if (F == 0 || embedded.faces.size() != F) return false;
        double volume = 0.0;
        for (const Tri& t : frame.faces)
            volume += frame.vertices[static_cast<std::size_t>(t[0])].dot(frame.vertices[static_cast<std::size_t>(t[1])].cross(frame.vertices[static_cast<std::size_t>(t[2])])) / 6.0;
        const double thickness = 4.0 * volume / std::max(quilt::mesh_area(frame), 1e-300);  // a round tube's diameter
        if (!(thickness > 0.0) || !std::isfinite(thickness)) return false;
        std::vector<std::vector<int>> nb(V);
        for (const Tri& t : frame.faces)
            for (int k = 0; k < 3; ++k) nb[static_cast<std::size_t>(t[k])].push_back(t[(k + 1) % 3]);
        Mesh current = frame;
        Mesh current_embedded = embedded;
        std::vector<double> depth(V, 0.0);  // the dent so far, per vertex, along the undented frame's normals
        const std::vector<Vec3> normal = vertex_normals(frame);
        const auto most = static_cast<std::size_t>(kDentMaxShare * static_cast<double>(F));
        for (int attempt = 0; attempt < kDentTries; ++attempt) {
            const std::vector<char> hit = collider_.colliding_faces(current_embedded, ignore, most);
            const auto hits = static_cast<std::size_t>(std::count(hit.begin(), hit.end(), 1));
            if (hits == 0 && attempt == 0) return false;  // nothing to dent
            if (hits == 0) break;
            if (hits > most) return false;  // an overlap, not a graze
            std::vector<double> add(V, 0.0);
            for (std::size_t f = 0; f < F; ++f)
                if (hit[f])
                    for (int k = 0; k < 3; ++k) add[static_cast<std::size_t>(frame.faces[f][k])] = 1.0;
            for (double share : {0.5, 0.25}) {  // the next two rings, eased
                std::vector<double> next = add;
                for (std::size_t v = 0; v < V; ++v)
                    if (add[v] > share)
                        for (int w : nb[v]) next[static_cast<std::size_t>(w)] = std::max(next[static_cast<std::size_t>(w)], share);
                add = std::move(next);
            }
            current = frame;
            for (std::size_t v = 0; v < V; ++v) {
                depth[v] += add[v] * kDentStep * thickness;
                if (normal[v].allFinite()) current.vertices[v] -= depth[v] * normal[v];
            }
            std::vector<SurfacePoint> anchors;
            Mesh emb;
            if (!embed_sized(current, source, fresh, flat, locator, hs, local, at, &anchors, &emb, nullptr)) return false;
            current_embedded = std::move(emb);
            *out_anchors = std::move(anchors);
        }
        if (collider_.collides(current_embedded, ignore) || count_self_intersections(current_embedded, 1) > 0 ||
            !stretched_faces(current, current_embedded).empty())
            return false;
        *out_frame = std::move(current);
        *out_embedded = std::move(current_embedded);
        return true;
    }

    /// Applies a plan like the planar stage does, with collisions tested on the embedded elements.
    /// `old` and `obstacles` are the output's elements in the patch frame before the plan (for the
    /// clearance of nudged elements).
    void apply(const quilt::PatchPlan& plan, const quilt::FlatPatch& flat, const quilt::PatchLocator& locator, double hs, double local,
               const std::vector<quilt::OldElement>& old, const std::vector<Mesh>& obstacles) {
        using Kind = quilt::PatchPlan::Change::Kind;
        struct Candidate {
            const quilt::PatchPlan::Change* change = nullptr;
            std::vector<SurfacePoint> anchors, fallback_anchors;
            Mesh embedded, fallback;
            double resize = 1.0;  ///< the element's scale in the frame for its size on the surface (embed_sized)
            double fallback_resize = 1.0;
            std::vector<char> folded;  ///< a thread's faces that the embedding folds or tears (stretched_faces; none: it does neither)
            std::vector<int> dent_hit;  ///< the collider ids it met when dent_clear was last tried (tried again only once one of them is gone)
            const Mesh* dented = nullptr;  ///< the thread's frame mesh dented clear (dent_clear), when it was
            // What `embedded` and `fallback` met in the collider before the loop below (known_hits),
            // with the ignored id of the change's old element; for a new element, its faces that met
            // them. Set aside once `embedded` changes.
            bool hits_known = false, fallback_hits_known = false, faces_known = false;
            std::vector<int> hits, fallback_hits;
            std::vector<char> hit_faces;
        };
        // A new element goes onto the surface at its swatch element's size: where the patch's map
        // scales area (LSCM is conformal, not area preserving; normal displacement fans out over
        // convex ground), the element is rescaled about its centre in the frame, once.
        //
        // Normal displacement folds an element where the base is concave with a radius below its
        // height; such an element is left out (counted), the ground stays for a later patch.
        auto folded = [&](const Mesh& embedded) {
            if (count_self_intersections(embedded, 1) == 0) return false;
            ++surface_.elements_folded;
            return true;
        };
        auto place_sized = [&](const Mesh& m, int source, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded,
                               double* resize = nullptr) {
            return embed_sized(m, source, fresh, flat, locator, hs, local, nullptr, anchors, embedded, resize);
        };
        auto place = [&](const Mesh& m, int source, bool fresh, std::vector<SurfacePoint>* anchors, Mesh* embedded, double* resize = nullptr) {
            if (!place_sized(m, source, fresh, anchors, embedded, resize)) return false;
            return !folded(*embedded);
        };
        // Each change is embedded on its own (everything it calls is const but the counters, which
        // each change keeps for itself): in parallel, then taken in the plan's order, so the
        // outcome does not depend on the threads.
        struct Built {
            Candidate c;
            bool placed = false;
            int folded = 0, torn = 0, enlarged = 0;
        };
        std::vector<Built> built(plan.changes.size());
        tbb::parallel_for(std::size_t{0}, plan.changes.size(), [&](std::size_t i) {
            const auto& ch = plan.changes[i];
            Built& b = built[i];
            Candidate& c = b.c;
            c.change = &ch;
            const bool fresh = ch.kind == Kind::Added || ch.kind == Kind::Replaced;
            const auto r = reach_.find(ch.old_id);
            const Reach* ch_reach = ch.old_id >= 0 && r != reach_.end() ? &r->second : nullptr;
            auto ch_folded = [&](const Mesh& embedded) {
                if (count_self_intersections(embedded, 1) == 0) return false;
                ++b.folded;
                return true;
            };
            auto ch_place_sized = [&](const Mesh& m, int source, bool fresh_, const Reach* at, std::vector<SurfacePoint>* anchors, Mesh* embedded,
                                      double* resize = nullptr) {
                return embed_sized(m, source, fresh_, flat, locator, hs, local, at, anchors, embedded, resize);
            };
            // A new thread that the embedding folds is not dropped whole: it is cut clear of the
            // fold (below), as where it collides.
            const bool thread = ch.kind == Kind::Added && quilt::is_elongated(ch.mesh);
            const bool placed = thread ? ch_place_sized(ch.mesh, ch.source, fresh, ch_reach, &c.anchors, &c.embedded, &c.resize)
                                       : ch_place_sized(ch.mesh, ch.source, fresh, ch_reach, &c.anchors, &c.embedded, &c.resize) && !ch_folded(c.embedded);
            if (!placed) return;
            if (thread && count_self_intersections(c.embedded, 1) > 0) {
                ++b.folded;
                c.folded = self_intersecting_faces(c.embedded);
            }
            // Beyond the paper: a thread whose embedding tore it (an old thread's part beyond the
            // patch, where it lies on the surface, joined to a part in the frame that the map puts
            // elsewhere) has faces stretched into a fan: a new one is cut clear of them, as of a
            // fold; a stitched or deformed old one is refused (the old thread stays; a stitch's new
            // partner goes in cut clear of it, below).
            if (quilt::is_elongated(ch.mesh))
                if (const std::vector<char> torn = stretched_faces(ch.mesh, c.embedded); !torn.empty()) {
                    ++b.torn;
                    if (c.folded.empty()) c.folded.assign(torn.size(), 0);
                    for (std::size_t f = 0; f < torn.size() && f < c.folded.size(); ++f) c.folded[f] = static_cast<char>(c.folded[f] | torn[f]);
                }
            // An element the plan shrank below kMinElementSize (a stitched or squeezed ring) goes in
            // at kGrowBackSize of its size, if it fits so (too_small refuses it otherwise).
            if (const int of = ch.source >= 0 || ch.old_id < 0 ? ch.source : elems_[static_cast<std::size_t>(ch.old_id)].source;
                !thread && too_small(c.embedded, of, local)) {
                const double f = c.resize * kGrowBackSize / std::max(element_size(c.embedded, of, local), 1e-3);
                std::vector<SurfacePoint> a2;
                Mesh e2;
                if (ch_place_sized(resized_in_frame(ch.mesh, f), of, false, nullptr, &a2, &e2) && !ch_folded(e2)) {
                    c.anchors = std::move(a2);
                    c.embedded = std::move(e2);
                    c.resize = f;
                    ++b.enlarged;
                }
            }
            if (!ch.fallback.faces.empty() &&
                !(ch_place_sized(ch.fallback, ch.source, true, nullptr, &c.fallback_anchors, &c.fallback, &c.fallback_resize) && !ch_folded(c.fallback)))
                c.fallback = Mesh();
            b.placed = true;
        });
        std::vector<Candidate> pending;
        std::vector<const Mesh*> applied;  // frame meshes of the changes applied, for nudging
        for (Built& b : built) {
            surface_.elements_folded += b.folded;
            surface_.threads_torn += b.torn;
            surface_.elements_enlarged += b.enlarged;
            if (b.placed) pending.push_back(std::move(b.c));
        }
        // Beyond the paper: an added blob keeps the swatch's clearance from the old elements around it,
        // as in the planar stage; one that does not goes to nudging. (Without it, pebbles came out up
        // to 19% denser than the swatch on the eight.) Where the patch's map shrinks ground, the
        // element goes in enlarged in the frame (embed_sized) and the clearance it needs there grows
        // with it: both are measured at that scale.
        std::vector<const Mesh*> around;
        for (const auto& oe : old) around.push_back(&oe.mesh);
        for (const Mesh& m : obstacles) around.push_back(&m);
        std::deque<Mesh> dented;  // frame meshes of threads dented clear (dent_clear), for nudging
        std::set<int> removed;    // collider ids of the old elements removed so far (a thread's dent is tried again only when one it met is gone)
        auto ignored = [&](const Candidate& c) {
            std::vector<int> ignore;
            if (c.change->old_id >= 0) ignore.push_back(elems_[static_cast<std::size_t>(c.change->old_id)].collider_id);
            return ignore;
        };
        // The collision tests below run in order, each seeing what the ones before put in. What a
        // candidate meets of the elements there before any went in is asked first, of all in
        // parallel; in the loop, only whether those are still there, and what went in since
        // (ElementCollider::colliding says why the answers are the same).
        const int since = collider_.next_id();
        tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t i) {
            Candidate& c = pending[i];
            const std::vector<int> ignore = ignored(c);
            c.hits = collider_.colliding(c.embedded, ignore);
            c.hits_known = true;
            if (!c.fallback.faces.empty() && !c.hits.empty()) {
                c.fallback_hits = collider_.colliding(c.fallback, ignore);
                c.fallback_hits_known = true;
            }
            // A new thread that meets something is cut clear of it (trim_thread, below, which ignores
            // nothing).
            if (c.change->kind == Kind::Added && quilt::is_elongated(c.change->mesh) && ignore.empty()) {
                c.hit_faces = c.hits.empty() ? std::vector<char>(c.embedded.faces.size(), 0) : collider_.colliding_faces(c.embedded);
                c.faces_known = true;
            }
        });
        auto still = [&](const std::vector<int>& hits) { return std::any_of(hits.begin(), hits.end(), [&](int id) { return collider_.contains(id); }); };
        auto collides_now = [&](const Mesh& m, bool known, const std::vector<int>& hits, const std::vector<int>& ignore) {
            return known ? still(hits) || collider_.collides(m, ignore, since) : collider_.collides(m, ignore);
        };
        for (int pass = 0; pass < 4 && !pending.empty(); ++pass) {
            std::vector<Candidate> refused;
            const std::size_t before = pending.size();
            for (auto& c : pending) {
                const auto* ch = c.change;
                if (!c.folded.empty()) {
                    refused.push_back(std::move(c));
                    continue;
                }
                if (ch->kind == Kind::Added && !keeps_clearance(resized_in_frame(ch->mesh, c.resize), ch->source, around, nullptr, c.resize)) {
                    refused.push_back(std::move(c));
                    continue;
                }
                const std::vector<int> ignore = ignored(c);
                Kind kind = ch->kind;
                const std::vector<Tri>* faces = &ch->mesh.faces;
                std::vector<SurfacePoint>* anchors = &c.anchors;
                Mesh* embedded = &c.embedded;
                const int of = ch->source >= 0 || ch->old_id < 0 ? ch->source : elems_[static_cast<std::size_t>(ch->old_id)].source;
                const bool dent_again =
                    c.dent_hit.empty() || std::any_of(c.dent_hit.begin(), c.dent_hit.end(), [&](int id) { return removed.count(id) > 0; });
                if (dent_again && c.folded.empty() && quilt::is_elongated(ch->mesh) && !off_size(c.embedded, of, local) &&
                    collides_now(c.embedded, c.hits_known, c.hits, ignore)) {
                    if (c.hits_known) {
                        c.dent_hit.clear();
                        for (int id : c.hits)
                            if (collider_.contains(id)) c.dent_hit.push_back(id);
                        const std::vector<int> more = collider_.colliding(c.embedded, ignore, since);
                        c.dent_hit.insert(c.dent_hit.end(), more.begin(), more.end());
                    } else {
                        c.dent_hit = collider_.colliding(c.embedded, ignore);
                    }
                    const auto r = reach_.find(ch->old_id);
                    const Reach* at = ch->old_id >= 0 && r != reach_.end() ? &r->second : nullptr;
                    Mesh frame;
                    std::vector<SurfacePoint> dent_anchors;
                    Mesh dent_embedded;
                    if (dent_clear(ch->mesh, ch->source, kind == Kind::Added || kind == Kind::Replaced, at, ignore, c.embedded, flat, locator, hs, local, &frame,
                                   &dent_anchors, &dent_embedded)) {
                        dented.push_back(std::move(frame));
                        c.anchors = std::move(dent_anchors);
                        c.embedded = std::move(dent_embedded);
                        c.dented = &dented.back();
                        c.hits_known = c.faces_known = false;
                        ++surface_.threads_dented;
                    }
                }
                if (collides_now(c.embedded, c.hits_known, c.hits, ignore) || off_size(c.embedded, of, local)) {
                    // A thread's whole partner would replace the old thread, parts beyond the patch
                    // included: it is cut clear of the old one instead (below).
                    const bool thread_partner = kind == Kind::Stitched && quilt::is_elongated(ch->fallback);
                    if (c.fallback.faces.empty() || thread_partner || collides_now(c.fallback, c.fallback_hits_known, c.fallback_hits, ignore) ||
                        off_size(c.fallback, of, local)) {
                        refused.push_back(std::move(c));
                        continue;
                    }
                    faces = &ch->fallback.faces;
                    anchors = &c.fallback_anchors;
                    embedded = &c.fallback;
                    if (kind != Kind::Added) kind = Kind::Replaced;  // an addition's fallback is the element squeezed
                }
                int source = ch->source;
                // A strand stitched to another length, or a piece deformed, is cut (SurfElement::cut).
                bool cut = false;
                if (kind != Kind::Added) {
                    if (source < 0) source = elems_[static_cast<std::size_t>(ch->old_id)].source;
                    cut = (kind == Kind::Stitched && quilt::is_strand_source(sw_, source)) ||
                          (kind != Kind::Replaced && elems_[static_cast<std::size_t>(ch->old_id)].cut);
                    removed.insert(elems_[static_cast<std::size_t>(ch->old_id)].collider_id);
                    remove_element(ch->old_id);
                    if (kind == Kind::Stitched) ++report_.elements_stitched;
                    if (kind == Kind::Replaced) ++report_.elements_replaced;
                }
                const Mesh* frame_mesh = faces == &ch->fallback.faces ? &ch->fallback : c.dented ? c.dented : &ch->mesh;
                add_element(std::move(*anchors), *faces, std::move(*embedded), source, cut);
                if (kind == Kind::Added && ch >= plan.changes.data() + plan.squeezed_from && ch < plan.changes.data() + plan.squeezed_from + plan.squeezed)
                    ++report_.losers_kept;
                applied.push_back(frame_mesh);
            }
            if (refused.size() == before) {
                pending = std::move(refused);
                break;
            }
            pending = std::move(refused);
        }
        // Beyond the paper: a new thread without partner that collides keeps its parts clear of
        // what it meets, capped flat (quilt/trim.h), instead of leaving a bald strip a swatch long.
        std::deque<Mesh> pieces_applied;
        {
            std::vector<Candidate> kept;
            for (auto& c : pending) {
                if (c.change->kind == Kind::Added && quilt::is_elongated(c.change->mesh)) {
                    std::vector<char> bad;
                    if (c.faces_known && !still(c.hits)) {
                        bad = collider_.colliding_faces(c.embedded, {}, static_cast<std::size_t>(-1), since);
                    } else if (c.faces_known && std::all_of(c.hits.begin(), c.hits.end(), [&](int id) { return collider_.contains(id); })) {
                        bad = collider_.colliding_faces(c.embedded, {}, static_cast<std::size_t>(-1), since);
                        for (std::size_t f = 0; f < bad.size(); ++f) bad[f] = static_cast<char>(bad[f] | c.hit_faces[f]);
                    } else {
                        bad = collider_.colliding_faces(c.embedded);
                    }
                    if (trim_thread(c.change->mesh, c.change->source, std::move(bad), c.resize, place, &pieces_applied, c.folded)) continue;
                }
                // A strand (knot work), new or a merge's loser, goes in as its pieces cut across it
                // clear of what it meets (trim_strand), as an under-crossing stops short.
                if (c.change->kind == Kind::Added && quilt::is_strand_source(sw_, c.change->source)) {
                    std::vector<const Mesh*> near = around;
                    near.insert(near.end(), applied.begin(), applied.end());
                    for (const Mesh& m : pieces_applied) near.push_back(&m);
                    if (trim_strand(c.change->mesh, c.change->source, c.embedded, c.resize, place, near, &pieces_applied, c.folded)) continue;
                }
                // A stitch of two threads that collides, and whose new partner whole collides too:
                // the old thread stays, the partner's parts clear of it and of the rest go in.
                if (c.change->kind == Kind::Stitched && !c.fallback.faces.empty() && quilt::is_elongated(c.change->fallback) &&
                    trim_thread(c.change->fallback, c.change->source, collider_.colliding_faces(c.fallback), c.fallback_resize, place, &pieces_applied))
                    continue;
                kept.push_back(std::move(c));
            }
            pending = std::move(kept);
        }
        for (const Mesh& m : pieces_applied) applied.push_back(&m);
        // Beyond the paper: a new element without partner that collides (on a doubly curved base
        // the lattices of neighbouring patches meet at small angles, and interlocked rings then
        // touch) tries small moves in the frame: 8 directions at half and one mean edge length,
        // the first that fits is taken. A blob (genus 0) must also keep the swatch's clearance
        // from the elements around it, or nudging would squeeze it into a gap the swatch never
        // leaves that narrow; a ring interlocks, and comes closer where the lattice bends.
        std::vector<const Mesh*> standing;
        for (const auto& oe : old) standing.push_back(&oe.mesh);
        for (const Mesh& m : obstacles) standing.push_back(&m);
        standing.insert(standing.end(), applied.begin(), applied.end());
        std::vector<Candidate> unplaced;
        for (auto& c : pending) {
            if (c.change->kind != Kind::Added || !nudge(*c.change, standing, place_sized, local)) unplaced.push_back(std::move(c));
        }
        pending = std::move(unplaced);
        for (const auto& c : pending) {
            if (c.change->kind == Kind::Stitched) ++report_.stitch_failures;
            else if (c.change->kind != Kind::Deformed) ++report_.collisions_avoided;
        }
    }

    /// A thread's piece that fits: its frame mesh, anchors and embedding.
    struct PieceFit {
        Mesh frame;
        std::vector<SurfacePoint> anchors;
        Mesh embedded;
    };

    /// The pieces of thread `frame` (a frame mesh of swatch element `source`, at its size on the
    /// surface) clear of its faces flagged `bad`: cut kTrimMargin of its width clear, at least
    /// kTrimMinLength widths long (so they stay threads for later patches), each embedded again by
    /// `place` (no resizing), colliding with nothing, not folding and not torn (stretched_faces).
    /// Nothing is added.
    template <class Place>
    std::vector<PieceFit> clear_pieces(const Mesh& frame, int source, const std::vector<char>& bad, const Place& place) const {
        const Vec3 size = bounding_box(frame).size();
        const double width = std::min(size.x(), size.y());
        quilt::ThreadCut cut;
        cut.margin = kTrimMargin * width;
        cut.min_length = kTrimMinLength * width;
        std::vector<PieceFit> out;
        for (Mesh& piece : quilt::thread_pieces(frame, bad, cut)) {
            PieceFit fit;
            if (!quilt::is_elongated(piece)) continue;  // a thread's shorter piece (its waviness widens it) is not one
            if (!place(piece, source, false, &fit.anchors, &fit.embedded, nullptr)) continue;
            if (!stretched_faces(piece, fit.embedded).empty() || collider_.collides(fit.embedded)) continue;
            fit.frame = std::move(piece);
            out.push_back(std::move(fit));
        }
        return out;
    }

    /// Adds `fits` (pieces of swatch element `source`) to the output and their frame meshes to `frames`.
    void add_pieces(std::vector<PieceFit> fits, int source, std::deque<Mesh>* frames) {
        for (PieceFit& fit : fits) {
            add_element(std::move(fit.anchors), fit.frame.faces, std::move(fit.embedded), source);
            frames->push_back(std::move(fit.frame));
            ++surface_.thread_pieces;
        }
    }

    /// Adds the pieces of new thread `mesh` (frame mesh of swatch element `source`, resized by
    /// `resize` in the frame) that stay clear of the output (clear_pieces): cut where its faces
    /// collide (`bad`: per face of its embedding, 1 where it meets the output) or are `folded`. Adds
    /// the pieces' frame meshes to `frames`; true when any went in.
    template <class Place>
    bool trim_thread(const Mesh& mesh, int source, std::vector<char> bad, double resize, const Place& place, std::deque<Mesh>* frames,
                     const std::vector<char>& folded = {}) {
        for (std::size_t f = 0; f < folded.size() && f < bad.size(); ++f) bad[f] = static_cast<char>(bad[f] | folded[f]);
        if (std::none_of(bad.begin(), bad.end(), [](char b) { return b != 0; })) return false;
        std::vector<PieceFit> fits = clear_pieces(resized_in_frame(mesh, resize), source, bad, place);
        if (fits.empty()) return false;
        ++surface_.threads_trimmed;
        add_pieces(std::move(fits), source, frames);
        return true;
    }

    /// The pieces of strand `frame` (a frame mesh of swatch element `source`, at its size on the
    /// surface; quilt::strand_pieces) clear of its faces flagged `bad` and of the faces that come
    /// closer than the clearance `gap` to any of `standing` (frame meshes): cut half the clearance
    /// beyond them, at least quilt::kStrandPieceGirths strand girths long, each embedded again by
    /// `place` (no resizing), colliding with nothing, not folding, not torn, and keeping half the
    /// clearance. None when the faces left unflagged hold less than `min_share` of its area (no
    /// pieces could hold more). Nothing is added.
    template <class Place>
    std::vector<PieceFit> clear_strand_pieces(const Mesh& frame, int source, std::vector<char> bad, const std::vector<const Mesh*>& standing,
                                              double gap, const Place& place, double min_share = 0.0) const {
        const std::vector<char> close = quilt::faces_near(frame, standing, gap);
        for (std::size_t f = 0; f < close.size() && f < bad.size(); ++f) bad[f] = static_cast<char>(bad[f] | close[f]);
        std::vector<PieceFit> out;
        if (std::none_of(bad.begin(), bad.end(), [](char b) { return b != 0; })) return out;
        if (min_share > 0.0 && quilt::unflagged_area(frame, bad) < min_share * mesh_area(frame)) return out;
        quilt::ThreadCut cut;
        cut.margin = 0.5 * gap;
        cut.min_girths = quilt::kStrandPieceGirths;
        for (Mesh& piece : quilt::strand_pieces(frame, bad, cut)) {
            PieceFit fit;
            if (!place(piece, source, false, &fit.anchors, &fit.embedded, nullptr)) continue;
            if (!stretched_faces(piece, fit.embedded).empty() || collider_.collides(fit.embedded) || count_self_intersections(fit.embedded, 1) > 0) continue;
            const Box3 pb = bounding_box(piece);
            if (std::any_of(standing.begin(), standing.end(), [&](const Mesh* o) { return quilt::element_gap(piece, pb, *o, gap) < 0.5 * gap; })) continue;
            fit.frame = std::move(piece);
            out.push_back(std::move(fit));
        }
        return out;
    }

    /// Adds the pieces of new strand `mesh` (frame mesh of swatch element `source`, embedded as
    /// `embedded`, resized by `resize` in the frame) that stay clear of the output and of `standing`
    /// (clear_strand_pieces): cut where its faces collide, are `folded`, or come closer than the
    /// clearance. Adds the pieces' frame meshes to `frames`; true when any went in.
    template <class Place>
    bool trim_strand(const Mesh& mesh, int source, const Mesh& embedded, double resize, const Place& place, const std::vector<const Mesh*>& standing,
                     std::deque<Mesh>* frames, const std::vector<char>& folded = {}) {
        if (!(sw_.near_gap > 0.0)) return false;
        std::vector<char> bad = collider_.colliding_faces(embedded);
        for (std::size_t f = 0; f < folded.size() && f < bad.size(); ++f) bad[f] = static_cast<char>(bad[f] | folded[f]);
        std::vector<PieceFit> fits = clear_strand_pieces(resized_in_frame(mesh, resize), source, std::move(bad), standing, resize * sw_.near_gap, place);
        if (fits.empty()) return false;
        for (PieceFit& fit : fits) {
            add_element(std::move(fit.anchors), fit.frame.faces, std::move(fit.embedded), source, true);
            frames->push_back(std::move(fit.frame));
            ++report_.strand_pieces;
        }
        return true;
    }

    /// Does frame mesh `m` of swatch element `source` keep the swatch's clearance (near_gap, vertex
    /// to vertex) from each of `standing` other than `self`? Rings (genus >= 1) interlock and threads
    /// cross: they are not held to it.
    bool keeps_clearance(const Mesh& m, int source, const std::vector<const Mesh*>& standing, const Mesh* self = nullptr, double scale = 1.0) const {
        if ((source >= 0 && sw_.element_genus[static_cast<std::size_t>(source)] > 0) || !(sw_.near_gap > 0.0) || quilt::is_elongated(m))
            return true;
        const Box3 box = bounding_box(m);
        const double gap = scale * sw_.near_gap;
        for (const Mesh* o : standing)
            if (o != self && !o->faces.empty() && !quilt::keeps_gap(quilt::element_gap(m, box, *o, gap), gap)) return false;
        return true;
    }

    /// Is `embedded`, an element of swatch element `source` placed with local scale `local`,
    /// smaller than kMinElementSize of its swatch element's size? The kernel may deform or squeeze
    /// an element, and a lowered shell flattens it; embed_sized undoes only what the map did. (On
    /// the armadillo 24 of 5,041 rings came out below 1/1.5, down to 0.39, from the patches' plans
    /// in its hands and feet.) Threads are left out: they are cut and stitched to any length. With
    /// a user height (--height) the element's thickness is not the swatch's, nor is its area.
    bool too_small(const Mesh& embedded, int source, double local) const {
        const double size = element_size(embedded, source, local);
        return size >= 0.0 && size < kMinElementSize;
    }
    /// ... or larger than kMaxElementSize of it.
    bool off_size(const Mesh& embedded, int source, double local) const {
        const double size = element_size(embedded, source, local);
        return size >= 0.0 && (size < kMinElementSize || size > kMaxElementSize);
    }
    /// ... its size as a share of its swatch element's (the square root of the area ratio); -1 where
    /// too_small does not apply.
    double element_size(const Mesh& embedded, int source, double local) const { return size_share(mesh_area(embedded), source, local); }
    /// ... of an element of area `area`.
    double size_share(double area, int source, double local) const {
        if (source < 0 || height_scale_ > 0) return -1.0;
        const Mesh& src = sw_.elements[static_cast<std::size_t>(source)];
        if (quilt::is_elongated(src)) return -1.0;
        const double want = mesh_area(src) * scale_ * scale_ * local * local;
        return want > 0.0 ? std::sqrt(area / want) : -1.0;
    }

    /// `m` scaled by `f` in xy about its area centroid (as embed_sized resizes it).
    static Mesh resized_in_frame(const Mesh& m, double f) {
        if (f == 1.0) return m;
        Mesh out = m;
        const Vec3 c = area_centroid(m);
        for (Vec3& v : out.vertices) v = Vec3(c.x() + f * (v.x() - c.x()), c.y() + f * (v.y() - c.y()), v.z());
        return out;
    }

    /// Tries the small moves of a colliding addition (see apply); true when one was added.
    template <class PlaceSized>
    bool nudge(const quilt::PatchPlan::Change& ch, const std::vector<const Mesh*>& standing, const PlaceSized& place_sized, double local) {
        const Mesh& m = ch.mesh;
        // Threads are left as they are: a move of a long element meets the threads it crosses as
        // often as not, and each try embeds and tests the whole thread (Bunny + Weave took twice
        // as long for 10% more elements).
        if (quilt::is_elongated(m)) return false;
        auto keeps_gap = [&](const Mesh& moved) { return keeps_clearance(moved, ch.source, standing, &m); };
        for (int radius = 1; radius <= 2; ++radius)
            for (int dir = 0; dir < 8; ++dir) {
                const double r = 0.5 * radius * sw_.mean_edge, a = dir * 0.7853981633974483;  // dir * 45 degrees
                const Vec3 d(r * std::cos(a), r * std::sin(a), 0.0);
                Mesh moved = m;
                for (Vec3& v : moved.vertices) v += d;
                std::vector<SurfacePoint> anchors;
                Mesh embedded;
                // The collision test first: most moves fail it, and it costs less than the others.
                if (!place_sized(moved, ch.source, true, &anchors, &embedded) || collider_.collides(embedded, {}) || off_size(embedded, ch.source, local) ||
                    !keeps_gap(moved) || count_self_intersections(embedded, 1) > 0)
                    continue;
                add_element(std::move(anchors), m.faces, std::move(embedded), ch.source);
                ++surface_.elements_nudged;
                return true;
            }
        return false;
    }

    void add_element(std::vector<SurfacePoint> anchors, const std::vector<Tri>& faces, Mesh embedded, int source, bool cut = false) {
        SurfElement e;
        e.cut = cut;
        e.anchors = std::move(anchors);
        e.faces = faces;
        e.source = source;
        e.alive = true;
        e.collider_id = collider_.add(embedded);
        if (is_ring_source(source)) e.centerline = ring_centerline(embedded);
        e.embedded = std::move(embedded);
        for (const SurfacePoint& sp : e.anchors) e.base_faces.push_back(sp.face);
        std::sort(e.base_faces.begin(), e.base_faces.end());
        e.base_faces.erase(std::unique(e.base_faces.begin(), e.base_faces.end()), e.base_faces.end());
        const int id = static_cast<int>(elems_.size());
        for (int f : e.base_faces) elems_on_face_[static_cast<std::size_t>(f)].push_back(id);
        elems_.push_back(std::move(e));
    }

    /// Beyond the paper: where two patches meet, each keeps its elements up to the swatch's
    /// smallest gap from the other's (keeps_clearance), so a seam packs free elements at that gap
    /// where the swatch has them at its typical spacing, and seams crossing one another leave spots
    /// denser than the swatch (pebbles on the eight: 4-7% of the elements stood closer to one of
    /// another patch than 0.8 of the swatch's closest pair, and the densest regions by count read
    /// 1.11-1.17 at seeds 1-3). After the last patch, every free element's window (a ball holding kThinWindow
    /// footprints of base area at its local scale) is measured as the report counts: its elements'
    /// swatch area over the window's base area, over the swatch's density. While a window holds more
    /// than kThinCap, its most crowded element (nearest element centre over the swatch's typical
    /// nearest spacing, below 1) goes, unless a window it stands in would fall below kThinFloor.
    /// Only free blobs (no rings, threads, strands, layered scales or pavings, whose elements keep
    /// a lattice a removal would break).
    void thin_dense_spots() {
        if (!rigid_frames_ || sw_.layered || joints_.paving || !sw_.elements_disjoint || sw_.elements.size() < 2) return;
        const double mx = kDensityInset * sw_.box.size().x(), my = kDensityInset * sw_.box.size().y();
        const double count_density = quilt::window_density(sw_.mesh, mx, my, sw_.box.size().x() - mx, sw_.box.size().y() - my);
        if (!(count_density > 0.0)) return;
        // The swatch's typical nearest spacing: the median over its elements of the distance from
        // an element's area centroid (xy) to the nearest other's.
        std::vector<Vec2> sc;
        std::vector<double> source_area;
        for (const Mesh& m : sw_.elements) {
            sc.push_back(area_centroid(m).head<2>());
            source_area.push_back(mesh_area(m));
        }
        std::vector<double> nearest_in_swatch;
        for (std::size_t i = 0; i < sc.size(); ++i) {
            double best = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < sc.size(); ++j)
                if (j != i) best = std::min(best, (sc[i] - sc[j]).norm());
            nearest_in_swatch.push_back(best);
        }
        std::nth_element(nearest_in_swatch.begin(), nearest_in_swatch.begin() + static_cast<std::ptrdiff_t>(nearest_in_swatch.size() / 2),
                         nearest_in_swatch.end());
        const double spacing = nearest_in_swatch[nearest_in_swatch.size() / 2];
        if (!(spacing > 0.0) || !std::isfinite(spacing)) return;
        const double fp = sw_.box.size().x() * sw_.box.size().y();
        // Elements: their centres on the base, swatch area at the scale, local scale.
        struct Item {
            int id = -1;
            Vec3 at = Vec3::Zero();
            double weight = 0.0, local = 1.0, window = 0.0, area = 0.0, held = 0.0;
            bool free = false;
        };
        std::vector<Item> items;
        const TriangleIndex index(base_.mesh);
        // On an open base the strip along its boundary that whole elements cannot fill is left out
        // of the windows, its ground and the elements standing over it, as the report's regions
        // leave it out. Counted as ground, the bare strip held the windows by a rim down, below the
        // cap or near the floor, and a crowd along the rim stayed: the camelhead's neck with pebbles
        // at seed 1, a report region of 1.58 footprints at 1.228 by count, its windows at 0.93-1.14;
        // with the strip left out they read up to 1.225, and the region 1.158.
        const std::vector<char> strip = near_boundary(0.5 * element_diag_ * scale_);
        for (std::size_t id = 0; id < elems_.size(); ++id) {
            const SurfElement& e = elems_[id];
            if (!e.alive || e.source < 0 || e.embedded.faces.empty() || !(mesh_area(e.embedded) > 0.0)) continue;
            const Vec3 c = area_centroid(e.embedded);
            if (!c.allFinite()) continue;
            const auto hit = index.closest(c);
            if (hit.face < 0 || strip[static_cast<std::size_t>(hit.face)]) continue;
            Item it;
            it.id = static_cast<int>(id);
            it.at = hit.point;
            it.local = local_scale_[static_cast<std::size_t>(hit.face)];
            it.weight = source_area[static_cast<std::size_t>(e.source)] * scale_ * scale_ * it.local * it.local;
            it.window = std::sqrt(kThinWindow * fp / M_PI) * scale_ * it.local;
            it.free = !e.cut && quilt::is_blob_source(sw_, e.source);
            items.push_back(it);
        }
        if (items.size() < 2) return;
        double reach = 0.0;
        for (const Item& it : items) reach = std::max(reach, it.window);
        // Hash grids of base face centroids and of element centres, cells of the largest window.
        auto key = [&](const Vec3& p) {
            return std::array<long, 3>{std::lround(std::floor(p.x() / reach)), std::lround(std::floor(p.y() / reach)), std::lround(std::floor(p.z() / reach))};
        };
        std::map<std::array<long, 3>, std::vector<int>> faces_at, items_at;
        for (std::size_t f = 0; f < base_.mesh.faces.size(); ++f)
            if (!strip[f]) faces_at[key(base_.centroid[f])].push_back(static_cast<int>(f));
        for (std::size_t i = 0; i < items.size(); ++i) items_at[key(items[i].at)].push_back(static_cast<int>(i));
        auto around = [&](const std::map<std::array<long, 3>, std::vector<int>>& grid, const Vec3& p, auto&& visit) {
            const auto k = key(p);
            for (long dx = -1; dx <= 1; ++dx)
                for (long dy = -1; dy <= 1; ++dy)
                    for (long dz = -1; dz <= 1; ++dz) {
                        const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                        if (it != grid.end())
                            for (int v : it->second) visit(v);
                    }
        };
        std::vector<std::vector<int>> members(items.size());  // the items in each item's window
        std::vector<std::vector<int>> windows_of(items.size());  // the windows each item stands in
        tbb::parallel_for(std::size_t{0}, items.size(), [&](std::size_t i) {
            Item& it = items[i];
            const double r2 = it.window * it.window;
            around(faces_at, it.at, [&](int f) {
                if ((base_.centroid[static_cast<std::size_t>(f)] - it.at).squaredNorm() <= r2) it.area += base_.area[static_cast<std::size_t>(f)];
            });
            around(items_at, it.at, [&](int j) {
                if ((items[static_cast<std::size_t>(j)].at - it.at).squaredNorm() <= r2) members[i].push_back(j);
            });
        });
        for (std::size_t i = 0; i < items.size(); ++i) {
            for (int j : members[i]) {
                items[i].held += items[static_cast<std::size_t>(j)].weight;
                windows_of[static_cast<std::size_t>(j)].push_back(static_cast<int>(i));
            }
        }
        auto density = [&](const Item& it) { return it.area > 0.0 ? it.held / it.area / count_density : 0.0; };
        std::vector<char> gone(items.size(), 0);
        // How crowded an item is: the distance to the nearest other centre, over the swatch's spacing.
        auto crowding = [&](int i) {
            const Item& it = items[static_cast<std::size_t>(i)];
            double best = std::numeric_limits<double>::infinity();
            around(items_at, it.at, [&](int j) {
                if (j != i && !gone[static_cast<std::size_t>(j)]) best = std::min(best, (items[static_cast<std::size_t>(j)].at - it.at).norm());
            });
            return best / (spacing * scale_ * it.local);
        };
        // Windows over the cap, densest first (ties by element order: deterministic).
        std::set<std::pair<double, int>, std::greater<>> over;
        for (std::size_t i = 0; i < items.size(); ++i)
            if (items[i].free && density(items[i]) > kThinCap) over.emplace(density(items[i]), static_cast<int>(i));
        while (!over.empty()) {
            const int w = over.begin()->second;
            over.erase(over.begin());
            int pick = -1;
            double pick_crowding = 1.0;
            for (int j : members[static_cast<std::size_t>(w)]) {
                const Item& cand = items[static_cast<std::size_t>(j)];
                if (gone[static_cast<std::size_t>(j)] || !cand.free) continue;
                const double c = crowding(j);
                if (!(c < pick_crowding)) continue;
                const bool keeps_floor = std::all_of(windows_of[static_cast<std::size_t>(j)].begin(), windows_of[static_cast<std::size_t>(j)].end(), [&](int k) {
                    const Item& win = items[static_cast<std::size_t>(k)];
                    return gone[static_cast<std::size_t>(k)] || win.area <= 0.0 || (win.held - cand.weight) / win.area / count_density >= kThinFloor;
                });
                if (!keeps_floor) continue;
                pick = j;
                pick_crowding = c;
            }
            if (pick < 0) continue;  // nothing here can go
            gone[static_cast<std::size_t>(pick)] = 1;
            const int removed_id = items[static_cast<std::size_t>(pick)].id;
            remove_element(removed_id);
            ++surface_.elements_thinned;
            over.erase({density(items[static_cast<std::size_t>(pick)]), pick});
            for (int k : windows_of[static_cast<std::size_t>(pick)]) {
                Item& win = items[static_cast<std::size_t>(k)];
                const double before = density(win);
                win.held -= items[static_cast<std::size_t>(pick)].weight;
                if (gone[static_cast<std::size_t>(k)] || !win.free) continue;
                over.erase({before, k});
                if (density(win) > kThinCap) over.emplace(density(win), k);
            }
        }
    }

    void remove_element(int id) {
        SurfElement& e = elems_[static_cast<std::size_t>(id)];
        if (!e.alive) return;
        e.alive = false;
        collider_.remove(e.collider_id);
        for (int f : e.base_faces) {
            auto& b = elems_on_face_[static_cast<std::size_t>(f)];
            b.erase(std::remove(b.begin(), b.end(), id), b.end());
        }
        e = SurfElement();
    }

    /// Output vertices behind the base (on the inner side of the closest base face, deeper than 1%
    /// of the shell height), and the elements that have any: decoration cut into the base.
    void measure_below_base(const SurfaceQuiltResult& result) {
        const TriangleIndex index(base_.mesh);
        const double tolerance = 0.01 * surface_.shell_height;
        std::vector<char> below(result.mesh.vertices.size(), 0);
        // The side is judged by the pseudo-normal of the closest feature (Baerentzen and Aanaes
        // 2005): the face's normal inside it, the sum of the two faces' normals on an edge, the
        // angle-weighted normal at a vertex. A face's normal alone misjudges points near a sharp
        // ridge.
        auto angle_weighted = [&](int vertex) {
            Vec3 n = Vec3::Zero();
            for (int f : base_.vertex_faces[static_cast<std::size_t>(vertex)]) {
                const Tri& t = base_.mesh.faces[static_cast<std::size_t>(f)];
                int k = 0;
                while (t[k] != vertex) ++k;
                const Vec3& x = base_.mesh.vertices[static_cast<std::size_t>(vertex)];
                const Vec3 e1 = base_.mesh.vertices[static_cast<std::size_t>(t[(k + 1) % 3])] - x;
                const Vec3 e2 = base_.mesh.vertices[static_cast<std::size_t>(t[(k + 2) % 3])] - x;
                n += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * index.face_normal(f);
            }
            return n;
        };
        tbb::parallel_for(std::size_t{0}, below.size(), [&](std::size_t v) {
            const Vec3& p = result.mesh.vertices[v];
            const ClosestHit hit = index.closest(p);
            if (hit.face < 0 || hit.distance <= tolerance) return;
            const auto f = static_cast<std::size_t>(hit.face);
            constexpr double kOn = 1e-9;
            int zero = 0, one = 0;
            for (int k = 0; k < 3; ++k) {
                if (hit.bary[k] < kOn) ++zero;
                if (hit.bary[k] > 1.0 - kOn) one = k;
            }
            // Closest to an open boundary (an edge or corner of the rim): the point hangs over the
            // rim, where the base has no inside to cut into.
            auto on_rim = [&](int vertex) {
                for (int g : base_.vertex_faces[static_cast<std::size_t>(vertex)]) {
                    const Tri& t = base_.mesh.faces[static_cast<std::size_t>(g)];
                    for (int k = 0; k < 3; ++k)
                        if (base_.nb[static_cast<std::size_t>(g)][static_cast<std::size_t>(k)] < 0 && (t[k] == vertex || t[(k + 1) % 3] == vertex)) return true;
                }
                return false;
            };
            Vec3 n = index.face_normal(hit.face);
            if (zero == 1) {
                int k = 0;
                hit.bary.minCoeff(&k);
                const int g = base_.nb[f][static_cast<std::size_t>((k + 1) % 3)];
                if (g < 0) return;
                n += index.face_normal(g);
            } else if (zero >= 2) {
                if (on_rim(base_.mesh.faces[f][one])) return;
                n = angle_weighted(base_.mesh.faces[f][one]);
            }
            below[v] = (p - hit.point).dot(n) < 0;
        });
        std::vector<char> element(static_cast<std::size_t>(result.element_of_face.empty() ? 0 : result.element_of_face.back() + 1), 0);
        for (std::size_t f = 0; f < result.mesh.faces.size(); ++f)
            for (int k = 0; k < 3; ++k)
                if (below[static_cast<std::size_t>(result.mesh.faces[f][k])]) element[static_cast<std::size_t>(result.element_of_face[f])] = 1;
        surface_.vertices_below_base = static_cast<int>(std::count(below.begin(), below.end(), 1));
        // Heights beyond the shell (an element deformed taller than H and lifted off the base):
        // the shell map extrapolates them above the offset surface.
        surface_.vertices_above_shell = 0;
        if (shell_)
            for (const SurfacePoint& sp : result.anchors) surface_.vertices_above_shell += sp.height > surface_.shell_height * (1.0 + 1e-9);
        surface_.elements_below_base = static_cast<int>(std::count(element.begin(), element.end(), 1));
    }

    void finish(SurfaceQuiltResult& result) {
        auto t0 = Clock::now();
        std::vector<int> kept;
        for (std::size_t id = 0; id < elems_.size(); ++id) {
            const SurfElement& e = elems_[id];
            if (!e.alive) continue;
            const bool source_closed = e.source >= 0 && sw_.element_closed[static_cast<std::size_t>(e.source)];
            if (source_closed && !quilt::is_closed_oriented(e.embedded)) {
                ++report_.elements_removed;
                continue;
            }
            kept.push_back(static_cast<int>(id));
        }
        // Elements that still intersect another (the swatch's own did not) are removed, smaller first.
        std::vector<const Mesh*> kept_meshes;
        for (int id : kept) kept_meshes.push_back(&elems_[static_cast<std::size_t>(id)].embedded);
        std::vector<char> drop(kept.size(), 0);
        if (sw_.elements_disjoint) drop = quilt::intersecting_to_remove(kept_meshes);
        for (char d : drop) report_.elements_removed += d;
        std::vector<const Mesh*> final_meshes;
        for (std::size_t k = 0; k < kept.size(); ++k) {
            if (drop[k]) continue;
            const SurfElement& e = elems_[static_cast<std::size_t>(kept[k])];
            final_meshes.push_back(&e.embedded);
            result.source_element.push_back(e.source);
            result_cut_.push_back(e.cut);
            result.anchors.insert(result.anchors.end(), e.anchors.begin(), e.anchors.end());
            if (quilt::is_closed_oriented(e.embedded)) ++report_.elements_closed;
        }
        ElementMesh out = concatenate(final_meshes);
        result.mesh = std::move(out.mesh);
        result.element_of_face = std::move(out.element_of_face);
        result.base = base_.mesh;
        result.shell = shell_;
        measure_below_base(result);
        stage_seconds_["finish"] += seconds_since(t0);

        QualityReport& r = report_;
        r.faces = static_cast<int>(result.mesh.faces.size());
        r.vertices = static_cast<int>(result.mesh.vertices.size());
        r.elements = static_cast<int>(result.source_element.size());
        r.cell_size = cell_;
        const double mx = kDensityInset * sw_.box.size().x(), my = kDensityInset * sw_.box.size().y();
        // With --height the elements are stretched in height: compare with the swatch stretched alike.
        Mesh reference = sw_.mesh;
        if (height_scale_ > 0)
            for (Vec3& v : reference.vertices) v.z() *= height_scale_ / scale_;
        r.swatch_density = quilt::window_density(reference, mx, my, sw_.box.size().x() - mx, sw_.box.size().y() - my);
        r.output_density = mesh_area(result.mesh) / std::max(base_.total_area, 1e-300);
        for (const auto& [phase, n] : phase_count_) r.largest_translation_share = std::max(r.largest_translation_share, n);
        for (const auto& [stage, s] : stage_seconds_) r.seconds.emplace_back(stage, s);
        result.report = r;
        surface_.swatch_density = r.swatch_density;
        for (char p : processed_) surface_.base_faces_processed += p;
        surface_.elements_torn = static_cast<int>(torn_tries_.load());
        region_density(result);
        element_sizes(result);
        // A swatch too large for the base's features: every placement folded, collided or fell off
        // its patch. An empty decoration is no result; a very sparse one gets a warning.
        const double footprint = scale_ * std::max(sw_.box.size().x(), sw_.box.size().y());
        if (result.source_element.empty())
            throw InvalidInput("no element of the swatch fits on the base at this scale (a swatch footprint of " + num(footprint) +
                               " base units, the base's diagonal " + num(diagonal_) +
                               "): every placement folded, collided or reached off its patch where the base curves more tightly than the elements are "
                               "wide; choose a smaller --scale or --swatch-size");
        if (surface_.regions > 0 && surface_.region_density_min < kSparseWarning && sw_.spans_swatch())
            warnings_.push_back("the decoration is sparse: its thinnest region (around " + num(surface_.region_density_min_at) + ") holds " +
                                num(surface_.region_density_min) + " of the swatch's density, and the swatch's largest element covers " + num(sw_.largest_element_cover) +
                                " of its footprint: a connected net or lattice can only be placed whole, and two placements that overlap "
                                "cannot be merged, so a smaller --scale does not cover more (a swatch of separate elements, such as threads, "
                                "rings or tiles, covers fully)");
        else if (surface_.regions > 0 && surface_.region_density_min < kSparseWarning)
            warnings_.push_back("the decoration is sparse: its thinnest region (around " + num(surface_.region_density_min_at) + ") holds " +
                                num(surface_.region_density_min) + " of the swatch's density (its largest element is " + num(element_diag_ * scale_) +
                                " base units across, and few fit where the base's features are not much larger); a smaller --scale or --swatch-size covers more fully");
        result.surface = surface_;
        result.warnings = warnings_;
        if (r.elements_removed > 0)
            result.warnings.push_back(std::to_string(r.elements_removed) + " element(s) could not be made whole or intersected others and were removed");
        if (sw_.thinned > 0.0) thicken(result);
    }

    /// A thinned swatch (SwatchData::thinned: its elements intersect, or its rings are tight): the
    /// output's elements are thickened back (quilt::thicken_output), after every measure (those
    /// compare thinned elements with the thinned swatch). Each element by the thinning times its
    /// own scale, the square root of its area over its swatch element's (both thinned); elements
    /// whose vertices no longer follow their swatch element's (stitched) take the median scale.
    /// `anchors` keep describing the thinned elements.
    void thicken(SurfaceQuiltResult& result) const {
        const auto t0 = Clock::now();
        const std::size_t n = result.source_element.size();
        std::vector<double> area(n, 0.0);
        std::vector<std::size_t> verts(n, 0);
        std::vector<char> seen(result.mesh.vertices.size(), 0);
        for (std::size_t f = 0; f < result.mesh.faces.size(); ++f) {
            const auto e = static_cast<std::size_t>(result.element_of_face[f]);
            area[e] += face_area(result.mesh, f);
            for (int k = 0; k < 3; ++k) {
                char& s = seen[static_cast<std::size_t>(result.mesh.faces[f][k])];
                verts[e] += s == 0;
                s = 1;
            }
        }
        std::vector<double> scale(n, 0.0), known;
        for (std::size_t e = 0; e < n; ++e) {
            const int s = result.source_element[e];
            if (s < 0) continue;
            const Mesh& src = sw_.elements[static_cast<std::size_t>(s)];
            const double a = quilt::mesh_area(src);
            if (src.vertices.size() != verts[e] || !(a > 0.0)) continue;
            scale[e] = std::sqrt(area[e] / a);
            known.push_back(scale[e]);
        }
        double median = scale_;
        if (!known.empty()) {
            std::nth_element(known.begin(), known.begin() + static_cast<std::ptrdiff_t>(known.size() / 2), known.end());
            median = known[known.size() / 2];
        }
        std::vector<double> offset(n);
        for (std::size_t e = 0; e < n; ++e) offset[e] = sw_.thinned * (scale[e] > 0.0 ? scale[e] : median);
        if (const int less = quilt::thicken_output(sw_, &result.mesh, result.element_of_face, offset); less > 0)
            result.warnings.push_back(std::to_string(less) + " of " + std::to_string(n) +
                                      " elements were thickened back less, since in full they would meet a neighbour the swatch's elements do not meet");
        result.report.seconds.emplace_back("thicken back", seconds_since(t0));
    }

    /// Per face: whether its centroid lies within `width` of the base's boundary (shortest paths
    /// between face centroids from the midpoints of boundary edges; an upper bound on the distance).
    std::vector<char> near_boundary(double width) const {
        const std::size_t F = base_.mesh.faces.size();
        std::vector<double> dist(F, std::numeric_limits<double>::infinity());
        using Item = std::pair<double, int>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        for (std::size_t f = 0; f < F; ++f)
            for (int k = 0; k < 3; ++k)
                if (base_.nb[f][static_cast<std::size_t>(k)] < 0) {
                    const Tri& t = base_.mesh.faces[f];
                    const Vec3 mid = 0.5 * (base_.mesh.vertices[static_cast<std::size_t>(t[k])] + base_.mesh.vertices[static_cast<std::size_t>(t[(k + 1) % 3])]);
                    const double d = (base_.centroid[f] - mid).norm();
                    if (d < dist[f]) {
                        dist[f] = d;
                        queue.emplace(d, static_cast<int>(f));
                    }
                }
        while (!queue.empty()) {
            const auto [d, f] = queue.top();
            queue.pop();
            if (d > dist[static_cast<std::size_t>(f)] || d >= width) continue;
            for (int g : base_.nb[static_cast<std::size_t>(f)]) {
                if (g < 0) continue;
                const double nd = d + (base_.centroid[static_cast<std::size_t>(g)] - base_.centroid[static_cast<std::size_t>(f)]).norm();
                if (nd < dist[static_cast<std::size_t>(g)]) {
                    dist[static_cast<std::size_t>(g)] = nd;
                    queue.emplace(nd, g);
                }
            }
        }
        std::vector<char> out(F, 0);
        for (std::size_t f = 0; f < F; ++f) out[f] = dist[f] < width;
        return out;
    }

    /// Each base face's area on the shell's middle surface, where the elements' middles lie: its
    /// corners mapped at half the shell's height (along the normals with --embed normal).
    std::vector<double> middle_areas() const {
        std::vector<double> mid(base_.mesh.faces.size(), 0.0);
        tbb::parallel_for(std::size_t{0}, base_.mesh.faces.size(), [&](std::size_t f) {
            std::array<Vec3, 3> p;
            for (int k = 0; k < 3; ++k) {
                SurfacePoint sp;
                sp.face = static_cast<int>(f);
                sp.bary = Vec3::Unit(k);
                sp.height = 0.5 * surface_.shell_height;
                p[static_cast<std::size_t>(k)] = embed(sp);
            }
            const double a = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
            mid[f] = std::isfinite(a) ? a : base_.area[f];
        });
        return mid;
    }

    /// Density per region: the base split into regions of about 4 footprints (farthest-point
    /// centres on face centroids, faces to the nearest centre); element faces count where they are
    /// anchored. A strip along the base's boundary half the largest element wide, which elements
    /// (whole, and on the base) cannot fill, is left out, as the tests' measure leaves it out. Regions
    /// with less than one footprint of area (small components, slivers at borders) are left out.
    /// Each region's element area is taken over its base area and over its area on the shell's
    /// middle surface (middle_areas).
    void region_density(const SurfaceQuiltResult& result) {
        const std::size_t F = base_.mesh.faces.size();
        const std::vector<char> strip = near_boundary(0.5 * element_diag_ * scale_);
        const double fp_area = sw_.box.size().x() * sw_.box.size().y() * scale_ * scale_;
        const int regions = std::clamp(static_cast<int>(base_.total_area / (4.0 * fp_area)), 1, 64);
        std::vector<Vec3> centres{base_.centroid[0]};
        std::vector<double> d(F, std::numeric_limits<double>::infinity());
        std::vector<int> region(F, 0);
        for (int r = 0; r < regions; ++r) {
            std::size_t far = 0;
            for (std::size_t f = 0; f < F; ++f) {
                const double dd = (base_.centroid[f] - centres.back()).squaredNorm();
                if (dd < d[f]) {
                    d[f] = dd;
                    region[f] = r;
                }
                if (d[f] > d[far]) far = f;
            }
            if (r + 1 < regions) centres.push_back(base_.centroid[far]);
        }
        std::vector<double> base_area(static_cast<std::size_t>(regions), 0.0), elem_area(static_cast<std::size_t>(regions), 0.0),
            mid_area(static_cast<std::size_t>(regions), 0.0);
        std::vector<Vec3> middle(static_cast<std::size_t>(regions), Vec3::Zero());
        for (std::size_t f = 0; f < F; ++f)
            if (!strip[f]) {
                base_area[static_cast<std::size_t>(region[f])] += base_.area[f];
                mid_area[static_cast<std::size_t>(region[f])] += widening_[f] * base_.area[f];
                middle[static_cast<std::size_t>(region[f])] += base_.area[f] * base_.centroid[f];
            }
        for (std::size_t f = 0; f < result.mesh.faces.size(); ++f) {
            const int bf = result.anchors[static_cast<std::size_t>(result.mesh.faces[f][0])].face;
            if (strip[static_cast<std::size_t>(bf)]) continue;
            elem_area[static_cast<std::size_t>(region[static_cast<std::size_t>(bf)])] += face_area(result.mesh, f);
        }
        double lo = std::numeric_limits<double>::infinity(), hi = 0.0, mid_lo = lo, mid_hi = 0.0;
        int counted = 0, thinnest = -1;
        for (int r = 0; r < regions; ++r) {
            const auto k = static_cast<std::size_t>(r);
            if (base_area[k] < fp_area) continue;
            const double ratio = elem_area[k] / base_area[k] / std::max(surface_.swatch_density, 1e-300);
            if (ratio < lo) thinnest = r;
            lo = std::min(lo, ratio);
            hi = std::max(hi, ratio);
            const double mid_ratio = elem_area[k] / std::max(mid_area[k], 1e-300) / std::max(surface_.swatch_density, 1e-300);
            mid_lo = std::min(mid_lo, mid_ratio);
            mid_hi = std::max(mid_hi, mid_ratio);
            ++counted;
        }
        surface_.regions = counted;
        surface_.region_density_min = counted ? lo : 0.0;
        surface_.region_density_max = counted ? hi : 0.0;
        surface_.region_density_mid_min = counted ? mid_lo : 0.0;
        surface_.region_density_mid_max = counted ? mid_hi : 0.0;
        // A point of the base near region r's middle: the centroid of its face closest to the
        // region's area-weighted centre.
        auto point_of = [&](int r) {
            const Vec3 centre = middle[static_cast<std::size_t>(r)] / base_area[static_cast<std::size_t>(r)];
            double best = std::numeric_limits<double>::infinity();
            Vec3 at = Vec3::Zero();
            for (std::size_t f = 0; f < F; ++f)
                if (region[f] == r && !strip[f] && (base_.centroid[f] - centre).squaredNorm() < best) {
                    best = (base_.centroid[f] - centre).squaredNorm();
                    at = base_.centroid[f];
                }
            return at;
        };
        if (thinnest >= 0) surface_.region_density_min_at = point_of(thinnest);
        const auto [sparsest, densest] = region_count_density(result, region, strip, base_area, mid_area, fp_area);
        if (sparsest >= 0) surface_.region_count_density_min_at = point_of(sparsest);
        if (densest >= 0) surface_.region_count_density_max_at = point_of(densest);
    }

    /// region_density by count (SurfaceQualityReport::region_count_density_min): per region of
    /// `region` (faces in `strip` left out, regions under `min_area` of base area skipped), the
    /// swatch area of the elements standing over it at the run's scale, over its base area, over
    /// the swatch's density; the same over its area on the shell's middle surface (`mid_area`).
    /// Not measured (left 0) where an element is a thread or a cut piece. Returns the sparsest and
    /// the densest region per base area (-1 when not measured).
    std::pair<int, int> region_count_density(const SurfaceQuiltResult& result, const std::vector<int>& region, const std::vector<char>& strip,
                                             const std::vector<double>& base_area, const std::vector<double>& mid_area, double min_area) {
        const std::size_t n = result.source_element.size();
        if (n == 0) return {-1, -1};
        for (std::size_t e = 0; e < n; ++e)
            if ((e < result_cut_.size() && result_cut_[e]) || quilt::is_elongated(sw_.elements[static_cast<std::size_t>(result.source_element[e])]))
                return {-1, -1};
        // The swatch's density as the count sees it: its elements' area (unstretched by --height,
        // as the count weighs them) per area in the density window, each face where it lies. (Its
        // elements counted whole by their centres would quantise: the bundled mail has 20 of its
        // 36 rings centred in the window, and their parts there weigh 24.2 rings.)
        const double mx = kDensityInset * sw_.box.size().x(), my = kDensityInset * sw_.box.size().y();
        const double count_density = quilt::window_density(sw_.mesh, mx, my, sw_.box.size().x() - mx, sw_.box.size().y() - my);
        if (!(count_density > 0.0)) return {-1, -1};
        // Each element's centre on the base: its faces' feet (their corners at height 0),
        // area-weighted, then the closest point of the base.
        std::vector<Vec3> vertex_foot(result.anchors.size());
        tbb::parallel_for(std::size_t{0}, result.anchors.size(), [&](std::size_t v) {
            SurfacePoint sp = result.anchors[v];
            sp.height = 0.0;
            vertex_foot[v] = embed(sp);
        });
        std::vector<Vec3> foot(n, Vec3::Zero());
        std::vector<double> weight(n, 0.0);
        for (std::size_t f = 0; f < result.mesh.faces.size(); ++f) {
            const auto e = static_cast<std::size_t>(result.element_of_face[f]);
            const double a = face_area(result.mesh, f);
            const Tri& t = result.mesh.faces[f];
            const Vec3 c = (vertex_foot[static_cast<std::size_t>(t[0])] + vertex_foot[static_cast<std::size_t>(t[1])] + vertex_foot[static_cast<std::size_t>(t[2])]) / 3.0;
            if (!(a > 0.0) || !c.allFinite()) continue;
            foot[e] += a * c;
            weight[e] += a;
        }
        const TriangleIndex index(base_.mesh);
        std::vector<double> counted(base_area.size(), 0.0);
        for (std::size_t e = 0; e < n; ++e) {
            if (!(weight[e] > 0.0)) continue;
            const int f = index.closest(foot[e] / weight[e]).face;
            if (f < 0 || strip[static_cast<std::size_t>(f)]) continue;
            const double local = local_scale_[static_cast<std::size_t>(f)];
            counted[static_cast<std::size_t>(region[static_cast<std::size_t>(f)])] +=
                mesh_area(sw_.elements[static_cast<std::size_t>(result.source_element[e])]) * scale_ * scale_ * local * local;
        }
        double lo = std::numeric_limits<double>::infinity(), hi = 0.0, mid_lo = lo, mid_hi = 0.0;
        int sparsest = -1, densest = -1;
        for (std::size_t r = 0; r < base_area.size(); ++r) {
            if (base_area[r] < min_area) continue;
            const double ratio = counted[r] / base_area[r] / count_density;
            if (ratio < lo) sparsest = static_cast<int>(r);
            if (ratio > hi) densest = static_cast<int>(r);
            lo = std::min(lo, ratio);
            hi = std::max(hi, ratio);
            const double mid_ratio = counted[r] / std::max(mid_area[r], 1e-300) / count_density;
            mid_lo = std::min(mid_lo, mid_ratio);
            mid_hi = std::max(mid_hi, mid_ratio);
        }
        if (!(hi > 0.0)) return {-1, -1};
        surface_.region_count_density_min = lo;
        surface_.region_count_density_max = hi;
        surface_.region_count_density_mid_min = mid_lo;
        surface_.region_count_density_mid_max = mid_hi;
        return {sparsest, densest};
    }

    /// Each element's size as a share of its swatch element's at the run's scale and the field's
    /// local scale on its first vertex's base face (size_share, as the stage's size floor
    /// measures it): the smallest and largest, and how many lie outside a factor of
    /// kReportedSizeFactor. Threads (cut and stitched to any length), strands cut or stitched
    /// (SurfElement::cut; whole strands are measured) and a run with --height (the elements'
    /// thickness is not the swatch's) are not measured.
    void element_sizes(const SurfaceQuiltResult& result) {
        const std::size_t n = result.source_element.size();
        std::vector<double> area(n, 0.0);
        std::vector<int> face(n, -1);
        for (std::size_t f = 0; f < result.mesh.faces.size(); ++f) {
            const auto e = static_cast<std::size_t>(result.element_of_face[f]);
            area[e] += face_area(result.mesh, f);
            if (face[e] < 0) face[e] = result.anchors[static_cast<std::size_t>(result.mesh.faces[f][0])].face;
        }
        double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
        for (std::size_t e = 0; e < n; ++e) {
            if (face[e] < 0 || (e < result_cut_.size() && result_cut_[e])) continue;
            const double size = size_share(area[e], result.source_element[e], local_scale_[static_cast<std::size_t>(face[e])]);
            if (size < 0.0) continue;
            lo = std::min(lo, size);
            hi = std::max(hi, size);
            ++surface_.elements_sized;
            surface_.elements_off_size += size < 1.0 / kReportedSizeFactor || size > kReportedSizeFactor;
        }
        surface_.element_size_min = surface_.elements_sized ? lo : 0.0;
        surface_.element_size_max = surface_.elements_sized ? hi : 0.0;
    }

    /// make_frame's largest disc as a share of a patch's (0: a patch's); set by mend_threads for
    /// its smaller frames.
    double frame_cap_ = 0.0;
    /// The elements near mend_frame's frame (ids into elems_; grows as it mends), for the clearance
    /// of mended blobs.
    const std::vector<int>* mend_near_ = nullptr;

    /// Does `embedded` (a blob on the surface, placed with local scale `local`) keep the swatch's
    /// clearance (near_gap at that scale, vertex to vertex) from the standing elements mend_near_
    /// lists? (keeps_clearance measures frame meshes; a mended blob is tested once embedded.)
    bool keeps_clearance_3d(const Mesh& embedded, double local) const {
        if (!mend_near_ || !(sw_.near_gap > 0.0)) return true;
        const double gap = sw_.near_gap * scale_ * local;
        const Box3 box = bounding_box(embedded);
        for (int id : *mend_near_) {
            const SurfElement& e = elems_[static_cast<std::size_t>(id)];
            if (e.alive && !e.embedded.faces.empty() && !quilt::keeps_gap(quilt::element_gap(embedded, box, e.embedded, gap), gap)) return false;
        }
        return true;
    }
    SurfaceQuiltOptions opt_;
    quilt::SwatchData sw_;
    std::vector<char> result_cut_;  ///< per result element: a strand's piece (SurfElement::cut)
    TriangleIndex index_;
    quilt::KernelParams params_;
    quilt::FillSetup fill_;
    double ring_crowd_reference_ = -1.0;  ///< ring_crowd_reference (computed on first use)
    /// The swatch's threads running along x (0) and along y (1) (prepare_thread_sets).
    struct ThreadSet {
        std::vector<int> ids;  ///< swatch elements
        double spacing = 0.0;  ///< median distance between neighbouring centre lines
        double width = 0.0;    ///< median width
    };
    std::array<ThreadSet, 2> thread_sets_;
    quilt::JointSetup joints_;
    double cell_ = 1.0;
    int sx_ = 0, sy_ = 0, k_ = 0;
    int symmetry_ = 4;
    double element_diag_ = 0.0;  ///< largest swatch element's footprint diagonal, swatch units
    double largest_face_ = 0.0;  ///< the swatch's largest face area, swatch units (torn)
    mutable std::atomic<long> torn_tries_{0};  ///< tries torn refused
    std::vector<std::pair<Vec3, Vec3>> mend_failed_;  ///< slots tried in vain (mend_frame): base point, direction
    std::map<std::array<long, 3>, std::vector<std::size_t>> mend_failed_grid_;
    std::map<std::pair<int, int>, Mesh> variant_;                   ///< ring_variant
    std::map<std::pair<int, int>, quilt::SolidGrid> variant_solid_;  ///< solid_of
    std::map<std::pair<int, int>, double> variant_diameter_;         ///< diameter_of
    long hole_tries_ = 0, hole_budget_ = 0, hole_free_ = 0;  ///< fill_ring_holes: tries embedded, and at most (hole_budget)
    long tilt_tries_ = 0, tilt_free_ = 0;  ///< tilted tries embedded, and at most (tilt_budget)
    std::vector<Vec3> hole_failed_;  ///< ring holes tried in vain (fill_ring_holes): base points
    std::map<std::array<long, 3>, std::vector<std::size_t>> hole_failed_grid_;
    double mend_cell_ = 1.0;
    bool rings_ = false;  ///< the swatch has rings (is_ring_source): their lattices are continued and mended
    bool interlocked_ = false;  ///< ... and they interlock (chain mail): no ring may be left unlinked
    bool woven_ = false;        ///< the swatch has threads in both directions (a weave)
    bool rigid_frames_ = false;  ///< patches flattened as rigid as possible (see prepare_rigid_frames)
    bool has_threads_ = false;   ///< the swatch has threads (either direction): patch discs (make_frame) and shell charts (build_shell) grow with slits
    Mesh lattice_probe_;        ///< the swatch's middle, for fit_lattice_scale (chain mail, weaves)
    std::vector<int> ring_kind_;      ///< per swatch element: the first ring it is a translate of (-1: no ring)
    std::vector<int> ring_need_;      ///< per swatch element: links a ring of it keeps in the output (prepare_ring_need)
    std::vector<Vec2> ring_centre_;   ///< per swatch element: its area centroid (xy)
    double ring_spacing_ = 0.0;       ///< the swatch's ring spacing (quilt::RingLattice), 0 without interlocked rings
    double last_radius_ = 0.0;  ///< the last patch's radius, divided by its local scale
    std::shared_ptr<const ShellMap> shell_;
    double diagonal_ = 0.0, scale_ = 1.0, height_scale_ = 0.0, min_field_scale_ = 1.0;
    Base base_;
    std::vector<Vec3> direction_;
    std::vector<double> local_scale_;
    std::vector<double> widening_;  ///< per base face: its area on the shell's middle surface over its base area
    std::vector<char> processed_;
    std::vector<int> score_;
    std::vector<int> face_slot_;
    std::map<int, Reach> reach_;  ///< per old element id: its vertices carried beyond the current patch
    std::vector<Vec3> frame_dir_;  ///< per base face: +x of the frame of the patch that processed it
    std::vector<std::vector<int>> elems_on_face_;
    std::vector<SurfElement> elems_;
    ElementCollider collider_;
    std::mt19937_64 rng_;
    QualityReport report_;
    SurfaceQualityReport surface_;
    std::vector<std::string> warnings_;
    std::map<std::pair<int, int>, int> phase_count_;
    std::map<std::string, double> stage_seconds_;
};

}  // namespace

SurfaceQuiltResult quilt_surface(const Mesh& base, const Mesh& swatch, const SurfaceQuiltOptions& options) {
    SurfaceQuilter q(base, swatch, options);
    return q.run();
}

}  // namespace meshquilt
