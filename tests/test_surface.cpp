// labels: property e2e
// Acceptance properties of surface mesh quilting (issue 3) on small bases of every kind: closed,
// genus 1 and 2, open, several components, inside-out, coarse (a cube), and the real "eight" and
// "spot" meshes.

#include "core/intersect.h"
#include "core/triangle_index.h"
#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/quilt.h"
#include "meshquilt/surface.h"
#include "quilt/swatch.h"
#include "support/checkers.h"
#include "support/paths.h"
#include "support/expect_error.h"
#include "support/shapes.h"
#include "support/shapes_isect.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <random>
#include <string>

namespace mq = meshquilt;
using meshquilt::test::swatch_path;
using meshquilt::test::surface_data_path;
using mq::Mesh;
using mq::Vec3;
namespace shapes = mq::test::shapes;
namespace isect = mq::test::isect;

namespace {

using mq::face_area;  // core/triangle_index.h

double area(const Mesh& m) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) a += face_area(m, f);
    return a;
}

/// An anisotropic swatch built here: long thin grains (ellipsoids 1.6 x 0.3 x 0.25) all along x, on
/// a jittered grid. Its layout has 2-fold symmetry.
Mesh grain_swatch() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jit(-0.08, 0.08);
    std::vector<Mesh> parts;
    const Mesh unit = isect::icosphere(1.0, 2);
    for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 5; ++i) {
            Mesh g = unit;
            const Vec3 c(1.0 + 2.0 * i + jit(rng), 0.5 + 1.0 * j + jit(rng), 0.25);
            for (Vec3& v : g.vertices) v = Vec3(0.8 * v.x(), 0.15 * v.y(), 0.125 * v.z()) + c;
            parts.push_back(std::move(g));
        }
    return mq::concatenate(parts).mesh;
}

struct SurfaceRun {
    Mesh swatch;  ///< as given
    mq::SurfaceQuiltResult r;
};

SurfaceRun quilt(const Mesh& base, const Mesh& swatch, double scale, std::uint64_t seed = 1, const mq::GuidanceField& field = {}) {
    mq::SurfaceQuiltOptions o;
    o.scale = scale;
    o.seed = seed;
    o.field = field;
    SurfaceRun run{swatch, mq::quilt_surface(base, swatch, o)};
    return run;
}

/// Every base face reached; every element closed; no two elements intersect (exact); no element
/// removed beyond 2%.
void expect_whole_and_disjoint(const SurfaceRun& run) {
    const auto& r = run.r;
    EXPECT_EQ(r.surface.base_faces_processed, r.surface.base_faces);
    ASSERT_GT(r.report.elements, 0);
    EXPECT_TRUE(mq::test::elements_closed(r.mesh, r.element_of_face));
    EXPECT_TRUE(mq::test::no_element_intersections(r.mesh, r.element_of_face));
    EXPECT_LE(r.report.elements_removed, 0.02 * (r.report.elements + r.report.elements_removed));
    ASSERT_EQ(r.anchors.size(), r.mesh.vertices.size());
    // No element folds through itself (embedding and height clamping included).
    int folded = 0;
    std::string first;
    const auto parts = mq::test::split_elements(r.mesh, r.element_of_face);
    for (std::size_t e = 0; e < parts.size(); ++e) {
        const auto ok = mq::test::no_self_intersections(parts[e]);
        if (!ok && folded++ == 0) first = "element " + std::to_string(e) + ": " + ok.message();
    }
    EXPECT_EQ(folded, 0) << first;
}

/// The tests' density regions: voxel cells of two footprints (at the run's scale), and the
/// swatch's element area per area in its window inset by 15% (as the planar measure).
struct VoxelRegions {
    Mesh swatch;  ///< the run's swatch, normalised (normalize_swatch)
    double swatch_density = 0.0;
    double fp_area = 0.0;  ///< a footprint's area on the base
    double cell = 1.0;
    [[nodiscard]] std::array<long, 3> key(const Vec3& p) const {
        return {std::lround(std::floor(p.x() / cell)), std::lround(std::floor(p.y() / cell)), std::lround(std::floor(p.z() / cell))};
    }
};

VoxelRegions voxel_regions(const SurfaceRun& run) {
    VoxelRegions vr;
    vr.swatch = mq::normalize_swatch(run.swatch);
    const Mesh& sw = vr.swatch;
    const mq::Box3 sb = mq::bounding_box(sw);
    const double mx = 0.15 * sb.size().x(), my = 0.15 * sb.size().y();
    double sa = 0.0;
    for (std::size_t f = 0; f < sw.faces.size(); ++f) {
        const Vec3 c = (sw.vertices[sw.faces[f][0]] + sw.vertices[sw.faces[f][1]] + sw.vertices[sw.faces[f][2]]) / 3.0;
        if (c.x() >= mx && c.x() <= sb.size().x() - mx && c.y() >= my && c.y() <= sb.size().y() - my) sa += face_area(sw, f);
    }
    vr.swatch_density = sa / ((sb.size().x() - 2 * mx) * (sb.size().y() - 2 * my));
    const double s = run.r.surface.base_scale;
    vr.fp_area = sb.size().x() * sb.size().y() * s * s;
    vr.cell = 2.0 * std::sqrt(vr.fp_area);
    return vr;
}

/// Element area per base area over regions of a coarse voxel partition of the base (cells of two
/// footprints), relative to the swatch's own density; regions with less than two footprints of
/// base area are left out. Returns {min, max}.
/// With `lift` > 0, each region's area is taken on the base offset by `lift` along its vertex
/// normals (area-weighted) instead: the surface the elements' middles stand on when `lift` is half
/// the shell's height, measured without the shell (which the report's region_density_mid_* map).
std::pair<double, double> region_density(const SurfaceRun& run, double lift = 0.0) {
    const auto& r = run.r;
    const Mesh& base = r.base;
    const VoxelRegions vr = voxel_regions(run);
    const double swatch_density = vr.swatch_density, fp_area = vr.fp_area, s = r.surface.base_scale;
    auto key = [&](const Vec3& p) { return vr.key(p); };
    // On an open base, elements stay whole and on the base, so a strip along the boundary as wide as
    // half the largest element is necessarily bare: it is left out (as the planar measure insets
    // its window).
    std::map<std::pair<int, int>, int> edge_count;
    for (const auto& t : base.faces)
        for (int k = 0; k < 3; ++k) ++edge_count[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    std::vector<Vec3> rim;
    for (const auto& [e, n] : edge_count)
        if (n == 1) rim.push_back(0.5 * (base.vertices[static_cast<std::size_t>(e.first)] + base.vertices[static_cast<std::size_t>(e.second)]));
    const Mesh& sw = vr.swatch;
    double element_diag = 0.0;
    {
        int n = 0;
        const std::vector<int> comp = mq::connected_components(sw, &n);
        std::vector<mq::Box3> boxes(static_cast<std::size_t>(n));
        for (std::size_t f = 0; f < sw.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) boxes[static_cast<std::size_t>(comp[f])].extend(sw.vertices[sw.faces[f][k]]);
        for (const auto& b : boxes) element_diag = std::max(element_diag, std::hypot(b.size().x(), b.size().y()));
    }
    const double strip = 0.5 * element_diag * s;
    std::map<std::array<long, 3>, std::pair<double, double>> cells;  // base area, element area
    std::vector<std::array<long, 3>> key_of_face(base.faces.size());
    std::vector<char> in_strip(base.faces.size(), 0);
    for (std::size_t f = 0; f < base.faces.size(); ++f) {
        const Vec3 c = (base.vertices[base.faces[f][0]] + base.vertices[base.faces[f][1]] + base.vertices[base.faces[f][2]]) / 3.0;
        for (const Vec3& q : rim)
            if ((q - c).norm() < strip) {
                in_strip[f] = 1;
                break;
            }
        key_of_face[f] = key(c);
    }
    std::vector<Vec3> normal(base.vertices.size(), Vec3::Zero());
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) normal[static_cast<std::size_t>(base.faces[f][k])] += face_cross(base, f);
    for (Vec3& n : normal) n = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero();
    for (std::size_t f = 0; f < base.faces.size(); ++f) {
        if (in_strip[f]) continue;
        std::array<Vec3, 3> q;
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(base.faces[f][k]);
            q[static_cast<std::size_t>(k)] = base.vertices[v] + lift * normal[v];
        }
        cells[key_of_face[f]].first += 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm();
    }
    for (std::size_t f = 0; f < r.mesh.faces.size(); ++f) {
        const auto bf = static_cast<std::size_t>(r.anchors[static_cast<std::size_t>(r.mesh.faces[f][0])].face);
        if (!in_strip[bf]) cells[key_of_face[bf]].second += face_area(r.mesh, f);
    }
    double lo = 1e300, hi = 0.0;
    int counted = 0;
    for (const auto& [k, v] : cells) {
        if (v.first < 2.0 * fp_area) continue;
        ++counted;
        const double ratio = v.second / v.first / swatch_density;
        lo = std::min(lo, ratio);
        hi = std::max(hi, ratio);
    }
    if (counted == 0) return {0.0, 0.0};
    return {lo, hi};
}

/// Element density by count over the same voxel regions as region_density (cells of two
/// footprints, regions under two footprints of base area left out): each element counted once, in
/// the cell of the base face closest to its area centroid, weighing its swatch element's area at
/// the scale, over the cell's base area and the swatch's density. Blind to what the embedding does
/// to an element's area. For whole elements (not threads); open bases are not handled (no strip).
/// Returns {min, max}.
std::pair<double, double> region_count_density(const SurfaceRun& run) {
    const VoxelRegions vr = voxel_regions(run);
    const auto& r = run.r;
    const Mesh& base = r.base;
    const double s = r.surface.base_scale;
    int count = 0;
    const std::vector<int> comp = mq::connected_components(run.swatch, &count);
    std::vector<double> source_area(static_cast<std::size_t>(count), 0.0);
    for (std::size_t f = 0; f < comp.size(); ++f) source_area[static_cast<std::size_t>(comp[f])] += face_area(run.swatch, f);
    std::map<std::array<long, 3>, std::pair<double, double>> cells;  // base area, counted swatch area
    for (std::size_t f = 0; f < base.faces.size(); ++f)
        cells[vr.key((base.vertices[base.faces[f][0]] + base.vertices[base.faces[f][1]] + base.vertices[base.faces[f][2]]) / 3.0)].first += face_area(base, f);
    const mq::TriangleIndex index(base);
    const auto parts = mq::test::split_elements(r.mesh, r.element_of_face);
    for (std::size_t e = 0; e < parts.size(); ++e) {
        Vec3 c = Vec3::Zero();
        double a = 0.0;
        for (std::size_t f = 0; f < parts[e].faces.size(); ++f) {
            const double fa = face_area(parts[e], f);
            c += fa * (parts[e].vertices[parts[e].faces[f][0]] + parts[e].vertices[parts[e].faces[f][1]] + parts[e].vertices[parts[e].faces[f][2]]) / 3.0;
            a += fa;
        }
        const int bf = index.closest(c / a).face;
        const auto& t = base.faces[static_cast<std::size_t>(bf)];
        cells[vr.key((base.vertices[t[0]] + base.vertices[t[1]] + base.vertices[t[2]]) / 3.0)].second +=
            source_area[static_cast<std::size_t>(r.source_element[e])] * s * s;
    }
    double lo = 1e300, hi = 0.0;
    for (const auto& [k, v] : cells) {
        if (v.first < 2.0 * vr.fp_area) continue;
        const double ratio = v.second / v.first / vr.swatch_density;
        lo = std::min(lo, ratio);
        hi = std::max(hi, ratio);
    }
    if (hi == 0.0) return {0.0, 0.0};
    return {lo, hi};
}

