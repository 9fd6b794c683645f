// labels: property e2e
// The tetrahedral shell map (issue 4, Zhou et al. 2006 Section 3.2): bijectivity (positive
// tetrahedra in texture space and in 3D, before and after optimisation), the stretch measure and
// its optimisation, limited heights in narrow concave places, a continuous map, and the end-to-end
// claim: on a base with a narrow slot the shell keeps every element out of the base and inside the
// shell, where normal displacement drives elements into the opposite wall.

#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/shellmap.h"
#include "meshquilt/surface.h"
#include "quilt/field.h"
#include "quilt/patch.h"
#include "support/checkers.h"
#include "support/paths.h"
#include "support/expect_error.h"
#include "support/shapes.h"
#include "support/shapes_isect.h"
#include "support/solid.h"

#include "core/intersect.h"
#include "core/triangle_index.h"
#include "shellmap/visibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <queue>
#include <random>
#include <set>
#include <string>

namespace mq = meshquilt;
using meshquilt::test::swatch_path;
using meshquilt::test::surface_data_path;
using mq::Mesh;
using mq::Vec3;
namespace shapes = mq::test::shapes;
namespace isect = mq::test::isect;

namespace {


double diagonal(const Mesh& m) { return mq::bounding_box(m).size().norm(); }

/// A block of 7 x 3 x 3 unit voxels with a slot one unit wide and two deep along y (x in [3, 4],
/// z in [1, 3]), refined to edges of at most `edge`: a closed base with a narrow concave gap.
Mesh slot_block(double edge) {
    std::vector<std::array<int, 3>> cells;
    for (int x = 0; x < 7; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z)
                if (!(x == 3 && z >= 1)) cells.push_back({x, y, z});
    std::vector<int> parent;
    return mq::quilt::refine_long_edges(shapes::voxels(cells), edge, &parent);
}

double tet_volume(const std::array<Vec3, 4>& p) { return (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0; }

/// No inverted tetrahedron (in 3D, or in texture space after optimisation), and an offset
/// surface that meets neither itself nor the base.
void expect_valid_shell(const mq::ShellMap& s, const Mesh& base) {
    EXPECT_EQ(s.statistics().inverted_world, 0);
    EXPECT_EQ(s.statistics().inverted_texture, 0);
    EXPECT_EQ(s.statistics().offset_intersections, 0);
    int bad = 0;
    for (const auto& t : s.tetrahedra()) bad += !(tet_volume(t.world) > 0);
    EXPECT_EQ(bad, 0);
    const Mesh off = s.offset_surface();
    EXPECT_EQ(mq::count_self_intersections(off, 1), 0);
    EXPECT_FALSE(mq::meshes_intersect(off, base));
}

/// Eq. 8-9 recomputed from the tetrahedra alone (texture-to-shell Jacobians, shell-volume
/// weights, cube-root normalisation).
double stretch_of(const std::vector<mq::ShellTet>& tets) {
    double num = 0.0, vw = 0.0, vt = 0.0;
    for (const auto& t : tets) {
        Eigen::Matrix3d T, W;
        for (int j = 1; j < 4; ++j) {
            T.col(j - 1) = t.texture[static_cast<std::size_t>(j)] - t.texture[0];
            W.col(j - 1) = t.world[static_cast<std::size_t>(j)] - t.world[0];
        }
        const double w = W.determinant() / 6.0;
        num += (W * T.inverse()).squaredNorm() / 3.0 * w;
        vw += w;
        vt += T.determinant() / 6.0;
    }
    return std::sqrt(num / vw) * std::cbrt(vt / vw);
}

struct Case {
    std::string name;
    Mesh base;
    double height;  ///< as a fraction of the diagonal
};

std::vector<Case> cases() {
    return {
        {"sphere", isect::icosphere(1.0, 3), 0.03},
        {"torus", shapes::torus(2.0, 0.6, 48, 20), 0.03},
        {"eight", mq::read_mesh(surface_data_path("eight.obj")), 0.02},
        {"spot", mq::read_mesh(surface_data_path("spot.obj")), 0.015},
        {"open cylinder", shapes::open_cylinder(1.0, 2.0, 32, 8), 0.03},
        {"slot block", slot_block(0.25), 0.08},
    };
}

double shell_height(const Case& c) { return c.height * diagonal(c.base); }

/// A 16 x 16 sheet of unit squares (split in two) crumpled in its middle by a smooth bump of
/// sideways and vertical waves, so strongly that the surface folds back over itself in a few places
/// (like a scan's crumpled flap) without meeting itself. Moving the fold vertices alone to their
/// neighbours' mean leaves two of them folded, and the shell over that keeps 4 inverted
/// tetrahedra; the surface stage's smoothing must leave none.
Mesh crumpled_sheet() {
    constexpr int n = 16;
    constexpr double amplitude = 1.58, wave = 0.889, phase = 1.094, radius = 2.619, lift = 0.371;
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = i, y = j;
            const double bump = std::exp(-((x - 8) * (x - 8) + (y - 8) * (y - 8)) / (4.0 * radius * radius));
            m.vertices.emplace_back(x + amplitude * bump * (std::sin(wave * y + phase) + std::cos(0.7 * x)),
                                    y + 0.5 * amplitude * bump * std::sin(0.9 * x + phase), 2.0 * lift * bump * std::sin(wave * x + phase));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            m.faces.emplace_back(a, b, c);
            m.faces.emplace_back(a, c, d);
        }
    return m;
}

}  // namespace

// Every tetrahedron positive in texture space and in 3D, before and after optimisation; the
// stretch is >= 1, agrees with an independent computation, and the optimisation never worsens it.
TEST(ShellMap, BijectiveAndStretchNeverWorse) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        mq::ShellOptions o;
        o.height = shell_height(c);
        o.optimise = false;
        const mq::ShellMap before(c.base, o);
        o.optimise = true;
        const mq::ShellMap after(c.base, o);
        for (const mq::ShellMap* s : {&before, &after}) {
            int bad_world = 0, bad_texture = 0;
            const auto tets = s->tetrahedra();
            ASSERT_EQ(tets.size(), 3 * c.base.faces.size());
            for (const auto& t : tets) {
                bad_world += !(tet_volume(t.world) > 0);
                bad_texture += !(tet_volume(t.texture) > 0);
            }
            EXPECT_EQ(bad_world, 0);
            EXPECT_EQ(bad_texture, 0);
            EXPECT_EQ(s->statistics().inverted_world, 0);
            EXPECT_EQ(s->statistics().inverted_texture, 0);
            EXPECT_NEAR(stretch_of(tets), s->stretch_l2(), 1e-9);
            EXPECT_GE(s->stretch_l2(), 1.0 - 1e-9);
        }
        const auto& st = after.statistics();
        EXPECT_NEAR(st.stretch_l2_initial, before.stretch_l2(), 1e-12);
        EXPECT_NEAR(st.stretch_l2_final, after.stretch_l2(), 1e-12);
        EXPECT_LE(st.stretch_l2_final, st.stretch_l2_initial);
        EXPECT_GT(st.free_offset_vertices, 0);
        EXPECT_GE(st.optimisation_passes, 1);
    }
}

