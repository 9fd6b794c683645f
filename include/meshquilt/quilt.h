// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file quilt.h
/// Mesh quilting (Zhou et al. 2006): grow a large, seamless, non-periodic geometric texture from a
/// small example mesh (the swatch), keeping every geometry element (connected component) whole.

#include "meshquilt/mesh.h"
#include "meshquilt/reporter.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace meshquilt {

/// Numbers that tests, benchmarks and users read. Filled by every synthesis call.
struct QualityReport {
    int faces = 0;
    int vertices = 0;
    int elements = 0;
    int elements_closed = 0;      ///< elements that are closed, edge-manifold surfaces
    int elements_removed = 0;     ///< removed because they could not be made whole or intersected others
    int patches = 0;              ///< swatch placements
    int elements_stitched = 0;    ///< merged from an old and a new part into one element (Section 2.7)
    int elements_replaced = 0;    ///< old element inside the overlap replaced by its partner
    int stitch_failures = 0;      ///< stitches that could not be made; the old element was kept
    int collisions_avoided = 0;   ///< new elements not added because they would intersect the output
    int elements_crowded_out = 0; ///< new elements without partner left out: an old element stands at about the same place
    int elements_squeezed = 0;    ///< blobs that lost a merge kept, squeezed clear of the winner (beyond the paper)
    int losers_kept = 0;          ///< a layered swatch's blobs (scales) that lost a merge kept whole beside the winner (beyond the paper)
    int strand_pieces = 0;        ///< pieces of colliding strands (knot work) that went in, cut across the strand clear of what they crossed (beyond the paper)
    int joints_closed = 0;        ///< blobs grown into joints wider than the swatch's (beyond the paper)
    int bald_spots_filled = 0;    ///< elements placed one by one into bare spots after the last patch (beyond the paper)
    double cell_size = 0.0;
    /// Element area per unit footprint area, counted by face centroid in a window inset by 15% of the
    /// swatch's sides from the border (of the swatch, and of the output), so both use one estimator.
    double swatch_density = 0.0;
    double output_density = 0.0;
    int largest_translation_share = 0;  ///< placements sharing the most common translation (mod the swatch grid)
    std::vector<std::pair<std::string, double>> seconds;  ///< wall time per stage
};

struct PlanarQuiltOptions {
    double width = 0.0;   ///< output footprint along x, in swatch units; > 0
    double height = 0.0;  ///< output footprint along y, in swatch units; > 0
    /// Grid cell size in swatch units; <= 0 chooses one from the swatch (about 1/24 of its longer side).
    double cell_size = 0.0;
    /// Side of the output sub-patch P_out around each seed, in cells; <= 0: one third of the swatch's cells.
    int subpatch_cells = 0;
    std::uint64_t seed = 1;   ///< same inputs and seed give identical output
    double lambda = 1.0;      ///< Eq. 1 weight of distance against normal difference
    double mu = 1.0;          ///< Eq. 5-6 weight of position constraints against Laplacian coordinates
    /// Among translations whose cost is within this fraction of the best, one is chosen at random
    /// (avoids visible repetition).
    double tolerance = 0.1;
    Reporter reporter;
};

struct QuiltResult {
    Mesh mesh;                        ///< all elements; faces of one element are contiguous
    std::vector<int> element_of_face;
    std::vector<int> source_element;  ///< per output element: the swatch element it grew from
    QualityReport report;
    std::vector<std::string> warnings;
};

/// Planar mesh quilting (Section 2). The swatch is first moved into its own frame: its thinnest
/// bounding-box axis becomes z, its footprint starts at the origin. The output covers
/// [0, width] x [0, height] (elements whose centroid lies inside are kept) at the swatch's thickness.
/// \throw InvalidInput swatch without a thin axis or without faces, non-positive or absurd sizes
/// \throw Cancelled    the reporter asked to stop
QuiltResult quilt_plane(const Mesh& swatch, const PlanarQuiltOptions& options);

/// The swatch moved into its own frame (thin axis -> z by a cyclic axis permutation, which keeps
/// orientation; footprint from the origin, height from 0).
Mesh normalize_swatch(const Mesh& swatch);

}  // namespace meshquilt