/// Each element's size (the square root of its area) within a factor `factor` of its swatch
/// element's size at the scale used.
/// ... and, with `floor` > 0, none smaller than `floor` of its swatch element's size: the stage's
/// size floor (kMinElementSize, 0.7, in src/quilt/surface.cpp) refuses or enlarges placed elements
/// below it. Only for runs without a field or --height (the floor then measures what this does).
void expect_element_sizes(const SurfaceRun& run, double factor, double floor = 0.0) {
    const auto& r = run.r;
    int count = 0;
    const std::vector<int> comp = mq::connected_components(run.swatch, &count);
    std::vector<double> source_area(static_cast<std::size_t>(count), 0.0);
    for (std::size_t f = 0; f < comp.size(); ++f) source_area[static_cast<std::size_t>(comp[f])] += face_area(run.swatch, f);
    const auto parts = mq::test::split_elements(r.mesh, r.element_of_face);
    const double s2 = r.surface.base_scale * r.surface.base_scale;
    // A thinned swatch (its elements intersect or stand tight) is quilted thinned, and the stage's
    // floor holds against the thinned elements; thickened back, an element grows towards its
    // swatch element's size, less where a neighbour stands close, at worst not at all. So its floor
    // is `floor` of its thinned element's size.
    const bool thinned = std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) { return w.find("quilted thinned") != std::string::npos; });
    std::vector<double> floor_of(source_area.size(), floor);
    if (thinned) {
        const mq::quilt::SwatchData prepared = mq::quilt::prepare_swatch(run.swatch);
        EXPECT_GT(prepared.thinned, 0.0);
        EXPECT_EQ(prepared.elements.size(), source_area.size());
        for (std::size_t e = 0; e < std::min(prepared.elements.size(), source_area.size()); ++e)
            floor_of[e] = floor * std::sqrt(mq::quilt::mesh_area(prepared.elements[e]) / source_area[e]);
    }
    int bad = 0, off = 0;
    double lo = 1e300, hi = 0.0;
    std::string first;
    for (std::size_t e = 0; e < parts.size(); ++e) {
        const double want = source_area[static_cast<std::size_t>(r.source_element[e])] * s2;
        const double ratio = std::sqrt(area(parts[e]) / want);
        lo = std::min(lo, ratio);
        hi = std::max(hi, ratio);
        off += ratio > 1.5 || ratio < 1.0 / 1.5;
        if (ratio > factor || ratio < std::max(1.0 / factor, floor_of[static_cast<std::size_t>(r.source_element[e])])) {
            if (bad++ == 0) first = "element " + std::to_string(e) + " has " + std::to_string(ratio) + " times its swatch element's size";
        }
    }
    EXPECT_EQ(bad, 0) << first;
    // The report measures the same (before a thinned swatch's elements are thickened back: then
    // it compares thinned with thinned, and this measure thickened with the swatch as given).
    if (!thinned && !parts.empty()) {
        EXPECT_EQ(r.surface.elements_sized, static_cast<int>(parts.size()));
        EXPECT_NEAR(r.surface.element_size_min, lo, 1e-9 * lo);
        EXPECT_NEAR(r.surface.element_size_max, hi, 1e-9 * hi);
        EXPECT_EQ(r.surface.elements_off_size, off);
    }
}

/// No element is torn: none of its faces is larger than `factor` times the swatch's largest face
/// (at the output's scale). An element whose embedding pulled part of it elsewhere (an old
/// thread's part beyond a patch joined to a part the patch's map puts elsewhere) shows a fan of
/// faces 5-10 times that (docs/surface.md, step 7).
void expect_no_torn_faces(const SurfaceRun& run, double factor) {
    const auto& r = run.r;
    double largest = 0.0;
    for (std::size_t f = 0; f < run.swatch.faces.size(); ++f) largest = std::max(largest, face_area(run.swatch, f));
    const double limit = factor * largest * r.surface.base_scale * r.surface.base_scale;
    int bad = 0;
    std::string first;
    for (std::size_t f = 0; f < r.mesh.faces.size(); ++f)
        if (face_area(r.mesh, f) > limit && bad++ == 0)
            first = "a face of element " + std::to_string(r.element_of_face[f]) + " has " + std::to_string(face_area(r.mesh, f) / limit * factor) +
                    " times the swatch's largest face area";
    EXPECT_EQ(bad, 0) << first;
}

/// Principal direction (largest spread) of an element's vertices, projected onto the plane with
/// normal n.
Vec3 principal_direction(const Mesh& m, const Vec3& n) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : m.vertices) c += v;
    c /= static_cast<double>(m.vertices.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& v : m.vertices) {
        Vec3 d = v - c;
        d -= d.dot(n) * n;
        cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    return es.eigenvectors().col(2);
}

double angle_mod_pi(const Vec3& a, const Vec3& b) {
    const double c = std::fabs(a.normalized().dot(b.normalized()));
    return std::acos(std::min(1.0, c));
}

Vec3 element_centroid(const Mesh& m) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : m.vertices) c += v;
    return c / static_cast<double>(m.vertices.size());
}

// ---------------------------------------------------------------------------------------------
// Coverage, integrity, density, element size on bases of every kind.

struct BaseCase {
    std::string name;
    std::function<Mesh()> make;
    std::string swatch;
    double scale;
    /// Each element within 1.5 of its swatch element's size. Off for threads, which are stitched
    /// across patches into elements longer than the swatch's (the planar tests check that they are).
    bool sizes = true;
    // Every case is held to the density within 15% in every region (chain mail on the eight since
    // session 20's ring holes; before, to its measured lowest region).
};

class SurfaceBases : public ::testing::TestWithParam<BaseCase> {};

