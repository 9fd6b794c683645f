// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Local patches of a base mesh for surface quilting (Zhou et al. 2006, Section 3.1): a disc grown
// around a seed triangle, flattened with LSCM (CGAL Surface_mesh_parameterization), and point
// location in the flattened patch.

#include "meshquilt/mesh.h"

#include <array>
#include <vector>

namespace meshquilt::quilt {

/// Faces around `seed` within `radius` (shortest paths between face centroids), grown breadth
/// first in order of distance; a face joins only if the region stays a topological disc (it shares
/// one edge and brings one new vertex, or shares two edges), so LSCM can flatten it. A face refused
/// is tried again whenever another of its neighbours joins, so no slit is left next to the seed.
/// With `close_slits` false, a refused face is tried again only when reached on a path as short as
/// before (the growth before session 56, which leaves slits; thread swatches keep it, see
/// docs/surface.md step 4, "Thin parts were slow").
std::vector<int> grow_disc(const Mesh& mesh, const std::vector<std::array<int, 3>>& neighbours,
                           const std::vector<Vec3>& centroids, int seed, double radius, bool close_slits = true);

/// Faces whose smallest angle is below this are thin (slivers and needles: CAD fans, CSG output)...
inline constexpr double kMinCellAngleDegrees = 10.0;
/// ... when their longest edge is longer than this fraction of the cell edge (smaller ones vanish in
/// a patch of many cells).
inline constexpr double kThinFaceMinLength = 0.25;
/// ... in clusters (sharing edges) of at least this share of a footprint (6 x 6 cells): a smaller
/// cluster lies within one patch among well-shaped faces (a coarse scan's few slivers, measured
/// harmless there: remeshing the eight's 14 clusters of at most 0.05 footprints cost its chain mail
/// a tenth of its rings linked with 4 others, docs/surface.md step 1).
inline constexpr double kThinClusterFootprints = 0.5;
/// ... unless thin faces cover at least this share of the base's area: then every cluster is
/// remeshed, whatever its size. A base riddled with small clusters of slivers (a CSG union whose
/// long edges were split) crumples the shell map: a sliver's prism inverts as soon as the offset
/// directions at its corners differ by a little, and the lowering spreads from each one (a genus-3
/// union of washers with chain mail at scale 0.12: shell lowered over 56% of the area, lowest
/// region 0.585; every cluster remeshed, 6.7% and 0.74). The shared meshes' thin faces cover at
/// most 2% (the eight), and stay as they were.
inline constexpr double kThinBaseShare = 0.05;
/// Faces whose longest edge is longer than this many cell edges (a footprint) are remeshed too,
/// whatever their shape: splitting their edges alone would leave fans of slivers across them (a
/// 12-face cube with rivets: its faces' middles held 0.1-0.2 of the rivets of their corners, lowest
/// region 0.349). Smaller ones stay: at 2 cells the eight's few long faces at scale 0.2 (up to 4.5
/// cells) were remeshed too and its chain mail fell to 998 rings, below its test's 1,020.
inline constexpr double kLargeFaceCells = 6.0;
/// ... at this edge (a share of the cell edge) when the base has no thin faces: as fine as the
/// cells elsewhere (the cube at scale 0.15: 13,716 cells, 39 s; at kThinFaceTarget 18,384, slower).
inline constexpr double kLargeFaceTarget = 1.0;
/// The remeshed regions' edge, at most (as a share of the cell edge).
inline constexpr double kThinFaceTarget = 0.75;
/// Faces with an angle over this (degrees) after the remeshing are caps: the edge opposite that
/// angle is flipped where that keeps the surface (a hole's rim of 48 sides turns by 7.5 degrees at
/// each corner, and a face across a corner has an angle of 172.5).
inline constexpr double kCapAngleDegrees = 170.0;
/// Dihedral angle (degrees) beyond which an edge is sharp and is kept by the remeshing of thin faces.
inline constexpr double kSharpEdgeDegrees = 45.0;

/// The cells of surface quilting. Clusters of thin faces (kMinCellAngleDegrees, kThinFaceMinLength,
/// kThinClusterFootprints), large faces (kLargeFaceCells) and one ring of faces around them are
/// remeshed first
/// (CGAL::Polygon_mesh_processing::isotropic_remeshing at the region's equilateral edge, at most
/// kThinFaceTarget of `max_length`; vertices stay on the input surface, sharp edges, corners and the
/// boundary keep their polylines): a sliver's centroid says little about where it is, and a fan of
/// them around one vertex defeats the disc growth and the marking of processed faces. Then
/// every edge longer than `max_length` is split (split_long_edges; the surface does not move).
/// `parent` receives, per new face, the input face closest to its centroid; `thin_remeshed` the
/// number of input faces in the remeshed regions (0: the surface is exactly the input's).
Mesh refine_long_edges(const Mesh& mesh, double max_length, std::vector<int>* parent, int* thin_remeshed = nullptr);

/// A disc of the base flattened (LSCM or ARAP).
struct FlatPatch {
    std::vector<int> faces;     ///< base faces
    std::vector<int> vertices;  ///< base vertices, in local order
    std::vector<Tri> local;     ///< faces in local vertex indices
    std::vector<Vec2> uv;       ///< per local vertex
};

/// Flattens `faces` (a disc) with LSCM, scaled so that the flat area equals the 3D area, and
/// orientation kept (counter-clockwise faces stay counter-clockwise). False when CGAL fails.
bool flatten_lscm(const Mesh& mesh, const std::vector<int>& faces, FlatPatch* patch);

/// As flatten_lscm, but as rigid as possible (CGAL's ARAP, Liu et al. 2008, `iterations` of its
/// local/global steps from the LSCM map, lambda 1000): area is kept as well as angles allow, where
/// LSCM keeps angles and lets area drift over a curved disc.
bool flatten_arap(const Mesh& mesh, const std::vector<int>& faces, FlatPatch* patch, int iterations);

/// Ratio of the 98th to the 2nd percentile (by area) of flat-to-3D area ratios over the patch.
double area_distortion(const Mesh& mesh, const FlatPatch& patch);

/// Point location in a flattened patch (uniform grid over the flat triangles).
class PatchLocator {
public:
    explicit PatchLocator(const FlatPatch& patch);
    struct Hit {
        int local_face = -1;  ///< index into patch.faces
        Vec3 bary = Vec3::Zero();
        bool inside = false;  ///< false: the nearest face, with barycentric coordinates extrapolated
    };
    /// The face containing `p`, else the nearest face within `reach` (then `inside` is false);
    /// local_face -1 when nothing is that near.
    [[nodiscard]] Hit locate(const Vec2& p, double reach) const;

private:
    const FlatPatch& patch_;
    Vec2 origin_;
    double cell_ = 1.0;
    int nx_ = 1, ny_ = 1;
    std::vector<std::vector<int>> bucket_;
};

}  // namespace meshquilt::quilt
