// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file surface.h
/// Surface mesh quilting (Zhou et al. 2006, Section 3.1): cover an arbitrary triangle mesh (the
/// base) with a geometric texture grown from a swatch. The planar kernel runs in local patches of
/// the base flattened with LSCM, oriented by a direction field; output vertices are stored relative
/// to the base and embedded through the stretch-optimised shell map (Section 3.2, shellmap.h) or,
/// on request, by normal displacement.

#include "meshquilt/mesh.h"
#include "meshquilt/quilt.h"
#include "meshquilt/reporter.h"
#include "meshquilt/shellmap.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace meshquilt {

/// A user's guidance field (see docs/surface.md for the file format read by read_guidance_field).
/// Directions are tangent vectors in base coordinates; they are projected onto the faces. Their
/// length is the local scale factor (1: the scale given by the options). Faces without a value
/// get one by smooth interpolation.
struct GuidanceField {
    struct FaceValue {
        int face = -1;
        Vec3 vector = Vec3::Zero();
    };
    struct VertexValue {
        int vertex = -1;
        Vec3 vector = Vec3::Zero();
    };
    std::vector<FaceValue> faces;
    std::vector<VertexValue> vertices;
    /// Polylines drawn on (or near) the surface: the faces nearest their points are constrained to
    /// the stroke's direction there, with scale 1 (Lapped Textures, Praun et al. 2000).
    std::vector<std::vector<Vec3>> strokes;
    [[nodiscard]] bool empty() const { return faces.empty() && vertices.empty() && strokes.empty(); }
};

/// Reads a field file. \throw IoError unreadable; InvalidInput (with file:line) malformed
GuidanceField read_guidance_field(const std::string& path);

/// How texture space (base point, height) becomes 3D.
enum class Embedding {
    Shell,   ///< the stretch-optimised tetrahedral shell map (Section 3.2): heights limited where the
             ///< base is concave or narrow, no inversions
    Normal,  ///< displacement along interpolated vertex normals (cuts into concave regions)
};

/// The default of SurfaceQuiltOptions::scale: about 150 footprints on a compact shape.
inline constexpr double kDefaultScale = 0.08;

struct SurfaceQuiltOptions {
    /// Swatch footprint's longer side as a fraction of the base's bounding-box diagonal. Unset (and
    /// no `swatch_size`): kDefaultScale, raised where the output would hold more than
    /// `default_face_budget` faces (a dense swatch).
    std::optional<double> scale;
    /// With the scale left unset: the most output faces (estimated) the default scale may give; the
    /// footprint grows until the estimate fits, with a warning. A swatch of 300 packed spheres of 320
    /// faces each would give 22-32 million faces at 0.08 on the shared test meshes. 0: no budget.
    double default_face_budget = 4e6;
    /// Swatch footprint's longer side in base units; > 0 overrides `scale`.
    double swatch_size = 0.0;
    /// Shell height in base units; <= 0: the swatch's thickness at the chosen scale.
    double height = 0.0;
    /// Rotational symmetry of the swatch for the automatic field (1, 2, 4 or 6); 0: detect.
    int symmetry = 0;
    GuidanceField field;
    std::uint64_t seed = 1;
    double lambda = 1.0;
    double mu = 1.0;
    double tolerance = 0.1;
    Embedding embedding = Embedding::Shell;
    bool optimise_shell = true;  ///< run the shell map's stretch optimisation
    Reporter reporter;
};

/// Where an output vertex lives (texture space): a triangle of the (internally refined) base,
/// barycentric coordinates on it, and a height: with the shell map, the height in the shell
/// (0 .. shell height H; the shell map squeezes it where the offset is lower); with normal
/// displacement, the distance along the interpolated vertex normal.
struct SurfacePoint {
    int face = -1;
    Vec3 bary = Vec3::Zero();
    double height = 0.0;
};