TEST_P(SurfaceBases, CoversEveryTriangleWithWholeDisjointElementsAtTheSwatchDensity) {
    const BaseCase& c = GetParam();
    const Mesh swatch = mq::read_mesh(swatch_path(c.swatch));
    const SurfaceRun run = quilt(c.make(), swatch, c.scale);
    expect_whole_and_disjoint(run);
    expect_no_torn_faces(run, 4.0);
    // The eight's chain mail meets placements that the map tears (6 at seed 1, faces up to 1.25
    // times the bound): the stage refuses them, so the output above holds none.
    if (c.name == "eight_chainmail") EXPECT_GT(run.r.surface.elements_torn, 0);
    if (c.sizes) {
        expect_element_sizes(run, 1.5, 0.7);
    } else {
        // Threads: old ones reaching beyond a patch were handed to the kernel and stitched; new
        // ones that collided or reached off their patch were cut and their free parts kept.
        EXPECT_GT(run.r.surface.threads_extended, 0);
        EXPECT_GT(run.r.report.elements_stitched, 0);
        EXPECT_GT(run.r.surface.threads_trimmed, 0);
        EXPECT_GE(run.r.surface.thread_pieces, run.r.surface.threads_trimmed);
        EXPECT_GT(run.r.surface.threads_cut_at_patch, 0);
        // Gaps left between threads running one way got a thread laid along them, right after
        // their patch and (gaps across a footprint's edge, or opened by later patches) after the last.
        EXPECT_GT(run.r.surface.threads_filled, 0);
        // On a developable base (the tube) the patches' lattices agree and their own filling may
        // leave nothing to mend; on a doubly curved one it does not.
        if (c.name != "tube_weave") EXPECT_GT(run.r.surface.threads_mended, 0);
        EXPECT_GE(run.r.surface.threads_filled, run.r.surface.threads_mended);
        // ... and where the threads beside a gap run at an angle to the patch's frame (another
        // patch's lattice on a doubly curved base), some go in turned to run with them.
        if (c.name != "tube_weave") EXPECT_GT(run.r.surface.threads_turned, 0);
        EXPECT_GE(run.r.surface.threads_filled, run.r.surface.threads_turned);
    }
    // Joints wider than the swatch's are closed on a paving only (cobbles' joints are a tenth of
    // a stone; pebbles' and rivets' half of one or more).
    // After the last patch the holes where several stones meet are closed too (quilt::grow_into_gaps).
    if (c.swatch == "cobbles") {
        EXPECT_GT(run.r.report.joints_closed, 0);
        EXPECT_GT(run.r.surface.gaps_closed, 0);
        EXPECT_LE(run.r.surface.gaps_closed, run.r.report.joints_closed);
    } else {
        EXPECT_EQ(run.r.report.joints_closed, 0);
        EXPECT_EQ(run.r.surface.gaps_closed, 0);
    }
    // Overlapping scales (a layered swatch) fill bald spots by the 3D test alone (no footprint
    // squeeze): 0.870-0.967 without, 0.920-0.975 with, on the eight.
    if (c.swatch == "scales") EXPECT_GT(run.r.report.bald_spots_filled, 0);
    // Lattice slots left empty after the last patch are mended for rings and for a layered
    // swatch's blobs (scales lie in rows); other blobs fill bald spots instead.
    if (c.swatch == "scales") EXPECT_GT(run.r.surface.elements_mended, 0);
    // ... and a layered swatch's merge losers that keep clear of their winners in 3D stay whole
    // beside them (quilt::KernelParams::layer_gap); no other swatch has such losers.
    if (c.swatch == "scales") EXPECT_GT(run.r.report.losers_kept, 0);
    else EXPECT_EQ(run.r.report.losers_kept, 0);
    if (c.swatch == "rivets" || c.swatch == "pebbles" || c.swatch == "cobbles") EXPECT_EQ(run.r.surface.elements_mended, 0);
    // Free elements' patches are flattened again as rigid as possible; a lattice's keep LSCM's angles.
    if (c.swatch == "chainmail" || c.swatch == "weave") EXPECT_EQ(run.r.surface.patches_rigid, 0);
    else EXPECT_GT(run.r.surface.patches_rigid, run.r.report.patches / 2);
    // The CAD-like bases' slivers were remeshed on the synthesis's copy (all of their faces are thin).
    if (c.name.rfind("fan_", 0) == 0) EXPECT_EQ(run.r.surface.base_thin_faces_remeshed, static_cast<int>(c.make().faces.size()));
    // ... and so were the large faces of a low-poly base (patch.h, kLargeFaceCells).
    if (c.name == "cube") EXPECT_EQ(run.r.surface.base_thin_faces_remeshed, 12);
    const auto [lo, hi] = region_density(run);
    RecordProperty("density_min", std::to_string(lo));
    RecordProperty("density_max", std::to_string(hi));
    std::printf("%s + %s: region density %.3f - %.3f of the swatch's (the report's %.3f - %.3f; threads laid into gaps %d, after the last patch %d)\n",
                c.name.c_str(), c.swatch.c_str(), lo, hi, run.r.surface.region_density_min, run.r.surface.region_density_max,
                run.r.surface.threads_filled, run.r.surface.threads_mended);
    // On an open base the report's regions leave out the strip along the boundary that whole
    // elements cannot fill, as this measure does, so the two lowest regions agree (measured within
    // 0.019 on the fan disc, the tube and the cylinder; 0.038-0.074 when the report counted the strip).
    if (mq::analyse(run.r.base).boundary_edges > 0) EXPECT_NEAR(run.r.surface.region_density_min, lo, 0.035);
    ASSERT_GT(hi, 0.0) << "no region of two footprints: choose a smaller scale";
    EXPECT_GE(lo, 0.85) << "a region is balder than the swatch";
    EXPECT_LE(hi, 1.15) << "a region is denser than the swatch";
    // The paving's holes closed after the last patch lift its thinnest region (0.931; 0.891
    // when only straight sides were pushed into joints).
    if (c.swatch == "cobbles") EXPECT_GE(lo, 0.91) << "the holes between the patches' stones were left open";
    // Threads laid into a weave's gaps are squashed where a crossing thread leaves less room than
    // their thickness (quilt::woven) and turned with the threads beside the gap: the eight's
    // thinnest region 0.899 -> 0.930, the torus's 0.932 -> 0.950 (session 33).
    if (c.swatch == "weave") EXPECT_GE(lo, 0.91) << "the gaps between the patches' threads were left open";
    // Counted (each element once, at its swatch element's area): threads have no count, and the
    // report says so; whole elements are as many per area as in the swatch, however the
    // embedding changed their area. Seed 1 (session 51, fills judged by the ground blobs claim on
    // the base): rivets 0.880-0.984 at worst (the sphere, the eight), pebbles 0.983-1.098 (the
    // sphere) and 0.991-1.149 (the eight), cobbles 0.877-0.942, scales 0.933-1.037, the eight's chain
    // mail 0.960-1.125 (the report's 0.983-1.126; 1.161 and 1.188 while mended rings were counted
    // in the lattice's spacing, docs/surface.md step 10). Session 53 (free elements' frames
    // flattened by ARAP, step 4): rivets 0.899-0.975 at worst (spot, the sphere), pebbles
    // 0.966-1.068 (the sphere) and 0.986-1.107 (the eight), cobbles 0.869-0.973, scales 0.956-1.053.
    const auto& sr = run.r.surface;
    if (!c.sizes) {
        EXPECT_EQ(sr.region_count_density_min, 0.0);
        EXPECT_EQ(sr.region_count_density_max, 0.0);
    } else {
        ASSERT_GT(sr.region_count_density_max, 0.0);
        EXPECT_LE(sr.region_count_density_min, sr.region_count_density_max);
        if (mq::analyse(run.r.base).boundary_edges == 0) {
            const auto [clo, chi] = region_count_density(run);
            std::printf("%s + %s: counted %.3f - %.3f (the report's %.3f - %.3f)\n", c.name.c_str(), c.swatch.c_str(), clo, chi,
                        sr.region_count_density_min, sr.region_count_density_max);
            EXPECT_GE(clo, 0.85) << "a region holds fewer elements than the swatch";
            EXPECT_LE(chi, 1.15) << "a region holds more elements than the swatch";
            EXPECT_GE(sr.region_count_density_min, 0.85);
            EXPECT_LE(sr.region_count_density_max, 1.15);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Bases, SurfaceBases,
    ::testing::Values(BaseCase{"sphere", [] { return isect::icosphere(1.0, 3); }, "rivets", 0.22},
                      BaseCase{"torus", [] { return shapes::torus(2.0, 0.7, 48, 24); }, "rivets", 0.2},
                      BaseCase{"eight", [] { return mq::read_mesh(surface_data_path("eight.obj")); }, "rivets", 0.2},
                      BaseCase{"spot", [] { return mq::read_mesh(surface_data_path("spot.obj")); }, "rivets", 0.2},
                      BaseCase{"cylinder_chainmail", [] { return shapes::open_cylinder(1.0, 2.0, 64, 32); }, "chainmail", 0.2},
                      BaseCase{"sphere_pebbles", [] { return isect::icosphere(1.0, 3); }, "pebbles", 0.22},
                      // A 12-face cube: its faces are 24 cells across, which split edges alone
                      // would have turned into fans of slivers (0.719 in the thinnest region).
                      BaseCase{"cube", [] { return shapes::cube(2.0); }, "rivets", 0.15},
                      BaseCase{"eight_chainmail", [] { return mq::read_mesh(surface_data_path("eight.obj")); }, "chainmail", 0.2},
                      BaseCase{"tube_weave", [] { return mq::read_mesh(surface_data_path("tube.obj")); }, "weave", 0.2, false},
                      BaseCase{"torus_weave", [] { return shapes::torus(2.0, 0.7, 48, 24); }, "weave", 0.2, false},
                      BaseCase{"eight_weave", [] { return mq::read_mesh(surface_data_path("eight.obj")); }, "weave", 0.2, false},
                      BaseCase{"eight_pebbles", [] { return mq::read_mesh(surface_data_path("eight.obj")); }, "pebbles", 0.2},
                      BaseCase{"torus_cobbles", [] { return shapes::torus(2.0, 0.7, 48, 24); }, "cobbles", 0.2},
                      BaseCase{"eight_scales", [] { return mq::read_mesh(surface_data_path("eight.obj")); }, "scales", 0.2},
                      // CAD-like triangulations: a round face as one fan of slivers (0.56 of the
                      // density in its thinnest region, and 159 s, before thin faces were remeshed;
                      // 0.96, 4.3 s after), and a cube whose faces are fans (sharp edges kept; 0.97
                      // before in 36 s, 0.92 after in 15 s).
                      BaseCase{"fan_disc", [] { return shapes::fan_disc(1.0, 400); }, "rivets", 0.2},
                      BaseCase{"fan_cube", [] { return shapes::fan_cube(2.0, 24); }, "rivets", 0.25}),
    [](const auto& info) { return info.param.name; });

// The stages that run in parallel (the kernel's merge plans, the tries of a thread laid into a
// gap, the embedding of a patch's changes, the batches of a mended ring's poses) take their
// results in a fixed order, so one thread gives the output that all give, to the bit. The weave
// exercises the threads laid into gaps and cut clear of folds and tears; the chain mail the
// mended rings, whose batches are as many poses as twice the cores (two with one thread).
class SurfaceThreads : public ::testing::TestWithParam<const char*> {};

TEST_P(SurfaceThreads, OneThreadGivesTheOutputOfAll) {
    const Mesh base = mq::read_mesh(surface_data_path("eight.obj"));
    const Mesh swatch = mq::read_mesh(swatch_path(GetParam()));
    const SurfaceRun all = quilt(base, swatch, 0.4);
    const SurfaceRun one = [&] {
        const tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
        return quilt(base, swatch, 0.4);
    }();
    if (std::string(GetParam()) == "weave") {
        EXPECT_GT(all.r.surface.threads_filled, 0);
        EXPECT_GT(all.r.surface.threads_torn, 0);
    }
    if (std::string(GetParam()) == "chainmail") {
        EXPECT_GT(all.r.surface.elements_mended, 0);
        EXPECT_GT(all.r.surface.ring_holes_filled, 0);
    }
    EXPECT_GT(all.r.surface.elements_folded, 0);
    // The counters the parallel stages keep per task and sum, or per try taken in order.
    EXPECT_EQ(all.r.surface.elements_mended, one.r.surface.elements_mended);
    EXPECT_EQ(all.r.surface.ring_holes_filled, one.r.surface.ring_holes_filled);
    EXPECT_EQ(all.r.surface.elements_torn, one.r.surface.elements_torn);
    EXPECT_EQ(all.r.surface.elements_folded, one.r.surface.elements_folded);
    EXPECT_EQ(all.r.surface.threads_torn, one.r.surface.threads_torn);
    EXPECT_EQ(all.r.surface.elements_enlarged, one.r.surface.elements_enlarged);
    EXPECT_EQ(all.r.report.elements, one.r.report.elements);
    ASSERT_EQ(all.r.mesh.vertices.size(), one.r.mesh.vertices.size());
    ASSERT_EQ(all.r.mesh.faces.size(), one.r.mesh.faces.size());
    std::size_t differ = 0;
    for (std::size_t v = 0; v < all.r.mesh.vertices.size(); ++v) differ += all.r.mesh.vertices[v] != one.r.mesh.vertices[v];
    EXPECT_EQ(differ, 0u) << "vertices differ between one thread and all";
    EXPECT_TRUE(all.r.mesh.faces == one.r.mesh.faces);
}

INSTANTIATE_TEST_SUITE_P(Swatches, SurfaceThreads, ::testing::Values("weave", "chainmail"));

// ---------------------------------------------------------------------------------------------

// Knot work (swatches/knots.obj): strands, closed and genus 0 but several times longer than wide
// (quilt::is_strand), are never squeezed or shrunk to fit, and fill bald spots whole or as pieces.
// Before (session 41), on the eight at scale 0.2: the report's region density 0.682-0.744, smallest
// element 0.741 of its swatch element's size (squeezed and shrunk strands); after 0.773-0.812 (this
// test's measure 0.754-0.833) and 0.858. Since session 42 a strand that does not go in whole (a new
// one that meets the output, a merge's loser, one too long for a bald spot) goes in as its pieces cut
// across it clear of what it crosses (quilt::strand_pieces), as an under-crossing of knot work stops
// short: 0.819-0.848 (this test's measure 0.823-0.867). Pieces and stitched strands have any length and
// are not measured against their swatch element's size; the whole ones measure 0.945-1.090.
TEST(Surface, KnotStrandsGoOnWhole) {
    const SurfaceRun run = quilt(mq::read_mesh(surface_data_path("eight.obj")), mq::read_mesh(swatch_path("knots")), 0.2);
    expect_whole_and_disjoint(run);
    expect_no_torn_faces(run, 4.0);
    // The report's sizes of the whole strands (pieces, and strands stitched longer, are left out).
    EXPECT_GT(run.r.surface.elements_sized, run.r.report.elements / 2);
    EXPECT_GE(run.r.surface.element_size_min, 0.85);
    EXPECT_EQ(run.r.surface.elements_off_size, 0);
    EXPECT_EQ(run.r.report.elements_squeezed, 0);
    EXPECT_GT(run.r.report.bald_spots_filled, 0);
    EXPECT_GT(run.r.report.strand_pieces, 100);
    const auto [lo, hi] = region_density(run);
    std::printf("eight + knots: region density %.3f - %.3f of the swatch's\n", lo, hi);
    EXPECT_GE(lo, 0.8);
    EXPECT_LE(hi, 1.15);
}

// A swatch of open caps, each one sheet (tests/data/planar/open_caps.obj): none is joined rim to
// rim into a closed blob (17 of 375 on this run before session 44), none meets another, bald spots
// take caps as they take blobs, and every region holds the swatch's density within 15%.
TEST(Surface, OpenElementsStayOpenAndFillBaldSpots) {
    const Mesh caps = mq::read_mesh(std::string(MQ_TEST_DATA_DIR) + "/planar/open_caps.obj");
    const SurfaceRun run = quilt(mq::read_mesh(surface_data_path("eight.obj")), caps, 0.2);
    const auto& r = run.r;
    EXPECT_EQ(r.surface.base_faces_processed, r.surface.base_faces);
    EXPECT_GT(r.report.elements, 300);
    EXPECT_EQ(r.report.elements_closed, 0);
    EXPECT_EQ(r.report.elements_stitched, 0);
    EXPECT_GT(r.report.bald_spots_filled, 0);
    EXPECT_TRUE(mq::test::no_element_intersections(r.mesh, r.element_of_face));
    expect_element_sizes(run, 1.5, 0.7);
    const auto [lo, hi] = region_density(run);
    std::printf("eight + open caps: region density %.3f - %.3f of the swatch's\n", lo, hi);
    EXPECT_GE(lo, 0.85);
    EXPECT_LE(hi, 1.15);
}

TEST(Surface, OpenBaseIsCoveredAndElementsStayOnIt) {
    const Mesh base = shapes::open_cylinder(1.0, 3.0, 48, 24);
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("pebbles")), 0.2);
    expect_whole_and_disjoint(run);
    // The report's regions are within the bar on an open base too (measured 0.992 lowest; the Bases
    // tests compare the report's measure with their own on open bases). Dense spots are thinned
    // with the strip along the rim left out of their windows, as the report leaves it out
    // (session 56): seed 1, by count 0.949-1.069 and 5 thinned before, 0.939-1.062 and 16 after;
    // by area 1.022-1.084 before, 1.015-1.045 after. (This base passed the bar before too; the
    // camelhead's neck, docs/surface.md step 11, is where it did not.)
    std::printf("open cylinder + pebbles: report's region density %.3f - %.3f, by count %.3f - %.3f, thinned %d\n", run.r.surface.region_density_min, run.r.surface.region_density_max, run.r.surface.region_count_density_min, run.r.surface.region_count_density_max, run.r.surface.elements_thinned);
    EXPECT_GE(run.r.surface.region_density_min, 0.85);
    EXPECT_LE(run.r.surface.region_density_max, 1.15);
    EXPECT_GE(run.r.surface.region_count_density_min, 0.85);
    EXPECT_LE(run.r.surface.region_count_density_max, 1.15);
    EXPECT_GT(run.r.surface.elements_thinned, 0);
    // Elements sit outside the cylinder (along the outward normals) and within its height.
    for (const Vec3& v : run.r.mesh.vertices) {
        EXPECT_GE(std::hypot(v.x(), v.y()), 0.97);
        EXPECT_GE(v.z(), -0.05);
        EXPECT_LE(v.z(), 3.05);
    }
}

// Where two patches meet, each keeps its elements only the swatch's smallest gap from the other's,
// so seams pack free elements closer than the swatch spaces them, and where seams cross, the count
// rose above the bar: pebbles on the eight read 1.107 / 1.143 / 1.167 in the densest region at
// seeds 1-3. After the last patch, spots denser than the swatch give up their most crowded
// elements (thin_dense_spots, docs/surface.md step 11): 1.107 / 1.119 / 1.064 (with session 56's
// discs, grow_disc: 1.087 / 1.085 / 1.040). Every seed, not
// one: the densest region is the tail of the seeds' spread, and one seed can pass it by luck.
TEST(Surface, PebblesAreWithinTheBarAtEverySeed) {
    const Mesh base = mq::read_mesh(surface_data_path("eight.obj"));
    const Mesh swatch = mq::read_mesh(swatch_path("pebbles"));
    int thinned = 0;
    for (std::uint64_t seed : {1, 2, 3}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const SurfaceRun run = quilt(base, swatch, 0.2, seed);
        expect_whole_and_disjoint(run);
        const auto [lo, hi] = region_count_density(run);
        const auto& s = run.r.surface;
        std::printf("eight + pebbles, seed %d: %d elements, %d thinned; counted %.3f - %.3f (the report's %.3f - %.3f)\n", static_cast<int>(seed),
                    run.r.report.elements, s.elements_thinned, lo, hi, s.region_count_density_min, s.region_count_density_max);
        EXPECT_GE(lo, 0.85);
        EXPECT_LE(hi, 1.15);
        EXPECT_GE(s.region_count_density_min, 0.85);
        EXPECT_LE(s.region_count_density_max, 1.15);
        thinned += s.elements_thinned;
    }
    EXPECT_GT(thinned, 0);
}