// Charts grown with slits (ShellOptions::close_chart_slits false, what the surface stage asks for
// swatches with threads) give a shell as valid as the default charts: every tetrahedron positive in
// both spaces and the stretch never worse after optimisation. On spot split into cells as the
// surface stage splits it the two growths give different atlases (else the option would not reach the charts); on
// the coarser bases here they give the same.
TEST(ShellMap, ChartsWithSlitsAreAsValid) {
    std::vector<Case> all = cases();
    // Spot split to edges of 1% of its diagonal, as the surface stage splits a base into cells (to
    // 1/6 of the footprint: 1.3% at the default scale 0.08): there the growths differ (at 2% not).
    const Mesh spot = mq::read_mesh(surface_data_path("spot.obj"));
    std::vector<int> parent;
    int thin = -1;
    all.push_back({"spot cells", mq::quilt::refine_long_edges(spot, 0.01 * diagonal(spot), &parent, &thin), 0.02});
    for (const Case& c : all) {
        SCOPED_TRACE(c.name);
        mq::ShellOptions o;
        o.height = shell_height(c);
        const mq::ShellMap whole(c.base, o);
        o.close_chart_slits = false;
        const mq::ShellMap slit(c.base, o);
        const auto tw = whole.tetrahedra(), ts = slit.tetrahedra();
        ASSERT_EQ(ts.size(), tw.size());
        int bad_world = 0, bad_texture = 0, moved = 0;
        for (std::size_t i = 0; i < ts.size(); ++i) {
            bad_world += !(tet_volume(ts[i].world) > 0);
            bad_texture += !(tet_volume(ts[i].texture) > 0);
            for (int k = 0; k < 4; ++k) moved += (ts[i].texture[k] - tw[i].texture[k]).norm() > 1e-9;
        }
        EXPECT_EQ(bad_world, 0);
        EXPECT_EQ(bad_texture, 0);
        const auto& st = slit.statistics();
        EXPECT_LE(st.stretch_l2_final, st.stretch_l2_initial);
        std::printf("%s: %d charts closing slits, %d with slits, %d of %zu texture corners differ; stretch %.4f, %.4f\n", c.name.c_str(),
                    whole.statistics().charts, st.charts, moved, 4 * ts.size(), whole.stretch_l2(), slit.stretch_l2());
        if (c.name == "spot cells") EXPECT_GT(moved, 0);
    }
}

// The offset surface meets neither itself nor the base (exact tests), heights stay in
// [floor, H], and the bottom of the shell is the base itself.
TEST(ShellMap, OffsetIsCleanAndBottomIsTheBase) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const mq::ShellMap s(c.base, {shell_height(c)});
        const Mesh off = s.offset_surface();
        EXPECT_EQ(mq::count_self_intersections(off, 1), 0);
        EXPECT_FALSE(mq::meshes_intersect(off, c.base));
        EXPECT_EQ(s.statistics().offset_intersections, 0);
        for (double h : s.heights()) {
            EXPECT_LE(h, shell_height(c));
            EXPECT_GE(h, 0.02 * shell_height(c) * (1 - 1e-12));
        }
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        double worst = 0.0;
        for (std::size_t f = 0; f < c.base.faces.size(); f += 7) {
            double a = u(rng), b = u(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const Vec3 bary(1 - a - b, a, b);
            const Vec3 want = bary[0] * c.base.vertices[c.base.faces[f][0]] + bary[1] * c.base.vertices[c.base.faces[f][1]] +
                              bary[2] * c.base.vertices[c.base.faces[f][2]];
            worst = std::max(worst, (s.map({static_cast<int>(f), bary, 0.0}) - want).norm());
        }
        EXPECT_LT(worst, 1e-9 * diagonal(c.base));
    }
}

// A point on an edge shared by two faces maps to the same place from either face, at every
// height (the map is continuous, inside charts and across chart boundaries).
TEST(ShellMap, ContinuousAcrossEdges) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const mq::ShellMap s(c.base, {shell_height(c)});
        const auto nb = mq::quilt::face_neighbours(c.base);
        double worst = 0.0;
        int tested = 0;
        for (std::size_t f = 0; f < c.base.faces.size(); f += 3)
            for (int k = 0; k < 3; ++k) {
                const int g = nb[f][static_cast<std::size_t>(k)];
                if (g < 0) continue;
                const int a = c.base.faces[f][k], b = c.base.faces[f][(k + 1) % 3];
                for (const double t : {0.25, 0.6})
                    for (const double h : {0.3, 0.95}) {
                        Vec3 bf = Vec3::Zero(), bg = Vec3::Zero();
                        for (int j = 0; j < 3; ++j) {
                            if (c.base.faces[f][j] == a) bf[j] = 1 - t;
                            if (c.base.faces[f][j] == b) bf[j] = t;
                            if (c.base.faces[static_cast<std::size_t>(g)][j] == a) bg[j] = 1 - t;
                            if (c.base.faces[static_cast<std::size_t>(g)][j] == b) bg[j] = t;
                        }
                        const Vec3 p = s.map({static_cast<int>(f), bf, h * shell_height(c)});
                        const Vec3 q = s.map({g, bg, h * shell_height(c)});
                        worst = std::max(worst, (p - q).norm());
                        ++tested;
                    }
            }
        EXPECT_GT(tested, 0);
        EXPECT_LT(worst, 1e-9 * diagonal(c.base));
    }
}

// In the slot (one unit wide) the height is limited so that the two walls' shells keep apart, and
// the report says where; on the open faces far from it the full height stays.
TEST(ShellMap, HeightLimitedInNarrowSlot) {
    const Mesh base = slot_block(0.25);
    mq::ShellOptions o;
    o.height = 0.6;  // taller than half the gap
    const mq::ShellMap s(base, o);
    const auto& st = s.statistics();
    ASSERT_GT(st.height_limited_vertices, 0);
    ASSERT_FALSE(st.limited_regions.empty());
    EXPECT_GT(st.limited_area_fraction, 0.0);
    EXPECT_LT(st.limited_area_fraction, 0.5);
    EXPECT_LT(st.min_height_ratio, 0.5 / 0.6);
    // The largest region is the slot.
    const Vec3 c = st.limited_regions.front().centre;
    EXPECT_NEAR(c.x(), 3.5, 0.5);
    // Offset surfaces of the two walls stay apart: walls at x = 3 and x = 4.
    const Mesh off = s.offset_surface();
    for (std::size_t v = 0; v < base.vertices.size(); ++v) {
        const Vec3& p = base.vertices[v];
        const bool in_slot = p.z() > 1.0 + 1e-9 && p.z() < 3.0 - 1e-9 && p.y() > 1e-9 && p.y() < 3.0 - 1e-9;
        if (in_slot && std::fabs(p.x() - 3.0) < 1e-9) EXPECT_LT(off.vertices[v].x(), 3.5) << v;
        if (in_slot && std::fabs(p.x() - 4.0) < 1e-9) EXPECT_GT(off.vertices[v].x(), 3.5) << v;
        // The top face of the block, two units from the slot and from the edges, keeps H.
        if (std::fabs(p.z() - 3.0) < 1e-9 && p.x() > 0.9 && p.x() < 1.6 && p.y() > 0.9 && p.y() < 2.1)
            EXPECT_NEAR(s.heights()[v], o.height, 1e-12) << v;
    }
}