struct SurfaceQualityReport {
    int base_faces = 0;            ///< faces of the base as used (after refinement)
    int base_faces_processed = 0;  ///< faces the synthesis reached (all, on success)
    int patches_shrunk = 0;        ///< patches made smaller because LSCM distorted area by more than 2 (98th over 2nd percentile)
    int patches_rigid = 0;         ///< patches of a swatch of free elements flattened again, as rigid as possible, from LSCM's map
    int frozen_elements_seen = 0;  ///< old elements reaching beyond a patch, treated as obstacles
    int threads_extended = 0;      ///< old threads reaching beyond a patch, handed to the kernel with their far part carried along
    int threads_trimmed = 0;       ///< new threads that collided, cut where they did; their free parts went in
    int thread_pieces = 0;         ///< pieces of trimmed threads that went in
    int threads_cut_at_patch = 0;  ///< new threads reaching off their patch whose parts on it were placed (pieces)
    int threads_filled = 0;        ///< threads laid into gaps where a direction's threads were missing (weave seams), whole or in pieces
    int threads_turned = 0;        ///< of threads_filled, those laid turned from the patch frame's axis to run with the threads beside their gap
    int threads_torn = 0;          ///< threads whose embedding stretched faces into a fan: cut clear of them (new) or refused (old)
    int threads_dented = 0;        ///< threads that grazed another element with a few faces, dented clear of it (a real thread flattens where pressed)
    int elements_torn = 0;         ///< tries of other elements refused where the embedding made a face over 4 times the swatch's largest
    int threads_mended = 0;        ///< of those, laid after the last patch (gaps left or opened by later patches)
    int gaps_closed = 0;           ///< paving stones grown radially into holes where several meet, after the last patch (included in joints_closed)
    int elements_folded = 0;       ///< placements left out because normal displacement folded the element
    int elements_nudged = 0;       ///< new elements that collided where placed and fit after a small move (at most a mean edge length)
    int elements_thinned = 0;      ///< free elements removed after the last patch from spots denser than the swatch (seams packed at its smallest gap; docs/surface.md, step 11)
    int elements_mended = 0;       ///< rings (or a layered swatch's scales) put into empty lattice slots after the last patch
    int ring_holes_filled = 0;     ///< of them, rings put into holes between lattices (off every lattice's slots)
    int ring_holes_tilted = 0;     ///< of those, rings tilted from their swatch ring's pose to fit
    int ring_holes_enlarged = 0;   ///< of those, rings put in at 1.1 of their swatch ring's size (reaching their neighbours' links)
    int rings_swapped = 0;         ///< lattice slots blocked by one ring of another lattice: that ring replaced by two of this one (each adds one ring)
    int elements_enlarged = 0;     ///< placed elements the patch's plan left below the size floor (0.7), enlarged to 0.85 of their size
    int rings_unlinked_removed = 0;  ///< interlocking swatches: rings that linked with no other ring, removed before mending
    int symmetry = 0;              ///< N of the N-direction field used
    double base_scale = 0.0;       ///< base units per swatch unit
    double scale = 0.0;            ///< the footprint's longer side used, over the base's bounding-box diagonal
    double swatch_density = 0.0;   ///< element area per footprint area in the swatch
    /// Element area per base area over a partition of the surface into regions of about 4 swatch
    /// footprints, divided by the swatch's: smallest and largest over regions.
    double region_density_min = 0.0;
    double region_density_max = 0.0;
    /// The same per area of the shell's middle surface (the base's faces mapped at half the
    /// shell's height), where the elements' middles lie: a decoration round a thin part stands on
    /// a wider surface than its base (the swatch's density is measured in the plane, where the two
    /// are one), and one in a hollow on a narrower.
    double region_density_mid_min = 0.0;
    double region_density_mid_max = 0.0;
    /// A point of the base near the middle of the thinnest region (the centroid of its face closest
    /// to the region's area-weighted centre): where to look first when the decoration is sparse.
    Vec3 region_density_min_at = Vec3::Zero();
    int regions = 0;
    /// Element density by count over the same regions: each element counted once, in the region
    /// of the base point under its centre (its faces' feet, area-weighted, closest point on the
    /// base), weighed by its swatch element's area at the run's and the field's scale, over the
    /// region's base area and the swatch's density (swatch_density's window, unstretched by
    /// --height as the count's weights are). Blind to what the shell does to an element's area (a lowered
    /// shell flattens rings; a thin part's wider middle surface enlarges them). 0 when not
    /// measured: threads and pieces of strands (cut to any length) have no count.
    double region_count_density_min = 0.0;
    double region_count_density_max = 0.0;
    /// The same count per area of the shell's middle surface (as region_density_mid_min): round
    /// a thin part an element embedded at its swatch size there stands on more surface than its
    /// base, so a decoration as dense as the swatch where it stands reads denser per base area.
    double region_count_density_mid_min = 0.0;
    double region_count_density_mid_max = 0.0;
    /// Points of the base near the middles of the sparsest and the densest region by count (per
    /// base area), as region_density_min_at.
    Vec3 region_count_density_min_at = Vec3::Zero();
    Vec3 region_count_density_max_at = Vec3::Zero();
    /// Each element's size over its swatch element's at the run's scale (and the guidance field's
    /// local scale): the square root of the area ratio, measured before a thinned swatch's
    /// elements are thickened back. Threads and runs with a user height are not measured.
    double element_size_min = 0.0;
    double element_size_max = 0.0;
    int elements_sized = 0;     ///< elements measured
    int elements_off_size = 0;  ///< of them, smaller than 1/1.5 or larger than 1.5 times their swatch element
    int base_flipped_components = 0;  ///< inside-out components flipped for the synthesis
    /// Shell embedding: vertices on folds of the base (no direction sees all their faces) moved to
    /// their neighbours' mean on the synthesis's copy of the base.
    int base_fold_vertices_smoothed = 0;
    /// Base faces in regions remeshed on the synthesis's copy because of thin faces (smallest angle
    /// under 10 degrees, longer than a quarter cell, in clusters of half a footprint or more: the
    /// slivers of CAD fans or CSG), with one ring of faces around them; their vertices stay on the
    /// base's surface.
    int base_thin_faces_remeshed = 0;
    /// Holes of the base (boundary loops) filled on the synthesis's copy: those spanning at most a
    /// quarter of the footprint's longer side (a scan's missing triangles), with faces over their
    /// own vertices.
    int base_holes_filled = 0;
    /// Output vertices behind the base (inner side of the closest base face, deeper than 1% of the
    /// shell height), and elements with any: decoration cutting into the base.
    int vertices_below_base = 0;
    int elements_below_base = 0;
    /// Shell embedding: output vertices whose height exceeds the shell's (mapped above the offset
    /// surface by extrapolation).
    int vertices_above_shell = 0;
    Embedding embedding = Embedding::Shell;
    double shell_height = 0.0;         ///< H in base units (texture-space height of the shell)
    ShellStatistics shell;             ///< with the shell embedding: construction, stretch, limited heights
};

struct SurfaceQuiltResult {
    Mesh mesh;                          ///< all elements embedded in 3D; faces of one element contiguous
    std::vector<int> element_of_face;
    std::vector<int> source_element;    ///< per element: its swatch element
    std::vector<SurfacePoint> anchors;  ///< per vertex of `mesh`
    Mesh base;                          ///< the base as used (welded, oriented, refined); anchors refer to it
    QualityReport report;
    SurfaceQualityReport surface;
    /// The shell map used (shell embedding only): maps `anchors` again, e.g. after editing heights.
    std::shared_ptr<const ShellMap> shell;
    std::vector<std::string> warnings;
};

/// Surface mesh quilting (Section 3.1). The base must be a valid mesh (see validate); it is never
/// changed: welding, orientation fixes and refinement happen on a copy.
/// \throw InvalidInput bad options, empty base, swatch without thin axis, absurd scale
/// \throw Cancelled    the reporter asked to stop
SurfaceQuiltResult quilt_surface(const Mesh& base, const Mesh& swatch, const SurfaceQuiltOptions& options);

}  // namespace meshquilt