// A part thinner than the footprint, with the fans of thin triangles at the poles that modelling
// tools' capsules and UV spheres have: each patch's disc must still reach its seed's neighbourhood
// (grow_disc, tests Patches.*), or each patch marks a handful of faces processed and the run takes
// thousands of patches (trimesh's capsule of radius 0.1 and length 1, subdivided once, at
// --swatch-size 0.2: 1,239 patches and 298 s before, 103 and 15 s after; radius 0.06: 4,220
// patches and 16 minutes, 155 and 21 s). The capsule here is built as trimesh builds it.
TEST(Surface, AThinCapsuleIsCoveredInFewPatches) {
    const Mesh base = shapes::subdivided(shapes::capsule(0.1, 1.0, 48, 24, 1));  // trimesh's capsule(radius=0.1, height=1).subdivide()
    const double diag = mq::bounding_box(base).size().norm();
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("pebbles")), 0.2 / diag);
    expect_whole_and_disjoint(run);
    const auto& s = run.r.surface;
    // Footprints the base's area holds (the swatch's footprint is at most 0.2 x 0.2 here).
    const double footprints = area(base) / (0.2 * 0.2);
    std::printf("thin capsule + pebbles: %d patches (%d shrunk) for %.1f footprints of area, %d elements, regions %.3f - %.3f by count\n",
                run.r.report.patches, s.patches_shrunk, footprints, run.r.report.elements, s.region_count_density_min, s.region_count_density_max);
    EXPECT_LE(run.r.report.patches, 12.0 * footprints);
    EXPECT_GE(s.region_count_density_min, 0.85);
    EXPECT_LE(s.region_count_density_max, 1.15);
}

TEST(Surface, SeveralComponentsAreAllCovered) {
    const Mesh base = shapes::concat(isect::icosphere(1.0, 3), shapes::translated(isect::icosphere(0.6, 3), Vec3(3, 0, 0)));
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("rivets")), 0.2);
    expect_whole_and_disjoint(run);
    int near_small = 0, near_large = 0;
    for (const auto& e : mq::test::split_elements(run.r.mesh, run.r.element_of_face))
        (element_centroid(e).x() > 1.5 ? near_small : near_large)++;
    EXPECT_GT(near_small, 10);
    EXPECT_GT(near_large, 10);
}

// Two spheres touching at one vertex (a base with a non-manifold vertex, as an STL soup or a base
// that --repair split welds back into): the vertex is split again on the synthesis's copy, with a
// warning, and both spheres are covered with whole, disjoint elements.
TEST(Surface, SpheresTouchingAtAVertexAreBothCovered) {
    const Mesh a = isect::icosphere(1.0, 3);
    const Vec3 touch = a.vertices[0];
    Mesh b = a;  // a reflected through the vertex: b's vertex 0 lands exactly on a's
    for (Vec3& v : b.vertices) v = 2.0 * touch - v;
    for (mq::Tri& t : b.faces) std::swap(t[1], t[2]);
    ASSERT_EQ(b.vertices[0], touch);
    Mesh base = shapes::concat(a, b);
    const int b0 = static_cast<int>(a.vertices.size());
    for (std::size_t f = a.faces.size(); f < base.faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (base.faces[f][k] == b0) base.faces[f][k] = 0;  // b shares a's vertex
    base.vertices[static_cast<std::size_t>(b0)] = touch + Vec3(9, 9, 9);  // left unused
    ASSERT_EQ(mq::analyse(base).non_manifold_vertices, 1);
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("rivets")), 0.2);
    expect_whole_and_disjoint(run);
    EXPECT_EQ(run.r.surface.base_faces_processed, run.r.surface.base_faces);
    EXPECT_EQ(std::count_if(run.r.warnings.begin(), run.r.warnings.end(),
                            [](const std::string& w) { return w.find("touches itself at 1 non-manifold vertex (separate fans") != std::string::npos; }),
              1);
    int on_a = 0, on_b = 0;
    for (const auto& e : mq::test::split_elements(run.r.mesh, run.r.element_of_face))
        (element_centroid(e).dot(touch) < touch.squaredNorm() ? on_a : on_b)++;
    EXPECT_GT(on_a, 10);
    EXPECT_GT(on_b, 10);
}

// A sphere with lone triangles missing (a scan's holes) and a cap cut off: the small holes are
// filled on the synthesis's copy, so elements run across them, and the cap's rim stays a rim.
TEST(Surface, SmallHolesAreFilledAndALargeOneIsNot) {
    const Mesh sphere = isect::icosphere(1.0, 4);
    Mesh base = sphere;
    base.faces.clear();
    int lone = 0;
    std::set<int> taken;  // vertices of the holes so far: no two holes share one
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
        const Vec3 c = (sphere.vertices[static_cast<std::size_t>(sphere.faces[f][0])] + sphere.vertices[static_cast<std::size_t>(sphere.faces[f][1])] + sphere.vertices[static_cast<std::size_t>(sphere.faces[f][2])]) / 3.0;
        // One face in 40 below the equator, no two sharing a vertex.
        const mq::Tri& t = sphere.faces[f];
        const bool hole = c.z() < -0.1 && f % 40 == 0 && !taken.count(t[0]) && !taken.count(t[1]) && !taken.count(t[2]);
        if (hole) taken.insert({t[0], t[1], t[2]});
        if (c.z() > 0.7) continue;  // the cap
        if (hole) {
            ++lone;
            continue;
        }
        base.faces.push_back(sphere.faces[f]);
    }
    const mq::MeshAnalysis an = mq::analyse(base);
    ASSERT_EQ(an.non_manifold_vertices, 0);
    ASSERT_EQ(an.boundary_loops, lone + 1);
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("rivets")), 0.2);
    expect_whole_and_disjoint(run);
    EXPECT_EQ(run.r.surface.base_holes_filled, lone);
    EXPECT_EQ(mq::analyse(run.r.base).boundary_loops, 1);  // the base as used keeps the cap's rim
    EXPECT_EQ(std::count_if(run.r.warnings.begin(), run.r.warnings.end(),
                            [&](const std::string& w) {
                                return w.find("the base has " + std::to_string(lone + 1) + " holes; the " + std::to_string(lone) + " smaller than") !=
                                       std::string::npos;
                            }),
              1);
    std::printf("sphere with %d small holes + rivets: report's region density %.3f - %.3f\n", lone, run.r.surface.region_density_min,
                run.r.surface.region_density_max);
    EXPECT_GE(run.r.surface.region_density_min, 0.85);  // measured 0.915: no bald spot at a hole
    // Elements stay below the cap's rim (none is placed over the large hole).
    double rim = -1.0;
    for (const mq::Tri& t : base.faces)
        for (int k = 0; k < 3; ++k) rim = std::max(rim, base.vertices[static_cast<std::size_t>(t[k])].z());
    for (const Vec3& v : run.r.mesh.vertices) EXPECT_LE(v.z(), rim + 0.05);
}

/// The output's rings and how many others each interlocks with (|linking number| 1, pairs within
/// 1.5 of the swatch's widest ring at the run's scale); `diameter` gets that width.
struct RingLinks {
    std::vector<Mesh> rings;
    std::vector<int> links;  ///< per ring
    double diameter = 0.0;
};
RingLinks ring_links(const SurfaceRun& run) {
    RingLinks out;
    const Mesh sw = mq::normalize_swatch(run.swatch);
    int n = 0;
    const std::vector<int> comp = mq::connected_components(sw, &n);
    for (const Mesh& r : mq::test::split_elements(sw, comp)) {
        const mq::Box3 b = mq::bounding_box(r);
        out.diameter = std::max({out.diameter, b.size().x(), b.size().y()});
    }
    out.diameter *= run.r.surface.base_scale;
    out.rings = mq::test::split_elements(run.r.mesh, run.r.element_of_face);
    const auto links = mq::test::link_counts(out.rings, 1.5 * out.diameter);
    for (std::size_t i = 0; i < out.rings.size(); ++i) out.links.push_back(links.count(static_cast<int>(i)) ? links.at(static_cast<int>(i)) : 0);
    return out;
}

/// "k rings with c links; ..." for a histogram of link counts.
std::string link_histogram_text(const std::map<int, int>& histogram) {
    std::string h;
    for (const auto& [c, k] : histogram) h += std::to_string(k) + " rings with " + std::to_string(c) + " links; ";
    return h;
}

TEST(Surface, ChainMailOnACylinderStaysChainMail) {
    // Away from the rims, most rings interlock with as many rings as the swatch's interior rings (4).
    const Mesh swatch = mq::read_mesh(swatch_path("chainmail"));
    const SurfaceRun run = quilt(shapes::open_cylinder(1.0, 2.0, 64, 32), swatch, 0.2);
    expect_whole_and_disjoint(run);
    const RingLinks rl = ring_links(run);
    int interior = 0, four = 0;
    std::map<int, int> histogram;
    for (std::size_t i = 0; i < rl.rings.size(); ++i) {
        const double z = element_centroid(rl.rings[i]).z();
        if (z < 1.5 * rl.diameter || z > 2.0 - 1.5 * rl.diameter) continue;
        ++interior;
        ++histogram[rl.links[i]];
        four += rl.links[i] == 4;
    }
    const std::string h = link_histogram_text(histogram);
    ASSERT_GT(interior, 50);
    RecordProperty("links", h);
    std::printf("cylinder chain mail: %s\n", h.c_str());
    // Measured: 949 of 978 (97%) since session 18's warp onto the old rings; 908 of 960 (95%) before,
    // 859 of 928 (93%) in session 11.
    EXPECT_GE(four, 0.96 * interior) << h;
    // Rings that collided where the kernel put them were nudged into place (measured: 824 of 917
    // rings linked with 4 without nudging).
    EXPECT_GT(run.r.surface.elements_nudged, 0);
}