// A bumpy base (a scan's skin: bumps a few edges wide, narrower than H) keeps nearly all of its
// height: the offset directions are smoothed further where prisms invert at full height, so the
// bumps no longer fold the offset surface (before: 9.9% of the area lowered, down to 0.64 of H).
// The shell stays valid. Where that smoothing mends little (a slot) it is refused: see
// ASlotsWallsKeepTheirNormalsAsOffsetDirections.
TEST(ShellMap, BumpyBaseKeepsItsHeight) {
    Mesh base = isect::icosphere(1.0, 5);
    double edge = 0.0;
    for (const auto& t : base.faces) edge += (base.vertices[t[0]] - base.vertices[t[1]]).norm();
    edge /= static_cast<double>(base.faces.size());
    for (Vec3& v : base.vertices) v *= 1.0 + 0.05 * std::sin(40 * v.x()) * std::sin(40 * v.y()) * std::sin(40 * v.z());
    mq::ShellOptions o;
    o.height = 3.0 * edge;
    o.optimise = false;
    const mq::ShellMap s(base, o);
    const auto& st = s.statistics();
    std::cerr << "bumpy sphere: " << 100 * st.limited_area_fraction << "% of the area lowered, least height " << st.min_height_ratio << " of H\n";
    EXPECT_LT(st.limited_area_fraction, 0.02);
    expect_valid_shell(s, base);
}

// A base folded back onto itself (no direction sees every face around some vertices from outside)
// cannot carry a valid shell as it is. The synthesis smooths its copy of such folds; the smoothing
// must leave no fold behind even where moving the fold vertices alone converges to a folded state
// (as on the camelhead's flap), and the shell over the result is then fully valid.
TEST(ShellMap, FoldedBaseSmoothedIntoAValidShell) {
    Mesh base = crumpled_sheet();
    auto folds = [](const Mesh& m) {
        const std::vector<Vec3> fn = mq::face_normals(m);
        std::vector<std::vector<Vec3>> around(m.vertices.size());
        for (std::size_t f = 0; f < m.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) around[static_cast<std::size_t>(m.faces[f][k])].push_back(fn[f]);
        int n = 0;
        for (const auto& normals : around) {
            Vec3 d;
            if (!normals.empty() && mq::shell::best_visibility(normals, normals.front(), &d) < mq::shell::kMinSeeingCos) ++n;
        }
        return n;
    };
    ASSERT_GT(folds(base), 0);
    ASSERT_EQ(mq::count_self_intersections(base, 1), 0);
    const Mesh original = base;
    const int moved = mq::shell::smooth_folds(base, mq::shell::kMinSeeingCos);
    EXPECT_GT(moved, 0);
    EXPECT_EQ(folds(base), 0);
    // Only the neighbourhood of the folds moves: the sheet's border stays.
    for (std::size_t v = 0; v < base.vertices.size(); ++v) {
        const int i = static_cast<int>(v) % 17, j = static_cast<int>(v) / 17;
        if (i == 0 || j == 0 || i == 16 || j == 16) EXPECT_EQ(base.vertices[v], original.vertices[v]) << v;
    }
    EXPECT_EQ(mq::count_self_intersections(base, 1), 0);
    mq::ShellOptions o;
    o.height = 0.3;
    const mq::ShellMap s(base, o);
    expect_valid_shell(s, base);
}

TEST(ShellMap, RejectsBadOptions) {
    const Mesh base = isect::icosphere(1.0, 1);
    mq::ShellOptions o;
    o.height = 0.0;
    EXPECT_THROW(mq::ShellMap(base, o), mq::InvalidInput);
    o.height = std::nan("");
    EXPECT_THROW(mq::ShellMap(base, o), mq::InvalidInput);
    o.height = 0.1;
    EXPECT_THROW(mq::ShellMap(Mesh{}, o), mq::InvalidInput);
}

namespace {

struct SlotRun {
    mq::SurfaceQuiltResult r;
    int vertices_in_base = 0;   ///< output vertices inside the base solid (beyond a small margin)
    int elements_in_base = 0;   ///< elements with such a vertex
    int outside_shell = 0;      ///< output vertices outside the offset surface (beyond the margin)
};

SlotRun quilt_slot(mq::Embedding embedding) {
    // Built from the voxels directly: the surface stage refines on its own.
    std::vector<std::array<int, 3>> cells;
    for (int x = 0; x < 7; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z)
                if (!(x == 3 && z >= 1)) cells.push_back({x, y, z});
    const Mesh base = shapes::voxels(cells);
    mq::SurfaceQuiltOptions o;
    o.swatch_size = 1.6;
    o.height = 1.2;  // taller than the slot is wide
    o.embedding = embedding;
    SlotRun run{mq::quilt_surface(base, mq::read_mesh(swatch_path("rivets")), o)};
    const mq::test::Solid solid(base);
    const double margin = 1e-6;
    std::vector<char> hit(static_cast<std::size_t>(run.r.report.elements), 0);
    for (std::size_t f = 0; f < run.r.mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(run.r.mesh.faces[f][k]);
            if (solid.inside(run.r.mesh.vertices[v], margin)) hit[static_cast<std::size_t>(run.r.element_of_face[f])] = 1;
        }
    for (const Vec3& p : run.r.mesh.vertices) run.vertices_in_base += solid.inside(p, margin);
    for (char h : hit) run.elements_in_base += h;
    if (run.r.shell) {
        const mq::test::Solid outer(run.r.shell->offset_surface());
        for (std::size_t v = 0; v < run.r.mesh.vertices.size(); ++v)
            if (!outer.inside(run.r.mesh.vertices[v]) && outer.distance(run.r.mesh.vertices[v]) > margin)
                ++run.outside_shell;
    }
    return run;
}

}  // namespace

// The proof that the shell map matters: on the slot, normal displacement pushes elements
// into the opposite wall; the shell map keeps every element out of the base and inside the shell.
TEST(ShellMap, SlotNoElementInBaseWhereNormalDisplacementCuts) {
    const SlotRun normal = quilt_slot(mq::Embedding::Normal);
    const SlotRun shell = quilt_slot(mq::Embedding::Shell);
    EXPECT_GT(normal.elements_in_base, 0);
    EXPECT_EQ(shell.vertices_in_base, 0);
    EXPECT_EQ(shell.elements_in_base, 0);
    EXPECT_EQ(shell.outside_shell, 0);
    EXPECT_EQ(shell.r.surface.vertices_above_shell, 0);
    EXPECT_EQ(shell.r.surface.elements_below_base, 0);
    EXPECT_GT(normal.r.surface.elements_below_base, 0);
    EXPECT_GT(shell.r.surface.shell.height_limited_vertices, 0);
    EXPECT_EQ(shell.r.surface.base_faces_processed, shell.r.surface.base_faces);
    EXPECT_TRUE(mq::test::elements_closed(shell.r.mesh, shell.r.element_of_face));
    EXPECT_TRUE(mq::test::no_element_intersections(shell.r.mesh, shell.r.element_of_face));
    std::cerr << "slot: normal displacement " << normal.elements_in_base << " of " << normal.r.report.elements << " elements ("
              << normal.vertices_in_base << " vertices) in the base; shell " << shell.elements_in_base << " of " << shell.r.report.elements
              << "\n";
}

namespace {

/// An element's diameter: the largest distance between two of its vertices. (A double sweep, the
/// farthest vertex from the farthest vertex from any, is only a lower bound: on a tilted ring mended
/// in the comb below it read 0.66 of the swatch ring's width where the ring spans 0.83.)
double diameter(const Mesh& m) {
    double d = 0.0;
    for (std::size_t a = 0; a < m.vertices.size(); ++a)
        for (std::size_t b = a + 1; b < m.vertices.size(); ++b) d = std::max(d, (m.vertices[a] - m.vertices[b]).squaredNorm());
    return std::sqrt(d);
}

double area_of(const Mesh& m) {
    double a = 0.0;
    for (const auto& t : m.faces) a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
    return a;
}

double p95_over_p5(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() * 95 / 100] / v[v.size() * 5 / 100];
}

