// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file shellmap.h
/// The stretch-optimised tetrahedral shell map of Zhou et al. 2006, Section 3.2, after Porumbescu
/// et al. 2005 (shell maps): a thin shell between a base mesh and an offset surface, cut into
/// tetrahedra, mapping texture space (base charts x height) into 3D without inversions.
///
/// Construction, in order:
/// 1. Offset directions: angle-weighted vertex normals, smoothed (more where the base is concave),
///    kept strictly on the outer side of every incident face (where the base folds so that no
///    direction is, the best-seeing one; such prisms may stay inverted and are counted).
/// 2. Offset heights: the shell height, limited per vertex so that (a) a ray along the direction
///    meets no other part of the base within 2.2 heights (narrow gaps and deep concavities), (b)
///    heights vary by at most half the edge length along an edge, (c) no prism inverts, (d) the
///    offset surface neither intersects itself nor the base and (e) no other part of the base
///    enters a prism (exact tests, CGAL).
/// 3. Texture space: a multi-chart atlas of the base (discs grown breadth first, flattened with
///    LSCM at true area, area distortion of each chart at most 1.25) times the height axis [0, H].
/// 4. Tetrahedra: each prism (a base triangle and its offset) split into three with the diagonals
///    chosen by vertex index (Porumbescu et al. 2005), so neighbouring prisms share faces.
/// 5. Stretch optimisation (Eq. 8-9): random line searches over the texture (u, v) of offset
///    vertices inside charts (chart boundaries fixed), keeping every texture tetrahedron positive,
///    until a pass gains less than a relative 1e-4; vertices of one colour (no shared face) move in
///    parallel, each with its own random stream, so results do not depend on the thread count.
///
/// Stretch normalisation: Eq. 9 with the texture-to-shell map J (Sander et al. 2001), weighted by
/// shell volume, times (sum of texture volumes / sum of shell volumes)^(1/3). The cube root makes 1
/// a true lower bound in 3D (the paper's square root is the 2D factor): by Jensen's inequality,
/// sum_T V_T (|J_T|_F^2 / 3) >= (sum V)(sum V_tex / sum V)^(-2/3), equal only for a similarity.

#include "meshquilt/mesh.h"
#include "meshquilt/reporter.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace meshquilt {

struct SurfacePoint;

struct ShellOptions {
    double height = 0.0;              ///< shell height H in base units (> 0)
    bool optimise = true;             ///< run the stretch optimisation
    int max_passes = 60;              ///< optimisation passes over all free offset vertices at most
    double min_relative_gain = 1e-4;  ///< stop once a pass lowers the objective by less than this
    std::uint64_t seed = 1;           ///< random line-search directions
    /// Atlas charts grow as discs that close slits (a refused face is tried again whenever another
    /// of its neighbours joins); false tries it again only when reached on a path as short as
    /// before, which leaves slits (quilt::grow_disc; the surface stage sets false for swatches
    /// with threads, as for its patch discs).
    bool close_chart_slits = true;
    Reporter reporter;                ///< progress ("shell map") and cancellation
};

/// A region (edge-connected vertices) where the offset height was reduced below H.
struct ShellLimitedRegion {
    Vec3 centre = Vec3::Zero();  ///< mean position of its base vertices
    int vertices = 0;
    double min_ratio = 1.0;      ///< smallest height / H in it
};

struct ShellStatistics {
    int vertices = 0;            ///< base vertices (each with one offset vertex)
    int prisms = 0;
    int tetrahedra = 0;
    int charts = 0;
    int free_offset_vertices = 0;  ///< offset vertices the optimisation may move (inside charts)
    int height_limited_vertices = 0;
    double limited_area_fraction = 0.0;  ///< base area (one third of each face per corner) with reduced height
    double min_height_ratio = 1.0;
    std::vector<ShellLimitedRegion> limited_regions;  ///< largest first, at most 20
    int inverted_world = 0;      ///< shell tetrahedra with volume <= 0 (0 unless the base defeats the construction)
    int inverted_texture = 0;    ///< texture tetrahedra with volume <= 0, after optimisation
    /// Pairs of faces where the offset surface still meets itself or the base, plus prisms that
    /// another part of the base still enters, once heights reached their floor (0 unless the base
    /// defeats the construction).
    int offset_intersections = 0;
    double stretch_l2_initial = 0.0;
    double stretch_l2_final = 0.0;
    int optimisation_passes = 0;
    double seconds_build = 0.0;
    double seconds_optimise = 0.0;
};

/// One tetrahedron of the shell: corners in texture space (chart u, v, height) and in 3D.
struct ShellTet {
    std::array<Vec3, 4> texture;
    std::array<Vec3, 4> world;
};

class ShellMap {
public:
    /// Builds (and by default optimises) the shell over `base`, which must be manifold, oriented
    /// with outward normals, and free of degenerate faces (as the surface stage prepares it).
    /// \throw InvalidInput height not positive and finite, or an empty base
    ShellMap(const Mesh& base, const ShellOptions& options);
    ~ShellMap();
    ShellMap(ShellMap&&) noexcept;
    ShellMap& operator=(ShellMap&&) noexcept;

    /// The 3D position of a texture point given on the base: face, barycentric coordinates, height
    /// (0 .. H). Located in the tetrahedra of its chart and mapped through their barycentric
    /// coordinates; heights outside [0, H] extrapolate the nearest tetrahedron.
    [[nodiscard]] Vec3 map(const SurfacePoint& point) const;

    [[nodiscard]] const ShellStatistics& statistics() const;
    /// The offset surface (the base's faces over the offset vertices).
    [[nodiscard]] Mesh offset_surface() const;
    /// Offset height per base vertex (<= H).
    [[nodiscard]] const std::vector<double>& heights() const;
    /// All tetrahedra (three per base face, in face order) in their current (optimised) state.
    [[nodiscard]] std::vector<ShellTet> tetrahedra() const;
    /// Eq. 9 over the current tetrahedra, normalised so that 1 is the lower bound.
    [[nodiscard]] double stretch_l2() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace meshquilt