TEST(Surface, ChainMailOnADoublyCurvedBaseContinuesAndMendsItsLattice) {
    // On the eight (genus 2) neighbouring patches' ring lattices meet at angles; each new lattice is
    // turned to continue the old rings at its seed, and empty slots along the seams get the ring the
    // swatch has there (docs/surface.md). Rings stay linked: a mended ring sits where one lattice has it.
    const Mesh swatch = mq::read_mesh(swatch_path("chainmail"));
    const SurfaceRun run = quilt(mq::read_mesh(surface_data_path("eight.obj")), swatch, 0.2);
    expect_whole_and_disjoint(run);
    expect_element_sizes(run, 1.5, 0.7);
    const RingLinks rl = ring_links(run);
    std::map<int, int> histogram;
    for (int c : rl.links) ++histogram[c];
    const std::string h = link_histogram_text(histogram);
    const auto [lo, hi] = region_density(run);
    std::printf("eight chain mail: %d mended (%d into holes, %d of them tilted, %d enlarged; %d swaps), region density %.3f - %.3f; %s\n",
                run.r.surface.elements_mended, run.r.surface.ring_holes_filled, run.r.surface.ring_holes_tilted, run.r.surface.ring_holes_enlarged,
                run.r.surface.rings_swapped, lo, hi, h.c_str());
    RecordProperty("links", h);
    // Measured at seed 1: 231 mended, 103 into holes, 53 tilted, 4 enlarged, 34 swaps, 1,061 rings,
    // 522 linked with 4, region density 0.972-1.088 (session 50: slots blocked by one ring of
    // another lattice swapped). Before: 187 mended, 129 into holes, 67 tilted, 10 enlarged, 511
    // linked with 4, region density 0.957-1.098 (session 49: mended rings counted on the surface,
    // which took the densest region by count from 1.188 to 1.126). Before: 229 mended, 165 into holes, 88 tilted, 14 enlarged (session 40),
    // 581 linked with 4, region density 0.994-1.135. Before: 1,091 rings, 227 mended (163 of them into holes between lattices, 92 of
    // those tilted, session 38), 568 linked with 4, none with none; region density 0.964-1.140.
    // Before tilting: 1,060 rings, 196 mended, 132 into holes, 537 linked with 4, 0.948-1.135
    // (session 20). Before the ring holes: 958
    // rings, 94 mended, 458 linked with 4, 0.843-1.078. Before session 18's warp of the new rings onto the old ones: 918 rings, 409 linked
    // with 4 (0.446 of them), 0.840-1.006; before session 17: 901 rings, 406 with 4, 0.821-0.997. With each ring resized about its own centre (before
    // session 16: the lattice broken): 762 rings, 114 mended, 253 linked with 4, 0.689-0.836. Before
    // lattice turning and mending (session 11): 667 rings, 132 linked with 4, 83 with none,
    // 0.646-0.796. Issue 3 asks for 0.85.
    const auto count = static_cast<double>(rl.rings.size());
    EXPECT_GT(run.r.surface.elements_mended, 20);
    EXPECT_GT(run.r.surface.ring_holes_filled, 60);
    EXPECT_LE(run.r.surface.ring_holes_filled, run.r.surface.elements_mended);
    // Rings tilted from their swatch ring's pose fill holes the untilted ring cannot (step 10).
    // How many holes need one depends on where the lattices meet: 53 / 14 / 0 at seeds 1-3 before
    // session 56's discs (grow_disc), 6 / 46 / 1 after.
    EXPECT_GT(run.r.surface.ring_holes_tilted, 0);
    EXPECT_LT(run.r.surface.ring_holes_tilted, run.r.surface.ring_holes_filled);
    // ... and rings enlarged to reach their neighbours' links (kRingSizes), still within the sizes
    // checked above.
    EXPECT_GT(run.r.surface.ring_holes_enlarged, 1);
    EXPECT_LT(run.r.surface.ring_holes_enlarged, run.r.surface.ring_holes_filled / 4);
    // Slots blocked by one ring of another lattice took two rings of theirs in its place (step 10,
    // "Swapped blockers"): each swap mends at least two rings into lattice slots, and no ring it
    // took away leaves another loose (the histogram below) or the mail intersecting (above).
    EXPECT_GT(run.r.surface.rings_swapped, 0);
    EXPECT_GE(run.r.surface.elements_mended - run.r.surface.ring_holes_filled, 2 * run.r.surface.rings_swapped);
    EXPECT_GT(run.r.surface.rings_unlinked_removed, 0);
    EXPECT_GE(histogram[4], 0.46 * count) << h;
    EXPECT_EQ(histogram[0], 0) << "a ring of the chain mail is loose; " << h;
    EXPECT_GE(count, 1020);
    EXPECT_GE(lo, 0.9);
}

// Round a thin part the decoration stands on a wider surface than the base: chain mail on a torus
// whose tube (radius 0.08) is not much thicker than the shell (0.05) puts its rings round the
// shell's middle as densely as the swatch has them, which per base area is a third more. The report
// measures density on the shell's middle surface too (a torus's offset by d has (r + d) / r times
// its area), and there the mail is within the 15% the stage allows. Measured at seed 1: per base
// area 1.156-1.241, on the middle surface 0.873-0.938.
TEST(Surface, DensityRoundAThinPartIsMeasuredOnTheShellsMiddle) {
    const double minor = 0.08;
    const SurfaceRun run = quilt(shapes::torus(1.0, minor, 128, 24), mq::read_mesh(swatch_path("chainmail")), 0.1);
    expect_whole_and_disjoint(run);
    const auto& s = run.r.surface;
    ASSERT_GT(s.regions, 4);
    const double widen = (minor + 0.5 * s.shell_height) / minor;
    ASSERT_GT(widen, 1.2);
    std::printf("thin torus chain mail: per base area %.3f-%.3f, on the middle surface %.3f-%.3f, widening %.3f; counted per base area %.3f-%.3f\n",
                s.region_density_min, s.region_density_max, s.region_density_mid_min, s.region_density_mid_max, widen, s.region_count_density_min,
                s.region_count_density_max);
    EXPECT_NEAR(s.region_density_mid_min * widen, s.region_density_min, 0.02 * s.region_density_min);
    EXPECT_NEAR(s.region_density_mid_max * widen, s.region_density_max, 0.02 * s.region_density_max);
    EXPECT_GT(s.region_density_min, 1.1);
    EXPECT_GE(s.region_density_mid_min, 0.85);
    EXPECT_LE(s.region_density_mid_max, 1.15);
    // Counted, the rings are as many per base area as the swatch has within the bar, fewer than
    // their area says (the shell widens them round the tube): measured 1.089-1.140 (session 49).
    EXPECT_GE(s.region_count_density_min, 0.85);
    EXPECT_LE(s.region_count_density_max, 1.15);
    EXPECT_LT(s.region_count_density_max, s.region_density_max);
    // The count on the middle surface is the count per base area over the same widening, and the
    // densest region by count is named by a point of the base (on the tube).
    EXPECT_NEAR(s.region_count_density_mid_min * widen, s.region_count_density_min, 0.02 * s.region_count_density_min);
    EXPECT_NEAR(s.region_count_density_mid_max * widen, s.region_count_density_max, 0.02 * s.region_count_density_max);
    const Vec3 at = s.region_count_density_max_at;
    const double ring = std::hypot(std::hypot(at.x(), at.y()) - 1.0, at.z());
    EXPECT_NEAR(ring, minor, 0.03 * minor) << at.transpose();
}

// Pebbles round the same thin tube: each is embedded at its swatch size on the shell's middle
// surface, which covers less of the base there, and the bald spots of a patch are judged by the
// ground the standing pebbles claim on the base (claimed_ground: their frame copies widened by the
// shell's widening), not by their frame copies, which read the ground as sparse by that widening.
// Measured at seed 1: 893 pebbles, 143 of them fills, counted per base area 1.020-1.110, on the
// middle surface 0.824-0.896. Judged by the frame copies (and at the old threshold, 0.85): 891
// pebbles, 179 fills, 1.017-1.095; on this tube the patches' own pebbles take most of what the
// extra fills took, so the count moves little, the fills do (on the bunny's ear the densest region
// by count went from 1.178 to 1.116, docs/surface.md step 8, "Fills counted on the base").
TEST(Surface, PebblesRoundAThinPartAreNotFilledUpToTheMiddleSurface) {
    const double minor = 0.08;
    const SurfaceRun run = quilt(shapes::torus(1.0, minor, 128, 24), mq::read_mesh(swatch_path("pebbles")), 0.1);
    expect_whole_and_disjoint(run);
    const auto& s = run.r.surface;
    const auto& r = run.r.report;
    ASSERT_GT(s.regions, 4);
    const double widen = (minor + 0.5 * s.shell_height) / minor;
    ASSERT_GT(widen, 1.15);
    std::printf("thin torus pebbles: %d elements, %d fills; counted per base area %.3f-%.3f, on the middle surface %.3f-%.3f, widening %.3f\n",
                r.elements, r.bald_spots_filled, s.region_count_density_min, s.region_count_density_max, s.region_count_density_mid_min,
                s.region_count_density_mid_max, widen);
    EXPECT_GE(s.region_count_density_min, 0.85);
    EXPECT_LE(s.region_count_density_max, 1.15);
    EXPECT_NEAR(s.region_count_density_mid_max * widen, s.region_count_density_max, 0.02 * s.region_count_density_max);
    EXPECT_LT(r.bald_spots_filled, 0.17 * r.elements) << "the fills made up the shell's widening";
}

// A mail whose linked rings intersect (the bundled mail with a wire 0.08 thicker, as in
// tests/test_planar.cpp), or stand closer than a twenty-fifth of their width (0.04 thicker), is
// quilted thinned and thickened back (docs/surface.md): on the eight every ring whole and at its
// swatch ring's size. The thick mail's rings are thickened in full and come out as dense as the
// bundled mail's; the tight mail's output stays disjoint, as its swatch is, so where rings came
// closer than in the swatch they are thickened less, and its area density is that much lower.
// Before: the thick mail 215 rings at 0.11-0.31 (CLI regions), the tight one 789 at 0.74-0.86.
class SurfaceThickMail : public ::testing::TestWithParam<double> {};

TEST_P(SurfaceThickMail, IsQuiltedThinnedAndThickenedBack) {
    const double by = GetParam();
    const Mesh thick = shapes::thickened(mq::read_mesh(swatch_path("chainmail")), by);
    const std::vector<int> comp = mq::connected_components(thick);
    const bool meet = !mq::intersecting_element_pairs(thick, comp, 1).empty();
    ASSERT_EQ(meet, by > 0.06);
    const SurfaceRun run = quilt(mq::read_mesh(surface_data_path("eight.obj")), thick, 0.2);
    const auto& r = run.r;
    const std::string said = meet ? "elements intersect one another" : "rings stand closer than";
    EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(), [&](const std::string& w) {
        return w.find(said) != std::string::npos && w.find("thickened back") != std::string::npos;
    }));
    EXPECT_EQ(r.surface.base_faces_processed, r.surface.base_faces);
    EXPECT_TRUE(mq::test::elements_closed(r.mesh, r.element_of_face));
    expect_element_sizes(run, 1.5, 0.7);
    const auto rings = mq::test::split_elements(r.mesh, r.element_of_face);
    // The rings' size (square root of area) over their swatch ring's at the scale used: the thick
    // mail's about 1 at the median, where its thinned wire alone would give 0.87.
    std::vector<double> size;
    const double s2 = r.surface.base_scale * r.surface.base_scale;
    std::vector<double> source_area(comp.empty() ? 0 : static_cast<std::size_t>(*std::max_element(comp.begin(), comp.end()) + 1), 0.0);
    for (std::size_t f = 0; f < comp.size(); ++f) source_area[static_cast<std::size_t>(comp[f])] += face_area(thick, f);
    for (std::size_t e = 0; e < rings.size(); ++e)
        size.push_back(std::sqrt(area(rings[e]) / (source_area[static_cast<std::size_t>(r.source_element[e])] * s2)));
    std::nth_element(size.begin(), size.begin() + static_cast<std::ptrdiff_t>(size.size() / 2), size.end());
    const auto pairs = mq::intersecting_element_pairs(r.mesh, r.element_of_face);
    const RingLinks rl = ring_links(run);
    std::map<int, int> histogram;
    for (int c : rl.links) ++histogram[c];
    const std::string h = link_histogram_text(histogram);
    const auto [lo, hi] = region_density(run);
    std::printf("eight, chain mail 0.%02d thicker: %zu rings, %zu pairs meet, median size %.3f, region density %.3f - %.3f (report %.3f - %.3f); %s\n",
                static_cast<int>(by * 100), rings.size(), pairs.size(), size[size.size() / 2], lo, hi, r.surface.region_density_min,
                r.surface.region_density_max, h.c_str());
    RecordProperty("links", h);
    EXPECT_GE(histogram[4], 0.45 * static_cast<double>(rings.size())) << h;
    EXPECT_GE(r.surface.region_density_min, 0.85);
    EXPECT_LE(r.surface.region_density_max, 1.15);
    if (meet) {
        // Rings link only at the swatch's spacing, and they stand in the shell, their middles at
        // half its height: on this eight that middle surface is 1.22-1.24 times the base in every
        // region, so a region whose mail has no hole holds about that many times the swatch's
        // rings per base area. Crowding is read there (an upper bar per base area would pass only
        // a mail with holes); coverage per base area, as the acceptance reads it. Measured at
        // seed 1: 1,096 rings, test regions 0.990-1.192 per base area, 0.810-0.963 on the middle
        // surface (the densest region the one with fewest holes: 91 of its 139 rings have six
        // neighbours within 1.5 spacings, as in the swatch; in the sparsest 52 of 115), 615
        // linked with 4. Seeds 2 and 3: 0.994-1.079 and 0.942-1.116 per base area. Before session
        // 56's discs (grow_disc): 1,111 rings, 1.002-1.130, 605.
        const auto [mid_lo, mid_hi] = region_density(run, 0.5 * r.surface.shell_height);
        std::printf("  on the middle surface (offset by %.4f): %.3f - %.3f\n", 0.5 * r.surface.shell_height, mid_lo, mid_hi);
        EXPECT_NEAR(size[size.size() / 2], 1.0, 0.05);
        EXPECT_GE(lo, 0.85);
        EXPECT_LE(mid_hi, 1.15);
        EXPECT_LE(r.surface.region_density_mid_max, 1.15);
    } else {
        // Measured at seed 1: 1,059 rings, none meeting, test regions 0.840-1.014 (the report's,
        // thinned against the thinned swatch: 1.00-1.13).
        EXPECT_TRUE(pairs.empty()) << pairs.size() << " pairs of rings meet";
        EXPECT_GE(lo, 0.8);
        EXPECT_LE(hi, 1.15);
    }
}