/// 95th over 5th percentile of element size relative to its swatch element's: by diameter (the
/// lateral size, which a lowered shell does not change) and by the square root of the area
/// (which flattening lowers).
std::pair<double, double> size_spread(const mq::SurfaceQuiltResult& r, const Mesh& swatch) {
    int count = 0;
    const std::vector<int> comp = mq::connected_components(swatch, &count);
    const std::vector<Mesh> source = mq::test::split_elements(swatch, comp);
    std::vector<double> by_diameter, by_area;
    const auto parts = mq::test::split_elements(r.mesh, r.element_of_face);
    for (std::size_t e = 0; e < parts.size(); ++e) {
        const Mesh& src = source[static_cast<std::size_t>(r.source_element[e])];
        by_diameter.push_back(diameter(parts[e]) / diameter(src));
        by_area.push_back(std::sqrt(area_of(parts[e]) / area_of(src)));
    }
    return {p95_over_p5(by_diameter), p95_over_p5(by_area)};
}

}  // namespace

// Element sizes stay as even with the shell map as with normal displacement (95th over 5th
// percentile of element diameter relative to its swatch element's), on curved bases.
TEST(ShellMap, ElementSizesAsEvenAsWithNormalDisplacement) {
    const Mesh swatch = mq::read_mesh(swatch_path("rivets"));
    for (const std::string name : {"eight.obj", "spot.obj"}) {
        SCOPED_TRACE(name);
        const Mesh base = mq::read_mesh(surface_data_path(name));
        mq::SurfaceQuiltOptions o;
        o.scale = 0.15;
        std::pair<double, double> normal{0.0, 0.0}, shell{0.0, 0.0};
        for (unsigned seed : {1u, 2u, 3u}) {
            o.seed = seed;
            o.embedding = mq::Embedding::Normal;
            const auto n = size_spread(mq::quilt_surface(base, swatch, o), swatch);
            o.embedding = mq::Embedding::Shell;
            const auto r = mq::quilt_surface(base, swatch, o);
            const auto sh = size_spread(r, swatch);
            std::cerr << name << " seed " << seed << ": size spread (p95/p5) by diameter: normal " << n.first << ", shell " << sh.first
                      << "; by area: normal " << n.second << ", shell " << sh.second << "\n";
            EXPECT_EQ(r.surface.elements_below_base, 0);
            normal = {normal.first + n.first / 3.0, normal.second + n.second / 3.0};
            shell = {shell.first + sh.first / 3.0, shell.second + sh.second / 3.0};
        }
        // Different syntheses (the embedding steers collisions and retries), so compared over three
        // seeds: at one seed the shell's spread was 2.2% over the normal one's (the eight at seed
        // 1, session 53), at the others between 1.2% under and 1.2% over.
        EXPECT_LE(shell.first, normal.first * 1.02);
        EXPECT_LE(shell.second, normal.second * 1.02);
    }
}

// Where the shell is lowered the map flattens elements; they keep their width (the size correction
// undoes only the map's lateral scale, not the area that flattening takes), so flattened rings are
// no wider than the others. A comb of narrow slots lowers the shell over much of the base.
TEST(ShellMap, FlattenedElementsKeepTheirWidth) {
    std::vector<std::array<int, 3>> cells;
    for (int x = 0; x < 13; ++x)
        for (int y = 0; y < 5; ++y)
            for (int z = 0; z < 3; ++z)
                if (!(x % 3 == 2 && z >= 1)) cells.push_back({x, y, z});
    const Mesh base = shapes::voxels(cells);
    const Mesh swatch = mq::read_mesh(swatch_path("chainmail"));
    mq::SurfaceQuiltOptions o;
    o.swatch_size = 4.5;
    const auto r = mq::quilt_surface(base, swatch, o);
    ASSERT_GT(r.surface.shell.height_limited_vertices, 0);
    int count = 0;
    const std::vector<Mesh> source = mq::test::split_elements(swatch, mq::connected_components(swatch, &count));
    const double s = r.surface.base_scale;
    const mq::test::Solid solid(base);
    std::vector<double> flattened, upright;  // diameter over the swatch element's at scale
    const auto parts = mq::test::split_elements(r.mesh, r.element_of_face);
    for (std::size_t e = 0; e < parts.size(); ++e) {
        const Mesh& src = source[static_cast<std::size_t>(r.source_element[e])];
        double top = 0.0;
        for (const Vec3& v : parts[e].vertices) top = std::max(top, solid.distance(v));
        const double height = mq::bounding_box(src).size().z() * s;
        const double width = diameter(parts[e]) / (diameter(src) * s);
        if (top < 0.6 * height) flattened.push_back(width);
        else if (top > 0.95 * height) upright.push_back(width);
        // No element is shrunk or widened out of the bound (where the shell is nearly flat
        // an unflattening that scaled sideways offsets back up once shrank rings threefold).
        EXPECT_GT(width, 1.0 / 1.5) << "element " << e << " (height " << top / height << " of its own)";
        EXPECT_LT(width, 1.5) << "element " << e << " (height " << top / height << " of its own)";
    }
    ASSERT_GE(flattened.size(), 10U);
    ASSERT_GE(upright.size(), 10U);
    auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    std::cerr << "comb: " << r.surface.elements_enlarged << " enlarged; " << flattened.size() << " elements flattened below 60% of their height, median width " << median(flattened)
              << "; " << upright.size() << " upright, median width " << median(upright) << "\n";
    EXPECT_LE(median(flattened), 1.05 * median(upright));
    EXPECT_EQ(r.surface.elements_below_base, 0);
    EXPECT_EQ(r.surface.vertices_above_shell, 0);
}

// A zero-area face (collinear corners) does not stop the shell, and every point still maps to a
// finite position (the face's prism is flat; its points follow the offset directions).
TEST(ShellMap, ZeroAreaFaceMapsToFinitePositions) {
    Mesh base = shapes::grid(4, 1.0);
    // Move an interior vertex onto the segment between two of its neighbours of one face.
    const auto& t = base.faces[10];
    base.vertices[t[0]] = 0.5 * (base.vertices[t[1]] + base.vertices[t[2]]);
    const mq::ShellMap s(base, {0.1});
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        for (const double h : {0.0, 0.05, 0.1, 0.2}) EXPECT_TRUE(s.map({static_cast<int>(f), Vec3(0.2, 0.3, 0.5), h}).allFinite()) << f;
    EXPECT_GE(s.stretch_l2(), 1.0 - 1e-9);
}