INSTANTIATE_TEST_SUITE_P(Wire, SurfaceThickMail, ::testing::Values(0.08, 0.04), [](const ::testing::TestParamInfo<double>& i) {
    return i.param > 0.06 ? std::string("intersecting") : std::string("tight");
});

// A weave of ribbons modelled as open sheets quilts as closed strips (SwatchData::solidified):
// before, no ribbon was stitched, and trimmed pieces of an open thread were dropped (the tests'
// eight at scale 0.2, seed 1: regions 0.47-0.57 of the density; 0.865-0.896 as strips).
TEST(Surface, ARibbonWeaveQuiltsAsClosedStrips) {
    const Mesh ribbons = shapes::ribbon_weave(6, 1.25, 0.9, 0.2, 60);
    SurfaceRun run = quilt(shapes::torus(2.0, 0.7, 48, 24), ribbons, 0.2);
    EXPECT_TRUE(std::any_of(run.r.warnings.begin(), run.r.warnings.end(), [](const std::string& w) { return w.find("12 threads are open sheets") != std::string::npos; }));
    expect_whole_and_disjoint(run);
    EXPECT_GT(run.r.report.elements_stitched, 0);
    EXPECT_GT(run.r.surface.thread_pieces, 0);
    // Measured against the strips the stage quilted (the sheets have half their area).
    run.swatch = mq::quilt::prepare_swatch(ribbons).mesh;
    const auto [lo, hi] = region_density(run);
    std::printf("torus + ribbons: region density %.3f - %.3f of the strips' (the report's %.3f - %.3f)\n", lo, hi, run.r.surface.region_density_min,
                run.r.surface.region_density_max);
    EXPECT_GE(lo, 0.85);
    EXPECT_LE(hi, 1.15);
}

TEST(Surface, ATightWeavesThreadsAreDentedClearWhereTheyGraze) {
    // Round threads 0.8 of their spacing wide, 0.1 apart where they cross (the bundled weave's are
    // 0.62 wide, 0.16 apart): a stitch's deformation moves a thread a hair, and it grazed a crossing
    // thread with a few faces, so the stitch was refused and the threads came out as short pieces.
    // Measured at seed 1 on the tube: the share of the output's area in threads longer than the
    // swatch 0.82 before threads were dented clear, 0.93 after; test regions 0.849 - 0.893 before,
    // 0.883 - 0.922 after.
    const int n = 8;
    const double pitch = 1.25;
    const Mesh weave = shapes::round_weave(n, pitch, 0.5, 0.15, 0.2, 8, 66);
    const mq::MeshAnalysis an = mq::analyse(weave);
    ASSERT_EQ(an.elements.size(), 16u);
    for (const auto& e : an.elements) {
        ASSERT_TRUE(e.closed);
        ASSERT_GT(e.volume, 0.0);
    }
    SurfaceRun run = quilt(mq::read_mesh(surface_data_path("tube.obj")), weave, 0.2);
    expect_whole_and_disjoint(run);
    EXPECT_GT(run.r.surface.threads_dented, 0);
    const auto [lo, hi] = region_density(run);
    // Each thread's length along its principal direction, against the swatch's (n * pitch).
    double long_area = 0.0, area = 0.0;
    for (const Mesh& e : mq::test::split_elements(run.r.mesh, run.r.element_of_face)) {
        Vec3 mean = Vec3::Zero();
        for (const Vec3& v : e.vertices) mean += v;
        mean /= static_cast<double>(e.vertices.size());
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const Vec3& v : e.vertices) cov += (v - mean) * (v - mean).transpose();
        const Vec3 axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
        double lo_t = std::numeric_limits<double>::infinity(), hi_t = -lo_t;
        for (const Vec3& v : e.vertices) {
            lo_t = std::min(lo_t, (v - mean).dot(axis));
            hi_t = std::max(hi_t, (v - mean).dot(axis));
        }
        const double a = mq::quilt::mesh_area(e);
        area += a;
        if (hi_t - lo_t > n * pitch * run.r.surface.base_scale) long_area += a;
    }
    std::printf("tube + tight weave: region density %.3f - %.3f, %d threads dented, %.3f of the area in threads longer than the swatch\n", lo, hi,
                run.r.surface.threads_dented, long_area / area);
    EXPECT_GT(long_area, 0.875 * area);
    EXPECT_GE(lo, 0.85);
    EXPECT_LE(hi, 1.15);
}

TEST(Surface, WeaveCoversASmallDomeThatThePatchMapMagnifies) {
    // Spot's head around its left horn (faces within 0.3 of it), at the size the default scale gives
    // the weave on the whole cow: the horn is a dome half a footprint wide. A frame that holds it
    // and the ground around magnifies it (area distortion above 2), and a thread's piece across
    // it stretched beyond what torn-thread detection lets through; smaller frames tile such ground
    // after the last patch (docs/surface.md, step 7). Measured at seed 1: 93% of the dome has an
    // output vertex within 0.012 (96% before session 16 kept the weave's lattice whole; 10% without
    // the smaller frames).
    const Mesh spot = mq::read_mesh(surface_data_path("spot.obj"));
    const Vec3 head(-0.205, 0.942, -0.288), horn(-0.19, 0.915, -0.265);
    auto centroid = [](const Mesh& m, std::size_t f) {
        return (m.vertices[m.faces[f][0]] + m.vertices[m.faces[f][1]] + m.vertices[m.faces[f][2]]) / 3.0;
    };
    std::vector<int> near_head(spot.faces.size(), 0);
    for (std::size_t f = 0; f < spot.faces.size(); ++f) near_head[f] = (centroid(spot, f) - head).norm() < 0.3;
    const auto parts = mq::test::split_elements(spot, near_head);
    ASSERT_EQ(parts.size(), 2u);
    const Mesh& base = parts[1];
    ASSERT_GT(base.faces.size(), 500u);
    mq::SurfaceQuiltOptions o;
    o.swatch_size = 0.207;
    o.seed = 1;
    const Mesh swatch = mq::read_mesh(swatch_path("weave"));
    const SurfaceRun run{swatch, mq::quilt_surface(base, swatch, o)};
    expect_whole_and_disjoint(run);
    expect_no_torn_faces(run, 4.0);
    // Points on the dome (15 inner points of a barycentric grid on each face whose centroid lies
    // within 0.05 of the horn), weighted by face area: covered when an output vertex lies within 0.012.
    const double reach = 0.012;
    std::map<std::array<long, 3>, std::vector<Vec3>> grid;
    auto key = [&](const Vec3& p) {
        return std::array<long, 3>{std::lround(std::floor(p.x() / reach)), std::lround(std::floor(p.y() / reach)), std::lround(std::floor(p.z() / reach))};
    };
    for (const Vec3& v : run.r.mesh.vertices) grid[key(v)].push_back(v);
    auto covered = [&](const Vec3& p) {
        const auto k = key(p);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dz = -1; dz <= 1; ++dz)
                    if (const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz}); it != grid.end())
                        for (const Vec3& v : it->second)
                            if ((v - p).norm() < reach) return true;
        return false;
    };
    double dome = 0.0, cover = 0.0;
    for (std::size_t f = 0; f < base.faces.size(); ++f) {
        if ((centroid(base, f) - horn).norm() >= 0.05) continue;
        const Vec3 a = base.vertices[base.faces[f][0]], b = base.vertices[base.faces[f][1]], c = base.vertices[base.faces[f][2]];
        const double w = face_area(base, f) / 15.0;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; i + j < 5; ++j) {
                const double u = (i + 1.0 / 3.0) / 5.0, v = (j + 1.0 / 3.0) / 5.0;
                dome += w;
                if (covered(a + u * (b - a) + v * (c - a))) cover += w;
            }
    }
    ASSERT_GT(dome, 0.0);
    std::printf("spot's horn + weave: %.3f of the dome covered\n", cover / dome);
    EXPECT_GE(cover / dome, 0.8);
}

/// A Japanese 4-in-1 mail, built here: `n` x `n` flat rings (radius 1, wire 0.12) on a grid of
/// pitch 2.6, each joined to its neighbours by a small ring standing on edge (radius 0.62, wire
/// 0.1) in the plane through both centres. A standing ring's xy box is 7 times longer than wide, as
/// a thread's is; it is a ring all the same.
Mesh japanese_mail(int n) {
    const double p = 2.6, z = 0.8;
    Eigen::Matrix3d about_x, about_y;
    about_x = Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitX());
    about_y = Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitY());
    Mesh swatch;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            swatch = shapes::concat(swatch, isect::torus(1.0, 0.12, 32, 8, Vec3(1.2 + i * p, 1.2 + j * p, z)));
            if (i + 1 < n) swatch = shapes::concat(swatch, isect::torus(0.62, 0.1, 20, 8, Vec3(1.2 + (i + 0.5) * p, 1.2 + j * p, z), about_x));
            if (j + 1 < n) swatch = shapes::concat(swatch, isect::torus(0.62, 0.1, 20, 8, Vec3(1.2 + i * p, 1.2 + (j + 0.5) * p, z), about_y));
        }
    return swatch;
}

TEST(Surface, JapaneseMailKeepsItsStandingRingsWholeAndJoined) {
    // The small rings stand on edge: long in xy like threads, but cutting or stitching one would
    // open it (kernel.h, is_elongated). Each small ring joins two flat ones in the swatch; one
    // that joins one in the output dangles, and goes (surface.cpp, prepare_ring_need).
    const Mesh swatch = japanese_mail(4);
    const SurfaceRun run = quilt(shapes::open_cylinder(1.0, 2.0, 64, 32), swatch, 0.25);
    expect_whole_and_disjoint(run);
    expect_element_sizes(run, 1.5, 0.7);
    const RingLinks rl = ring_links(run);
    const auto parts = mq::test::split_elements(run.r.mesh, run.r.element_of_face);
    ASSERT_EQ(parts.size(), rl.rings.size());
    int small = 0, large = 0, small_joined = 0, large_loose = 0, open = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        // Genus from Euler's formula: every element is a whole ring (genus 1), never a piece.
        const long v = static_cast<long>(parts[i].vertices.size()), f = static_cast<long>(parts[i].faces.size());
        open += v - f / 2 != 0;
        // By area: a small ring's is 0.52 of a large one's (4 pi^2 R r).
        const double scale = run.r.surface.base_scale;
        if (area(parts[i]) < 3.6 * scale * scale) {
            ++small;
            small_joined += rl.links[i] == 2;
        } else {
            ++large;
            large_loose += rl.links[i] == 0;
        }
    }
    const auto [lo, hi] = region_density(run);
    std::printf("cylinder japanese mail: %d large, %d small (%d joining two), %d mended, %d removed, region density %.3f - %.3f\n", large, small,
                small_joined, run.r.surface.elements_mended, run.r.surface.rings_unlinked_removed, lo, hi);
    EXPECT_EQ(open, 0);
    EXPECT_EQ(large_loose, 0);
    EXPECT_GE(small_joined, 0.97 * small);
    EXPECT_GE(small, 1.6 * large);
    EXPECT_GE(lo, 0.8);
    EXPECT_LE(hi, 1.2);
}

/// A European 4-in-1 mail on a rectangular lattice, built here: `rows` rows of `cols` rings (radius
/// 1, wire 0.1) 1.25 apart along x, rows 1.5 apart along y and shifted by half a ring, each row's
/// rings tilted by 30 degrees about y, alternately either way. Each ring links the two rings
/// diagonally above and the two below it, as in the bundled mail (square: rows 1.25 apart).
Mesh rectangular_mail(int rows, int cols) {
    Mesh swatch;
    for (int k = 0; k < rows; ++k)
        for (int i = 0; i < cols; ++i) {
            const Vec3 c(1.2 + 1.25 * i + 0.625 * (k % 2), 1.2 + 1.5 * k, 0.7);
            swatch = shapes::concat(swatch, isect::torus(1.0, 0.1, 24, 6, c, isect::rotation(Vec3::UnitY(), (k % 2 ? -1.0 : 1.0) * M_PI / 6.0)));
        }
    return swatch;
}

TEST(Surface, RingsMendedIntoHolesDoNotCrowdTheMail) {
    // Where two patches' lattices meet, mending puts rings into the holes between them. In a
    // rectangular lattice the swatch's own holes are nearly as wide as those (0.70 of the ring
    // spacing, against 0.64 in the square bundled mail), so rings went in where the mail was
    // already as dense as the swatch: 1.12-1.19 of its density before, 1.05-1.09 now (surface.cpp,
    // ring_crowd).
    const Mesh swatch = rectangular_mail(6, 8);
    const SurfaceRun run = quilt(isect::icosphere(1.0, 3), swatch, 0.25);
    expect_whole_and_disjoint(run);
    expect_element_sizes(run, 1.5, 0.7);
    const RingLinks rl = ring_links(run);
    const int loose = static_cast<int>(std::count(rl.links.begin(), rl.links.end(), 0));
    const auto [lo, hi] = region_density(run);
    std::printf("sphere rectangular mail: %zu rings, %d in holes, %d loose, region density %.3f - %.3f\n", rl.rings.size(), run.r.surface.ring_holes_filled,
                loose, lo, hi);
    EXPECT_EQ(loose, 0);
    EXPECT_GT(run.r.surface.ring_holes_filled, 0);
    EXPECT_GE(lo, 0.9);
    EXPECT_LE(hi, 1.12);
}

TEST(Surface, RingsThatDoNotInterlockInTheSwatchAreKept) {
    // A swatch of washers side by side (tori that link with nothing): their lattice is continued and
    // mended like chain mail's, but no ring is removed for being unlinked.
    Mesh swatch;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            swatch = shapes::concat(swatch, shapes::translated(shapes::torus(1.0, 0.25, 24, 12), Vec3(1.5 + 3.0 * i, 1.5 + 3.0 * j, 0.25)));
    const SurfaceRun run = quilt(isect::icosphere(1.0, 3), swatch, 0.25);
    expect_whole_and_disjoint(run);
    expect_element_sizes(run, 1.5, 0.7);
    EXPECT_EQ(run.r.surface.rings_unlinked_removed, 0);
    EXPECT_GT(run.r.surface.elements_mended, 0);
    const auto [lo, hi] = region_density(run);
    std::printf("sphere washers: %d mended, region density %.3f - %.3f\n", run.r.surface.elements_mended, lo, hi);
    EXPECT_GE(lo, 0.85);
    EXPECT_LE(hi, 1.15);
}

TEST(Surface, InsideOutBaseIsFlippedWithAWarningAndDecoratedOutside) {
    const Mesh base = shapes::flipped(isect::icosphere(1.0, 3));
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("pebbles")), 0.25);
    expect_whole_and_disjoint(run);
    EXPECT_EQ(run.r.surface.base_flipped_components, 1);
    ASSERT_FALSE(run.r.warnings.empty());
    EXPECT_NE(run.r.warnings[0].find("facing inwards"), std::string::npos);
    for (const Vec3& v : run.r.mesh.vertices) EXPECT_GE(v.norm(), 0.97);
}

TEST(Surface, InsideOutOpenBaseWithAHoleIsFlippedButAnOpenSheetIsNot) {
    // A sphere with a few faces removed (a scan with a hole), inside out: flipped.
    Mesh holed = shapes::flipped(isect::icosphere(1.0, 3));
    holed.faces.resize(holed.faces.size() - 6);
    const SurfaceRun run = quilt(holed, mq::read_mesh(swatch_path("rivets")), 0.3);
    EXPECT_EQ(run.r.surface.base_flipped_components, 1);
    for (const Vec3& v : run.r.mesh.vertices) EXPECT_GE(v.norm(), 0.97);
    // A flat sheet facing down is a valid choice of side: kept.
    Mesh sheet = shapes::flipped(shapes::grid(8, 4.0));
    const SurfaceRun flat = quilt(sheet, mq::read_mesh(swatch_path("rivets")), 0.3);
    EXPECT_EQ(flat.r.surface.base_flipped_components, 0);
    double top = -1e300, mean = 0.0;
    for (const Vec3& v : flat.r.mesh.vertices) {
        top = std::max(top, v.z());
        mean += v.z() / static_cast<double>(flat.r.mesh.vertices.size());
    }
    EXPECT_LE(top, 1e-12);  // heights are never negative: nothing sinks into the base
    EXPECT_LT(mean, -0.02);
}

TEST(Surface, AnchorsReproduceTheEmbeddedVertices) {
    const SurfaceRun run = quilt(isect::icosphere(1.0, 3), mq::read_mesh(swatch_path("rivets")), 0.3);
    const auto& r = run.r;
    // Normal embedding: p = sum_i b_i (V_i + h N_i); on a sphere, |p| ~ 1 + h and p lies over its face.
    double worst = 0.0;
    for (std::size_t v = 0; v < r.mesh.vertices.size(); ++v) {
        const mq::SurfacePoint& sp = r.anchors[v];
        ASSERT_GE(sp.face, 0);
        ASSERT_LT(static_cast<std::size_t>(sp.face), r.base.faces.size());
        EXPECT_NEAR(sp.bary.sum(), 1.0, 1e-9);
        const auto& t = r.base.faces[static_cast<std::size_t>(sp.face)];
        const Vec3 foot = sp.bary[0] * r.base.vertices[t[0]] + sp.bary[1] * r.base.vertices[t[1]] + sp.bary[2] * r.base.vertices[t[2]];
        // The vertex lies above its foot point, along the (interpolated) normal.
        const Vec3 d = r.mesh.vertices[v] - foot;
        worst = std::max(worst, (d - d.dot(foot.normalized()) * foot.normalized()).norm());
    }
    EXPECT_LT(worst, 0.02) << "vertices drift sideways from their anchors";
}

TEST(Surface, HeightOptionSetsTheShellHeight) {
    const Mesh base = isect::icosphere(1.0, 3);
    mq::SurfaceQuiltOptions o;
    o.scale = 0.25;
    o.height = 0.12;
    const mq::SurfaceQuiltResult r = mq::quilt_surface(base, mq::read_mesh(swatch_path("rivets")), o);
    ASSERT_GT(r.report.elements, 20);
    double top = 0.0, top_anchor = 0.0;
    for (const Vec3& v : r.mesh.vertices) top = std::max(top, v.norm() - 1.0);
    for (const auto& a : r.anchors) top_anchor = std::max(top_anchor, a.height);
    EXPECT_NEAR(top_anchor, 0.12, 0.012);  // the tallest rivet reaches the shell's top
    EXPECT_LT(top, 0.125);                 // nothing beyond it (the icosphere's faces lie inside the unit sphere)
    EXPECT_GT(r.surface.region_density_min, 0.8);  // density compared with the swatch stretched alike
}

TEST(Surface, SameSeedSameOutputOtherSeedOtherOutput) {
    const Mesh base = mq::read_mesh(surface_data_path("eight.obj"));
    const Mesh sw = mq::read_mesh(swatch_path("rivets"));
    const SurfaceRun a = quilt(base, sw, 0.25, 3), b = quilt(base, sw, 0.25, 3), c = quilt(base, sw, 0.25, 4);
    EXPECT_EQ(a.r.mesh.faces, b.r.mesh.faces);
    EXPECT_TRUE(a.r.mesh.vertices == b.r.mesh.vertices);
    EXPECT_FALSE(a.r.mesh.vertices == c.r.mesh.vertices);
}

// ---------------------------------------------------------------------------------------------
// Orientation: with a field, elements follow it; without, neighbours agree.

/// Mean angle in degrees (mod 180) between the elements' principal directions and `want(normal)`
/// on a cylinder around the z axis; fails the test when fewer than 20 elements came out.
double mean_error_on_cylinder(const SurfaceRun& run, const std::function<Vec3(const Vec3&)>& want) {
    double sum = 0.0;
    int n = 0;
    for (const auto& e : mq::test::split_elements(run.r.mesh, run.r.element_of_face)) {
        const Vec3 c = element_centroid(e);
        const Vec3 normal = Vec3(c.x(), c.y(), 0.0).normalized();
        sum += angle_mod_pi(principal_direction(e, normal), want(normal));
        ++n;
    }
    EXPECT_GT(n, 20);
    return n > 0 ? sum / n * 180.0 / M_PI : 180.0;
}

TEST(SurfaceField, AnisotropicElementsFollowAUserFieldOnACylinder) {
    const Mesh base = shapes::open_cylinder(1.0, 4.0, 64, 32);
    mq::GuidanceField field;
    // Along the axis on every face (the grains must stand upright), given per vertex.
    for (std::size_t v = 0; v < base.vertices.size(); ++v) field.vertices.push_back({static_cast<int>(v), Vec3::UnitZ()});
    const SurfaceRun run = quilt(base, grain_swatch(), 0.22, 1, field);
    expect_whole_and_disjoint(run);
    EXPECT_LT(mean_error_on_cylinder(run, [](const Vec3&) { return Vec3(Vec3::UnitZ()); }), 10.0);
}

TEST(SurfaceField, StrokesSteerTheField) {
    // One stroke around the cylinder: grains lie around it, not along the axis.
    const Mesh base = shapes::open_cylinder(1.0, 4.0, 64, 32);
    mq::GuidanceField field;
    std::vector<Vec3> stroke;
    for (int k = 0; k <= 24; ++k) stroke.emplace_back(std::cos(k * M_PI / 12), std::sin(k * M_PI / 12), 2.0);
    field.strokes.push_back(stroke);
    const SurfaceRun run = quilt(base, grain_swatch(), 0.22, 2, field);
    expect_whole_and_disjoint(run);
    EXPECT_LT(mean_error_on_cylinder(run, [](const Vec3& normal) { return Vec3(Vec3::UnitZ().cross(normal)); }), 10.0);
}

TEST(SurfaceField, WithoutAFieldRowsRunAlongAnOpenRim) {
    // On a tube every constant-angle field is equally smooth; the automatic field is turned as a
    // whole to follow the open rims, so grains lie around the tube, parallel to its rims, as rows
    // of a fabric run along its hem (a weave's threads no longer end on the rim at 45 degrees).
    const SurfaceRun run = quilt(shapes::open_cylinder(1.0, 4.0, 64, 32), grain_swatch(), 0.22, 1);
    expect_whole_and_disjoint(run);
    const double error = mean_error_on_cylinder(run, [](const Vec3& normal) { return Vec3(Vec3::UnitZ().cross(normal)); });
    RecordProperty("mean_error_deg", std::to_string(error));
    EXPECT_LT(error, 10.0);  // measured: 0.4 degrees (before the turn: 70.7)
}

TEST(SurfaceField, FieldMagnitudeSetsTheLocalScale) {
    // Vectors of length 1 on the lower half of a cylinder, 2 on the upper half: elements up there
    // come out twice as large (in size, the square root of area).
    const Mesh base = shapes::open_cylinder(1.0, 6.0, 64, 48);
    mq::GuidanceField field;
    for (std::size_t v = 0; v < base.vertices.size(); ++v)
        field.vertices.push_back({static_cast<int>(v), Vec3(0, 0, base.vertices[v].z() < 3.0 ? 1.0 : 2.0)});
    const SurfaceRun run = quilt(base, mq::read_mesh(swatch_path("rivets")), 0.1, 1, field);
    expect_whole_and_disjoint(run);
    std::vector<double> low, high;
    for (const auto& e : mq::test::split_elements(run.r.mesh, run.r.element_of_face)) {
        const double z = element_centroid(e).z();
        if (z < 2.0) low.push_back(std::sqrt(area(e)));
        if (z > 4.0) high.push_back(std::sqrt(area(e)));
    }
    ASSERT_GT(low.size(), 20u);
    ASSERT_GT(high.size(), 5u);
    std::sort(low.begin(), low.end());
    std::sort(high.begin(), high.end());
    const double ratio = high[high.size() / 2] / low[low.size() / 2];
    EXPECT_GT(ratio, 1.7);
    EXPECT_LT(ratio, 2.3);
}