// A point given slightly beyond its face's edge (extrapolated barycentric coordinates, as a patch
// border produces) continues onto the neighbouring face: at height 0 it lies on the base, not on
// the face's plane extended under the neighbour.
TEST(ShellMap, PointsBeyondAnEdgeContinueOntoTheNeighbour) {
    const Mesh base = isect::icosphere(1.0, 2);  // coarse: 16 degrees between neighbouring faces
    const mq::ShellMap s(base, {0.05});
    const mq::test::Solid solid(base);
    double worst = 0.0;
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            Vec3 bary = Vec3::Constant(0.55);
            bary[k] = -0.1;  // beyond the edge opposite corner k
            worst = std::max(worst, solid.distance(s.map({static_cast<int>(f), bary, 0.0})));
        }
    EXPECT_LT(worst, 1e-9);
    // Beyond a corner (two coordinates negative, as a patch border gives near a vertex): the point
    // walks round the corner's fan onto the face that holds it, on the base, not off it. A spindle
    // (two cones on a ring of 8) has corners whose fans take more than three steps.
    Mesh spindle;
    const int n = 8;
    for (int i = 0; i < n; ++i) spindle.vertices.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0.0);
    spindle.vertices.emplace_back(0.0, 0.0, 1.0);
    spindle.vertices.emplace_back(0.0, 0.0, -1.0);
    for (int i = 0; i < n; ++i) {
        spindle.faces.push_back({n, i, (i + 1) % n});
        spindle.faces.push_back({n + 1, (i + 1) % n, i});
    }
    const mq::ShellMap spindle_shell(spindle, {0.05});
    const mq::test::Solid spindle_solid(spindle);
    worst = 0.0;
    for (std::size_t f = 0; f < spindle.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            Vec3 bary = Vec3::Constant(-0.1);
            bary[k] = 1.2;
            worst = std::max(worst, spindle_solid.distance(spindle_shell.map({static_cast<int>(f), bary, 0.0})));
        }
    EXPECT_LT(worst, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// The cells of surface quilting: thin faces remeshed, long edges split (quilt/patch.h).

namespace {

double smallest_angle_degrees(const Mesh& m) {
    double lo = 180.0;
    for (const mq::Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = m.vertices[t[(k + 1) % 3]] - m.vertices[t[k]], b = m.vertices[t[(k + 2) % 3]] - m.vertices[t[k]];
            lo = std::min(lo, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
        }
    return lo;
}

/// The share of angles below `degrees`.
double share_of_angles_below(const Mesh& m, double degrees) {
    int below = 0;
    for (const mq::Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = m.vertices[t[(k + 1) % 3]] - m.vertices[t[k]], b = m.vertices[t[(k + 2) % 3]] - m.vertices[t[k]];
            below += std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI < degrees;
        }
    return static_cast<double>(below) / (3.0 * static_cast<double>(m.faces.size()));
}

double longest_edge(const Mesh& m) {
    double hi = 0.0;
    for (const mq::Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) hi = std::max(hi, (m.vertices[t[(k + 1) % 3]] - m.vertices[t[k]]).norm());
    return hi;
}

double total_area(const Mesh& m) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) a += mq::face_area(m, f);
    return a;
}

double enclosed_volume(const Mesh& m) {
    double v = 0.0;
    for (const mq::Tri& t : m.faces) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

bool has_vertex_at(const Mesh& m, const Vec3& p) {
    return std::any_of(m.vertices.begin(), m.vertices.end(), [&](const Vec3& v) { return (v - p).norm() < 1e-12; });
}

}  // namespace

// The flattening of a patch (quilt/patch.h): LSCM keeps angles, ARAP from its map keeps area too.
namespace {

int turned_faces(const mq::quilt::FlatPatch& q) {
    int n = 0;
    for (const mq::Tri& t : q.local) {
        const mq::Vec2 e1 = q.uv[static_cast<std::size_t>(t[1])] - q.uv[static_cast<std::size_t>(t[0])];
        const mq::Vec2 e2 = q.uv[static_cast<std::size_t>(t[2])] - q.uv[static_cast<std::size_t>(t[0])];
        n += !(e1.x() * e2.y() - e1.y() * e2.x() > 0.0);
    }
    return n;
}

/// Faces whose centroid, carried to the plane, lies in no flat face or in more than one (brute
/// force): 0 for a one-to-one map.
int stray_faces(const mq::quilt::FlatPatch& p) {
    const auto side = [](const mq::Vec2& u, const mq::Vec2& v, const mq::Vec2& w) { return (v - u).x() * (w - u).y() - (v - u).y() * (w - u).x(); };
    int stray = 0;
    for (const mq::Tri& f : p.local) {
        mq::Vec2 c = mq::Vec2::Zero();
        for (int k = 0; k < 3; ++k) c += p.uv[static_cast<std::size_t>(f[k])] / 3.0;
        int inside = 0;
        for (const mq::Tri& t : p.local) {
            const mq::Vec2 a = p.uv[static_cast<std::size_t>(t[0])], b = p.uv[static_cast<std::size_t>(t[1])], d = p.uv[static_cast<std::size_t>(t[2])];
            inside += side(a, b, c) > 0 && side(b, d, c) > 0 && side(d, a, c) > 0;
        }
        stray += inside != 1;
    }
    return stray;
}

std::vector<int> all_faces(const Mesh& m) {
    std::vector<int> all(m.faces.size());
    for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
    return all;
}

/// Each face's centroid, the points grow_disc measures its paths between.
std::vector<Vec3> centroids_of(const Mesh& mesh) {
    std::vector<Vec3> centroid(mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) centroid[f] = mq::face_centroid(mesh, f);
    return centroid;
}

}  // namespace

TEST(Patches, ADiscTakesEveryFaceNearItsSeed) {
    // grow_disc adds faces in order of distance (shortest paths between face centroids) while the
    // region stays a disc. A face refused because it would pinch the disc (one edge shared, its
    // third corner already taken from the other side) must be tried again when its other
    // neighbour joins: left out, the fronts passing on both sides of it leave a slit, and every
    // slit is a cut next to the seed (step 9 marks no face within a margin of a cut). On a capsule
    // built as modelling tools build one (fans of thin triangles at the poles) such slits cut the
    // patches at its caps down to a handful of faces each, and a thin capsule took 16 minutes.
    // Here: the disc is a topological disc, and every face within 0.6 of the radius by the same
    // path metric is in it.
    const std::vector<std::pair<std::string, Mesh>> meshes = {{"capsule", shapes::capsule(1.0, 2.0, 48, 16, 8)},
                                                              {"icosphere", isect::icosphere(1.0, 4)}};
    for (const auto& [name, mesh] : meshes) {
        SCOPED_TRACE(name);
        const auto nb = mq::quilt::face_neighbours(mesh);
        const std::size_t F = mesh.faces.size();
        const std::vector<Vec3> centroid = centroids_of(mesh);
        int seeds = 0, missing_seeds = 0;
        for (std::size_t seed = 0; seed < F; seed += 11) {
            const double radius = 0.7;
            const std::vector<int> disc = mq::quilt::grow_disc(mesh, nb, centroid, static_cast<int>(seed), radius);
            // Shortest paths between centroids from the seed (Dijkstra), the metric grow_disc uses.
            std::vector<double> dist(F, 1e300);
            using Item = std::pair<double, std::size_t>;
            std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
            dist[seed] = 0.0;
            queue.emplace(0.0, seed);
            while (!queue.empty()) {
                const auto [d, f] = queue.top();
                queue.pop();
                if (d > dist[f] || d > radius) continue;
                for (int g : nb[f]) {
                    if (g < 0) continue;
                    const auto gi = static_cast<std::size_t>(g);
                    const double nd = d + (centroid[gi] - centroid[f]).norm();
                    if (nd < dist[gi]) queue.emplace(dist[gi] = nd, gi);
                }
            }
            std::set<int> in(disc.begin(), disc.end());
            ASSERT_EQ(in.size(), disc.size());
            int missing = 0;
            for (std::size_t f = 0; f < F; ++f)
                if (dist[f] <= 0.6 * radius && !in.count(static_cast<int>(f))) ++missing;
            // A topological disc: one boundary loop and Euler characteristic 1 (V - E + F).
            std::map<std::pair<int, int>, int> edges;
            std::set<int> vertices;
            for (int f : disc)
                for (int k = 0; k < 3; ++k) {
                    const int a = mesh.faces[static_cast<std::size_t>(f)][k], b = mesh.faces[static_cast<std::size_t>(f)][(k + 1) % 3];
                    ++edges[{std::min(a, b), std::max(a, b)}];
                    vertices.insert(a);
                }
            std::map<int, int> rim_degree;
            for (const auto& [e, n] : edges)
                if (n == 1) {
                    ++rim_degree[e.first];
                    ++rim_degree[e.second];
                }
            const long euler = static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(disc.size());
            EXPECT_EQ(euler, 1) << "seed " << seed;
            for (const auto& [v, n] : rim_degree) EXPECT_EQ(n, 2) << "seed " << seed << ": the rim passes vertex " << v << " " << n / 2 << " times";
            ++seeds;
            if (missing > 0) {
                ++missing_seeds;
                ADD_FAILURE() << "seed " << seed << ": " << missing << " faces within 0.6 of the radius are not in the disc of " << disc.size();
            }
        }
        std::printf("%s: %d seeds, %d discs with faces missing near their seed\n", name.c_str(), seeds, missing_seeds);
    }
}

TEST(Patches, WithoutClosingSlitsADiscTakesLessAndNeverMore) {
    // grow_disc(..., close_slits = false) is the growth before session 56, which make_frame keeps
    // for thread swatches (whole discs cost the armadillo's weave 0.856 -> 0.644 in its lowest
    // region: docs/surface.md step 4; that choice itself is not held by a test). On the capsule's caps it leaves faces out that the growth closing slits takes (78
    // of the 341 discs here are smaller), and it never takes more.
    const Mesh mesh = shapes::capsule(1.0, 2.0, 48, 16, 8);
    const auto nb = mq::quilt::face_neighbours(mesh);
    const std::size_t F = mesh.faces.size();
    const std::vector<Vec3> centroid = centroids_of(mesh);
    int differ = 0, smaller = 0;
    for (std::size_t seed = 0; seed < F; seed += 11) {
        const std::vector<int> whole = mq::quilt::grow_disc(mesh, nb, centroid, static_cast<int>(seed), 0.7);
        const std::vector<int> slit = mq::quilt::grow_disc(mesh, nb, centroid, static_cast<int>(seed), 0.7, false);
        ASSERT_FALSE(slit.empty());
        EXPECT_EQ(slit.front(), static_cast<int>(seed));
        EXPECT_EQ(std::set<int>(slit.begin(), slit.end()).size(), slit.size());
        const std::set<int> slit_set(slit.begin(), slit.end()), whole_set(whole.begin(), whole.end());
        if (slit_set != whole_set) ++differ;
        if (slit.size() < whole.size()) ++smaller;
        EXPECT_TRUE(std::includes(whole_set.begin(), whole_set.end(), slit_set.begin(), slit_set.end())) << "seed " << seed;
    }
    std::printf("capsule: %d discs differ between the two growths, %d with slits are smaller\n", differ, smaller);
    EXPECT_GT(smaller, 10);
}

TEST(Flattening, RigidKeepsAreaOnACapWhereConformalDoesNot) {
    // A hemisphere's worth of an icosphere: a curved disc that no flattening keeps whole.
    const Mesh sphere = isect::icosphere(1.0, 4);
    std::vector<int> cap;
    for (std::size_t f = 0; f < sphere.faces.size(); ++f)
        if (mq::face_centroid(sphere, f).z() > 0.0) cap.push_back(static_cast<int>(f));
    ASSERT_GT(cap.size(), 500u);
    mq::quilt::FlatPatch lscm, arap;
    ASSERT_TRUE(mq::quilt::flatten_lscm(sphere, cap, &lscm));
    ASSERT_TRUE(mq::quilt::flatten_arap(sphere, cap, &arap, 10));
    const double d_lscm = mq::quilt::area_distortion(sphere, lscm), d_arap = mq::quilt::area_distortion(sphere, arap);
    std::printf("cap of %zu faces: area distortion (98th / 2nd percentile) LSCM %.3f, ARAP %.3f\n", cap.size(), d_lscm, d_arap);
    EXPECT_GT(d_lscm, 2.0) << "the cap is too flat to tell the flattenings apart";
    EXPECT_LT(d_arap, 0.6 * d_lscm);
    for (const mq::quilt::FlatPatch* p : {&lscm, &arap}) {
        // Same faces, counter-clockwise (no face turned over), one to one, the 3D area in all.
        EXPECT_EQ(p->faces, cap);
        ASSERT_EQ(p->uv.size(), p->vertices.size());
        EXPECT_EQ(turned_faces(*p), 0);
        EXPECT_EQ(stray_faces(*p), 0);
        double flat = 0.0, area = 0.0;
        for (std::size_t f = 0; f < p->local.size(); ++f) {
            const mq::Tri& t = p->local[f];
            const mq::Vec2 e1 = p->uv[static_cast<std::size_t>(t[1])] - p->uv[static_cast<std::size_t>(t[0])];
            const mq::Vec2 e2 = p->uv[static_cast<std::size_t>(t[2])] - p->uv[static_cast<std::size_t>(t[0])];
            flat += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
            area += mq::face_area(sphere, static_cast<std::size_t>(p->faces[f]));
        }
        EXPECT_NEAR(flat, area, 1e-9 * area);
    }
    // One triangle is its own flattening.
    mq::quilt::FlatPatch one;
    ASSERT_TRUE(mq::quilt::flatten_arap(sphere, {cap.front()}, &one, 10));
    const mq::Tri& t0 = sphere.faces[static_cast<std::size_t>(cap.front())];
    EXPECT_NEAR((one.uv[1] - one.uv[0]).norm(), (sphere.vertices[t0[1]] - sphere.vertices[t0[0]]).norm(), 1e-12);
}

TEST(Flattening, ARigidMapOfADiscTooCurvedToLieFlatStaysOneToOne) {
    // Discs that cannot lie flat at their area: caps of a sphere up to nearly all of it, a disc with
    // a wavy rim (z = r^2 sin 5t / 2, negative curvature all over: its rim is longer than a flat
    // disc's), and a helical ribbon of one and a half turns (radii 1 to 1.5, rising 0.05 per
    // radian), which lies flat as an annulus sector of about 540 degrees. Kept at their area they
    // would wrap over themselves; CGAL's ARAP mends such a map (its post-processing: measured, LSCM's
    // maps of the last three lie over themselves at 98, 1,138 and 2,160 faces, ARAP's at none).
    // Where it fails make_frame keeps LSCM's map.
    const Mesh sphere = isect::icosphere(1.0, 4);
    std::vector<std::pair<std::string, std::pair<Mesh, std::vector<int>>>> cases;
    for (double below : {-0.5, -0.95}) {
        std::vector<int> faces;
        for (std::size_t f = 0; f < sphere.faces.size(); ++f)
            if (mq::face_centroid(sphere, f).z() > below) faces.push_back(static_cast<int>(f));
        cases.push_back({"cap above z = " + std::to_string(below), {sphere, faces}});
    }
    {
        Mesh wavy;
        const int rings = 24, around = 120;
        wavy.vertices.push_back(Vec3::Zero());
        for (int i = 1; i <= rings; ++i)
            for (int j = 0; j < around; ++j) {
                const double r = static_cast<double>(i) / rings, t = 2.0 * M_PI * j / around;
                wavy.vertices.emplace_back(r * std::cos(t), r * std::sin(t), 0.5 * r * r * std::sin(5.0 * t));
            }
        const auto at = [&](int i, int j) { return i == 0 ? 0 : 1 + (i - 1) * around + (j % around); };
        for (int j = 0; j < around; ++j) wavy.faces.push_back({0, at(1, j), at(1, j + 1)});
        for (int i = 1; i < rings; ++i)
            for (int j = 0; j < around; ++j) {
                wavy.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                wavy.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        cases.push_back({"wavy disc", {wavy, all_faces(wavy)}});
    }
    {
        Mesh ribbon;
        const int across = 6, along = 270;
        for (int j = 0; j <= along; ++j)
            for (int i = 0; i <= across; ++i) {
                const double r = 1.0 + 0.5 * i / across, t = 3.0 * M_PI * j / along;
                ribbon.vertices.emplace_back(r * std::cos(t), r * std::sin(t), 0.05 * t);
            }
        const auto at = [&](int i, int j) { return j * (across + 1) + i; };
        for (int j = 0; j < along; ++j)
            for (int i = 0; i < across; ++i) {
                ribbon.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                ribbon.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        cases.push_back({"helical ribbon", {ribbon, all_faces(ribbon)}});
    }
    for (const auto& [name, c] : cases) {
        const auto& [mesh, faces] = c;
        mq::quilt::FlatPatch lscm, arap;
        ASSERT_TRUE(mq::quilt::flatten_lscm(mesh, faces, &lscm)) << name;
        const int lscm_stray = stray_faces(lscm);
        const bool ok = mq::quilt::flatten_arap(mesh, faces, &arap, 10);
        const int arap_stray = ok ? stray_faces(arap) : -1;
        std::printf("%s: %zu faces, LSCM %d stray, ARAP %s, %d stray\n", name.c_str(), faces.size(), lscm_stray, ok ? "done" : "failed", arap_stray);
        EXPECT_TRUE(ok) << name;
        EXPECT_EQ(arap_stray, 0) << name << ": the rigid map lies over itself";
    }
}

TEST(Cells, AFanOfSliversBecomesWellShapedCellsOnTheSameDisc) {
    // A round face as CAD exports it: 400 slivers of 0.9 degrees around one vertex.
    const Mesh fan = shapes::fan_disc(1.0, 400);
    ASSERT_LT(smallest_angle_degrees(fan), 1.0);
    std::vector<int> parent;
    int thin = -1;
    const Mesh cells = mq::quilt::refine_long_edges(fan, 0.05, &parent, &thin);
    EXPECT_EQ(thin, 400);
    std::printf("fan: %zu cells, smallest angle %.1f, %.2f%% of the angles under 15 degrees\n", cells.faces.size(), smallest_angle_degrees(cells),
                100.0 * share_of_angles_below(cells, 15.0));
    // Well shaped (measured: smallest angle 15.5 degrees, at the rim, whose edges are kept; the
    // target edge is 0.75 of the asked length). Edges about as long as asked: split_long_edges
    // leaves the new diagonals of a split face unchecked. The same flat disc: every vertex on the
    // plane and in the disc, every rim vertex kept (the boundary is split, never collapsed), so the
    // area is the fan's.
    EXPECT_GT(smallest_angle_degrees(cells), 12.0);
    EXPECT_LE(longest_edge(cells), 1.15 * 0.05);
    for (const Vec3& v : cells.vertices) {
        EXPECT_EQ(v.z(), 0.0);
        EXPECT_LE(std::hypot(v.x(), v.y()), 1.0 + 1e-12);
    }
    for (std::size_t i = 1; i < fan.vertices.size(); ++i) EXPECT_TRUE(has_vertex_at(cells, fan.vertices[i])) << "rim vertex " << i;
    EXPECT_NEAR(total_area(cells), total_area(fan), 1e-9);
    ASSERT_EQ(parent.size(), cells.faces.size());
    for (int p : parent) EXPECT_TRUE(p >= 0 && p < 400);
}

TEST(Cells, SliversOnACubeAreRemeshedKeepingItsEdgesAndCorners) {
    // Each face of the cube [-1, 1]^3 a fan of 4 x 24 slivers (3.75 degrees): sharp edges, corners.
    const Mesh cube = shapes::fan_cube(2.0, 24);
    ASSERT_TRUE(mq::test::is_closed_manifold(cube));
    ASSERT_NEAR(enclosed_volume(cube), 8.0, 1e-12);
    std::vector<int> parent;
    int thin = -1;
    const Mesh cells = mq::quilt::refine_long_edges(cube, 0.15, &parent, &thin);
    EXPECT_EQ(thin, static_cast<int>(cube.faces.size()));
    std::printf("cube: %zu cells, smallest angle %.1f, %.2f%% of the angles under 15 degrees\n", cells.faces.size(), smallest_angle_degrees(cells),
                100.0 * share_of_angles_below(cells, 15.0));
    EXPECT_TRUE(mq::test::is_closed_manifold(cells));
    EXPECT_GT(smallest_angle_degrees(cells), 12.0);  // measured 22.5
    EXPECT_LE(longest_edge(cells), 1.15 * 0.15);
    // Still the cube: every vertex on its surface, its 8 corners there, the volume unchanged (a
    // rounded edge or a corner cut would lose volume).
    for (const Vec3& v : cells.vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0, 1e-12);
    for (int i = 0; i < 8; ++i) EXPECT_TRUE(has_vertex_at(cells, Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1))) << "corner " << i;
    EXPECT_NEAR(enclosed_volume(cells), 8.0, 1e-9);
}

// A base that is thin faces all over is remeshed even where its clusters are small: the fan cube,
// one cluster of 24 area units, is under half a footprint (26 units) with cells of 1.2, where a few
// slivers amid well-shaped faces would be left (kThinClusterFootprints), but its thin faces cover
// all of it (kThinBaseShare): slivers crumple the shell map's prisms wherever they lie.
TEST(Cells, ABaseRiddledWithSliversIsRemeshedWhateverItsClusters) {
    const Mesh cube = shapes::fan_cube(2.0, 24);
    const double cell = 1.2;
    ASSERT_LT(total_area(cube), mq::quilt::kThinClusterFootprints * 36.0 * cell * cell);
    std::vector<int> parent;
    int thin = -1;
    const Mesh cells = mq::quilt::refine_long_edges(cube, cell, &parent, &thin);
    EXPECT_EQ(thin, static_cast<int>(cube.faces.size()));
    EXPECT_TRUE(mq::test::is_closed_manifold(cells));
    // Remeshed at the slivers' mean area (edges of about 0.155), along kept cube edges split every 0.083:
    // a few faces at the edges stay narrow (measured: smallest angle 6.4 degrees, 0.6% of the
    // angles under 10 degrees; the input's are all under 4).
    std::printf("riddled cube: %zu cells, smallest angle %.1f, %.2f%% of the angles under 10 degrees\n", cells.faces.size(),
                smallest_angle_degrees(cells), 100.0 * share_of_angles_below(cells, 10.0));
    EXPECT_GT(smallest_angle_degrees(cells), 5.0);
    EXPECT_LT(share_of_angles_below(cells, 10.0), 0.02);
    for (const Vec3& v : cells.vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0, 1e-12);
    EXPECT_NEAR(enclosed_volume(cells), 8.0, 1e-9);
}

// A face a footprint or more across (kLargeFaceCells) is remeshed: its split edges alone would
// leave a fan of slivers reaching across it, with no vertex inside (a 12-face cube's middles went
// bare). Its surface and its sharp edges and corners stay where they were.
TEST(Cells, FacesAFootprintAcrossAreRemeshedNotSplitIntoFans) {
    const Mesh cube = shapes::cube(2.0, Vec3(-1.0, -1.0, -1.0));  // faces 2 to 2.83 long
    const double cell = 0.1;                                        // 20 cells and more
    std::vector<int> parent;
    int thin = -1;
    const Mesh cells = mq::quilt::refine_long_edges(cube, cell, &parent, &thin);
    EXPECT_EQ(thin, 12);
    EXPECT_TRUE(mq::test::is_closed_manifold(cells));
    std::printf("large-faced cube: %zu cells, smallest angle %.1f, %.2f%% of the angles under 10 degrees\n", cells.faces.size(),
                smallest_angle_degrees(cells), 100.0 * share_of_angles_below(cells, 10.0));
    // Split only, the faces' middles hold no vertex and its angles fall far below 10 degrees.
    EXPECT_GT(smallest_angle_degrees(cells), 10.0);
    for (const Vec3& v : cells.vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0, 1e-12);
    EXPECT_NEAR(enclosed_volume(cells), 8.0, 1e-9);
    for (const Vec3& v : cube.vertices) EXPECT_TRUE(has_vertex_at(cells, v));
    int inside = 0;  // vertices in the middle ninth of some face
    for (const Vec3& v : cells.vertices) {
        const Vec3 a = v.cwiseAbs();
        int mid = 0;
        for (int k = 0; k < 3; ++k) mid += a[k] < 1.0 / 3.0 ? 1 : 0;
        inside += mid == 2 ? 1 : 0;
    }
    EXPECT_GT(inside, 6 * 20);
    // A face under a footprint across is only split, as before (Cells.AWellShapedBaseIsOnlySplit).
    (void)mq::quilt::refine_long_edges(cube, 2.9 / mq::quilt::kLargeFaceCells, &parent, &thin);
    EXPECT_EQ(thin, 0);
}

// A CSG plate with a hole (tests/data/surface/holed_plate.obj: manifold3d's difference and refine,
// so the hole's 48-sided rims are split into collinear pieces among slivers) is remeshed; the
// remesher's flips along the rims leave caps, faces on a rim's line or across one of its corners
// from the hole's side, whose normals fold the base (six vertices without a direction seeing their
// faces, then smoothed, and an inverted shell prism, on a plate with three holes) unless they are
// flipped back (quilt::kCapAngleDegrees).
TEST(Cells, NoCapsOrFoldsAlongAHolesRimAfterRemeshing) {
    const Mesh plate = mq::read_mesh(surface_data_path("holed_plate.obj"));
    ASSERT_TRUE(mq::test::is_closed_manifold(plate));
    std::vector<int> parent;
    int thin = -1;
    // At cells of 0.7 the remesher left 18 such vertices on this plate, faces of 180 degrees among them.
    Mesh cells = mq::quilt::refine_long_edges(plate, 0.7, &parent, &thin);
    EXPECT_GT(thin, static_cast<int>(plate.faces.size()) / 2);
    EXPECT_TRUE(mq::test::is_closed_manifold(cells));
    double largest = 0.0;
    for (const mq::Tri& t : cells.faces)
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = cells.vertices[t[(k + 1) % 3]] - cells.vertices[t[k]], b = cells.vertices[t[(k + 2) % 3]] - cells.vertices[t[k]];
            largest = std::max(largest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
        }
    std::printf("holed plate: %zu cells, angles %.1f to %.1f degrees\n", cells.faces.size(), smallest_angle_degrees(cells), largest);
    EXPECT_LT(largest, mq::quilt::kCapAngleDegrees);
    EXPECT_EQ(mq::shell::smooth_folds(cells, mq::shell::kMinSeeingCos), 0);
    // The same solid: the flips move the surface by at most a cap's height.
    EXPECT_NEAR(enclosed_volume(cells), enclosed_volume(plate), 1e-3 * enclosed_volume(plate));
}

TEST(Cells, AWellShapedBaseIsOnlySplit) {
    // No thin face: nothing is remeshed, and every input vertex stays where it was.
    const Mesh sphere = isect::icosphere(1.0, 3);
    std::vector<int> parent;
    int thin = -1;
    const Mesh cells = mq::quilt::refine_long_edges(sphere, 0.05, &parent, &thin);
    EXPECT_EQ(thin, 0);
    EXPECT_GT(cells.faces.size(), 4 * sphere.faces.size());
    for (const Vec3& v : sphere.vertices) EXPECT_TRUE(has_vertex_at(cells, v));
    EXPECT_NEAR(total_area(cells), total_area(sphere), 1e-9);
    // The eight's 16 thin faces (5-10 degrees, 3.5-4.5 cells long at scale 0.2) lie in clusters of
    // at most 0.05 footprints, each within one patch, and cover 2% of it: left as they are
    // (kThinClusterFootprints, kThinBaseShare).
    const Mesh eight = mq::read_mesh(surface_data_path("eight.obj"));
    const double cell = 0.2 * diagonal(eight) / 6.0;
    const Mesh eight_cells = mq::quilt::refine_long_edges(eight, cell, &parent, &thin);
    EXPECT_EQ(thin, 0);
    for (const Vec3& v : eight.vertices) EXPECT_TRUE(has_vertex_at(eight_cells, v));
    // ... while at a quarter of that cell its largest clusters are 0.75 footprints: remeshed.
    (void)mq::quilt::refine_long_edges(eight, cell / 4.0, &parent, &thin);
    EXPECT_GT(thin, 16);
}

// The further smoothing of bumpy bases is kept only where it mends the inverted prisms. In the
// slot block's slot (one unit wide, H = 0.6) it mends few, so it is refused and the walls'
// offset directions stay along their normals: 2.7 degrees off on average, 12.6 at worst (kept
// there, they would lean 23 degrees on average and 41 at worst, and elements in the slot shear).
TEST(ShellMap, ASlotsWallsKeepTheirNormalsAsOffsetDirections) {
    const Mesh base = slot_block(0.25);
    mq::ShellOptions o;
    o.height = 0.6;
    o.optimise = false;
    const mq::ShellMap s(base, o);
    const Mesh off = s.offset_surface();
    double worst = 0.0, sum = 0.0;
    int n = 0;
    for (std::size_t v = 0; v < base.vertices.size(); ++v) {
        const Vec3& p = base.vertices[v];
        const bool wall = (std::fabs(p.x() - 3.0) < 1e-9 || std::fabs(p.x() - 4.0) < 1e-9) && p.z() > 1.4 && p.z() < 2.6 && p.y() > 0.4 && p.y() < 2.6;
        if (!wall) continue;
        const Vec3 d = (off.vertices[v] - p).normalized();
        const double degrees = std::acos(std::min(1.0, std::fabs(d.x()))) * 180.0 / M_PI;
        worst = std::max(worst, degrees);
        sum += degrees;
        ++n;
    }
    ASSERT_GE(n, 40);
    std::cerr << "slot walls: " << n << " vertices, directions " << sum / n << " degrees off the wall normal on average, " << worst << " at worst\n";
    EXPECT_LT(sum / n, 6.0);
    EXPECT_LT(worst, 20.0);
}