TEST(SurfaceField, WithoutAFieldNeighboursAgreeUpToTheSwatchSymmetry) {
    const SurfaceRun run = quilt(shapes::torus(2.0, 0.8, 64, 32), grain_swatch(), 0.18, 1);
    expect_whole_and_disjoint(run);
    EXPECT_EQ(run.r.surface.symmetry, 2);
    const auto parts = mq::test::split_elements(run.r.mesh, run.r.element_of_face);
    std::vector<Vec3> c, d, nrm;
    for (const auto& e : parts) {
        c.push_back(element_centroid(e));
        // Torus normal at c: away from the tube's centre line.
        const Vec3 ring = Vec3(c.back().x(), c.back().y(), 0.0).normalized() * 2.0;
        nrm.push_back((c.back() - ring).normalized());
        d.push_back(principal_direction(e, nrm.back()));
    }
    // Each element against its nearest neighbour (the grains are 1.6 long, 1 apart).
    double sum = 0.0;
    int n = 0;
    const double reach = 1.2 * run.r.surface.base_scale;
    for (std::size_t i = 0; i < c.size(); ++i) {
        double best = 1e300;
        std::size_t j = i;
        for (std::size_t k = 0; k < c.size(); ++k)
            if (k != i && (c[k] - c[i]).norm() < best) {
                best = (c[k] - c[i]).norm();
                j = k;
            }
        if (j == i || best > 3 * reach) continue;
        Vec3 dj = d[j] - d[j].dot(nrm[i]) * nrm[i];
        sum += angle_mod_pi(d[i], dj);
        ++n;
    }
    ASSERT_GT(n, 20);
    RecordProperty("mean_neighbour_angle_deg", std::to_string(sum / n * 180.0 / M_PI));
    EXPECT_LT(sum / n * 180.0 / M_PI, 12.0);
}

// ---------------------------------------------------------------------------------------------
// Bad input.

// A swatch whose elements are as wide as the base's features: on a bar narrower than half a ring
// nothing fits, which is an error (no empty decoration is written); on a bar a little wider a few
// rings fit, which is a result with a warning that names the density reached. The bars' long faces
// (two triangles each) are thin and get remeshed (quilt::refine_long_edges): since then rings wrap
// around a bar 0.6 wide at 0.94 of the swatch's density (0.19 on a bar 1.0 wide before).
// The default scale suits swatches of a few dozen elements; a dense swatch would make tens of
// millions of faces there (300 packed spheres: 22-32 million on the shared meshes). Left to the
// default, the footprint grows until the estimated output fits the face budget, with a warning; a
// scale the caller gives is kept. (The budget is 4 million faces; here 100,000, for a fast test.)
TEST(SurfaceScale, ADenseSwatchRaisesTheDefaultScaleToTheFaceBudget) {
    const Mesh sw = mq::read_mesh(swatch_path("pebbles"));
    const Mesh sphere = isect::icosphere(1.0, 2);
    mq::SurfaceQuiltOptions o;
    EXPECT_FALSE(o.scale.has_value());
    EXPECT_EQ(o.default_face_budget, 4e6);
    o.default_face_budget = 1e5;
    o.embedding = mq::Embedding::Normal;
    const auto r = mq::quilt_surface(sphere, sw, o);
    // At 0.08 the sphere would hold about 1.3 million faces of pebbles: the scale is raised by about
    // the square root of 13.
    std::printf("raised: scale %.4f, %d faces, %d elements\n", r.surface.scale, r.report.faces, r.report.elements);
    EXPECT_GT(r.surface.scale, 3.0 * mq::kDefaultScale);
    EXPECT_LT(r.surface.scale, 4.5 * mq::kDefaultScale);
    EXPECT_GT(r.report.faces, 50000);
    EXPECT_LT(r.report.faces, 130000);
    EXPECT_EQ(r.surface.base_faces_processed, r.surface.base_faces);
    const bool warned = std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
        return w.find("the scale was raised to") != std::string::npos && w.find("pass --scale") != std::string::npos &&
               w.find("7560 faces") != std::string::npos;
    });
    EXPECT_TRUE(warned);
    // The same scale given: kept exactly, even with a budget it would pass, and no warning.
    o.scale = r.surface.scale;
    o.default_face_budget = 5e4;
    const auto given = mq::quilt_surface(sphere, sw, o);
    EXPECT_EQ(given.surface.scale, *o.scale);
    for (const std::string& w : given.warnings) EXPECT_EQ(w.find("raised"), std::string::npos) << w;
    EXPECT_EQ(given.report.faces, r.report.faces);  // the same footprint: the same output
    o.default_face_budget = -1.0;
    EXPECT_TRUE(mq::test::throws_with<mq::InvalidInput>([&] { (void)mq::quilt_surface(sphere, sw, o); }, {"face budget"}));
}

TEST(SurfaceErrors, ASwatchTooLargeForTheBaseIsAnErrorOrAWarning) {
    const Mesh chainmail = mq::read_mesh(swatch_path("chainmail"));
    mq::SurfaceQuiltOptions o;
    o.swatch_size = 4.5;  // rings about 0.75 wide
    EXPECT_TRUE(mq::test::throws_with<mq::InvalidInput>([&] { (void)mq::quilt_surface(isect::cuboid(Vec3(0, 0, 0), Vec3(0.3, 0.3, 8.0)), chainmail, o); },
                                                        {"no element of the swatch fits", "smaller --scale or --swatch-size"}));
    // Long enough (16) for a region of a footprint's area, where the density is measured.
    const auto r = mq::quilt_surface(isect::cuboid(Vec3(0, 0, 0), Vec3(0.4, 0.4, 16.0)), chainmail, o);
    EXPECT_GT(r.report.elements, 0);
    ASSERT_GT(r.surface.regions, 0);
    EXPECT_LT(r.surface.region_density_min, 0.5);  // measured: 0.29 (16 rings)
    // The warning and the report name a point of the thinnest region: a face's centroid, so on one
    // side of the bar and strictly inside it (not on an edge or a corner, such as an unset origin).
    const Vec3 at = r.surface.region_density_min_at;
    const std::array<double, 6> to_sides{at.x(), at.y(), at.z(), 0.4 - at.x(), 0.4 - at.y(), 16.0 - at.z()};
    EXPECT_EQ(std::count_if(to_sides.begin(), to_sides.end(), [](double d) { return std::abs(d) < 1e-9; }), 1) << at.transpose();
    EXPECT_EQ(std::count_if(to_sides.begin(), to_sides.end(), [](double d) { return d > 1e-6; }), 5) << at.transpose();
    char xyz[64];
    std::snprintf(xyz, sizeof xyz, "%.4g, %.4g, %.4g", at.x(), at.y(), at.z());
    const std::string where = "its thinnest region (around " + std::string(xyz) + ") holds 0.";
    EXPECT_EQ(std::count_if(r.warnings.begin(), r.warnings.end(),
                            [&](const std::string& w) { return w.find("decoration is sparse: " + where) != std::string::npos &&
                                                              w.find("smaller --scale") != std::string::npos; }),
              1)
        << (r.warnings.empty() ? std::string("no warning") : r.warnings.back());
}

// A swatch that is one connected net (a grid of bars, genus 64) can only be placed whole: where
// two placements overlap they cannot be merged. Its sparse decoration says so, and does not advise a
// smaller scale, which covers less, not more (the eight, seed 1: thinnest region 0.35 at scale
// 0.2, 0.08 at 0.08).
TEST(SurfaceErrors, ASparseNetSaysItCanOnlyBePlacedWhole) {
    mq::SurfaceQuiltOptions o;
    o.scale = 0.2;
    o.seed = 1;
    const auto r = mq::quilt_surface(mq::read_mesh(surface_data_path("eight.obj")), shapes::grid_net(8, 1.25, 0.25, 0.3, 0.125), o);
    EXPECT_GT(r.report.elements, 0);
    ASSERT_GT(r.surface.regions, 0);
    EXPECT_LT(r.surface.region_density_min, 0.5);
    int net = 0, scale = 0;
    for (const std::string& w : r.warnings) {
        net += w.find("decoration is sparse") != std::string::npos && w.find("net or lattice can only be placed whole") != std::string::npos &&
               w.find("does not cover more") != std::string::npos;
        scale += w.find("covers more fully") != std::string::npos;
    }
    EXPECT_EQ(net, 1) << (r.warnings.empty() ? std::string("no warning") : r.warnings.back());
    EXPECT_EQ(scale, 0);
}

TEST(SurfaceErrors, BadBasesAndOptionsGiveClearErrors) {
    using mq::test::throws_with;
    const Mesh sw = mq::read_mesh(swatch_path("pebbles"));
    const Mesh sphere = isect::icosphere(1.0, 2);
    auto run = [&](const Mesh& base, mq::SurfaceQuiltOptions o) { return [=] { (void)mq::quilt_surface(base, sw, o); }; };
    mq::SurfaceQuiltOptions o;
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(Mesh{}, o), {"base has no faces"}));
    for (double s : {0.0, -1.0, 3.0, std::nan("")}) {
        o.scale = s;
        EXPECT_TRUE(throws_with<mq::InvalidInput>(run(sphere, o), {"scale must be in (0, 2]"}));
    }
    o.scale = 1e-5;
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(sphere, o), {"million output faces", "larger --scale"}));
    o.scale = 0.08;
    o.height = 1.5;
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(sphere, o), {"shell height 1.5", "too thick"}));
    o.height = 0.0;
    o.scale = 1.0;  // a slab 4.9 thick per 10 wide: the shell would be 1.7, half the sphere's diagonal
    const Mesh thick = isect::cuboid(Vec3(0, 0, 0), Vec3(10, 10, 4.9));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::quilt_surface(sphere, thick, o); }, {"too thick"}));
    o.scale = 0.08;
    o.symmetry = 3;
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(sphere, o), {"symmetry must be 1, 2, 4 or 6"}));
    o.symmetry = 0;
    o.field.faces.push_back({100000, Vec3::UnitX()});
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(sphere, o), {"face 100000", "320 faces"}));
    o.field = {};
    // A non-manifold base: three triangles on one edge.
    Mesh fin = shapes::cube(1.0);
    fin.vertices.emplace_back(0.5, 0.5, 3.0);
    fin.faces.emplace_back(0, 1, static_cast<int>(fin.vertices.size()) - 1);
    EXPECT_TRUE(throws_with<mq::InvalidInput>(run(fin, o), {"not manifold"}));
    // A swatch that is not a slab.
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::quilt_surface(sphere, sphere, {}); }, {"no thin axis"}));
}

TEST(SurfaceErrors, FieldFilesAreCheckedLineByLine) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("mq_field_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    using mq::test::throws_with;
    const std::string good = write("good.txt", "# field\nface 3 1 0 0\nvertex 2 0 1 0  # comment\nstroke 0 0 0 1 0 0 1 1 0\n");
    const mq::GuidanceField f = mq::read_guidance_field(good);
    EXPECT_EQ(f.faces.size(), 1u);
    EXPECT_EQ(f.vertices.size(), 1u);
    ASSERT_EQ(f.strokes.size(), 1u);
    EXPECT_EQ(f.strokes[0].size(), 3u);
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("a.txt", "face 1 1 0\n")); }, {"a.txt:1", "three"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("b.txt", "\n\nface x 1 0 0\n")); }, {"b.txt:3", "index"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("c.txt", "face 1 nan 0 0\n")); }, {"c.txt:1", "non-finite"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("d.txt", "edge 1 1 0 0\n")); }, {"d.txt:1", "unknown record"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("e.txt", "stroke 0 0 0\n")); }, {"e.txt:1", "two points"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("f.txt", "# nothing\n")); }, {"f.txt", "no values"}));
    EXPECT_TRUE(throws_with<mq::InvalidInput>([&] { (void)mq::read_guidance_field(write("g.txt", "face 0 0 0 0\n")); }, {"g.txt:1", "zero"}));
    EXPECT_TRUE(throws_with<mq::IoError>([&] { (void)mq::read_guidance_field((dir / "missing.txt").string()); }, {"missing.txt", "cannot open"}));
    fs::remove_all(dir);
}

}  // namespace
