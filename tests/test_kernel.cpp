// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// The planar kernel's deformation and stitching of threads (quilt/deform.h, quilt/kernel.h): parts
// away from the contested ground stay exactly where they were, so the threads crossing them there
// stay clear.

#include "core/intersect.h"
#include "meshquilt/analysis.h"
#include "quilt/deform.h"
#include "quilt/kernel.h"
#include "support/shapes.h"
#include "support/shapes_isect.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace mq = meshquilt;
using mq::Mesh;
using mq::Vec2;
using mq::Vec3;
namespace shapes = mq::test::shapes;

namespace {

// A square tube of 40 unit voxels along x, scaled to 10 x 0.25 x 0.25: a thread.
Mesh thread(const Vec3& offset) {
    std::vector<std::array<int, 3>> cells;
    for (int i = 0; i < 40; ++i) cells.push_back({i, 0, 0});
    Mesh m = shapes::voxels(cells);
    for (Vec3& v : m.vertices) v = 0.25 * v + offset;
    return m;
}

std::set<std::array<double, 3>> points(const Mesh& m) {
    std::set<std::array<double, 3>> out;
    for (const Vec3& v : m.vertices) out.insert({v.x(), v.y(), v.z()});
    return out;
}

}  // namespace

TEST(Deformation, FixedVerticesStayAndTheRestFollowsTheConstraints) {
    const Mesh m = thread(Vec3::Zero());
    std::vector<mq::quilt::PointConstraint> cons;
    std::vector<char> fixed(m.vertices.size(), 0);
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
        if (m.vertices[v].x() > 7.5) cons.push_back(mq::quilt::PointConstraint::vertex(static_cast<int>(v), m.vertices[v] + Vec3(0, 0.2, 0)));
        fixed[v] = m.vertices[v].x() < 5.0;
    }
    const std::vector<Vec3> held = mq::quilt::laplacian_deform(m, cons, 1.0, fixed);
    const std::vector<Vec3> free = mq::quilt::laplacian_deform(m, cons, 1.0);
    double far_free = 0.0;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
        const Vec3& p = m.vertices[v];
        if (fixed[v]) {
            EXPECT_EQ(held[v], p) << "fixed vertex " << v << " moved";  // bit for bit
            if (p.x() < 1.0) far_free = std::max(far_free, (free[v] - p).norm());
        }
        if (p.x() > 8.5) EXPECT_NEAR(held[v].y() - p.y(), 0.2, 0.05) << "vertex " << v;
    }
    // Without the mask the whole thread goes along with its constrained end (what fixing prevents).
    EXPECT_GT(far_free, 0.1);
}

TEST(Stitching, TwoThreadsBecomeOneAndMoveOnlyNearTheSeam) {
    // An old thread over x in [0, 10], a new one over [6, 16] slightly off it; the new patch covers
    // x >= 6, the output x < 10.
    const Mesh old_thread = thread(Vec3::Zero());
    const Mesh new_thread = thread(Vec3(6.0, 0.04, 0.02));
    mq::quilt::Overlap ov;
    ov.old_side = [](double x, double) { return x >= 6.0; };
    ov.new_side = [](double x, double) { return x < 10.0; };
    mq::quilt::KernelParams params;
    params.metric.unit = 0.25;
    Mesh joined;
    std::string why;
    mq::quilt::StitchOutcome outcome = mq::quilt::StitchOutcome::KeepOld;
    ASSERT_TRUE(mq::quilt::stitch_elements(old_thread, new_thread, ov, params, &joined, &why, &outcome)) << why;
    ASSERT_EQ(outcome, mq::quilt::StitchOutcome::Stitched);
    EXPECT_TRUE(mq::quilt::is_closed_oriented(joined));
    const mq::Box3 box = mq::bounding_box(joined);
    EXPECT_NEAR(box.min.x(), 0.0, 1e-9);
    EXPECT_NEAR(box.max.x(), 16.0, 1e-9);
    // Away from the contested ground [6, 10] (and the seam inside it), both halves are untouched.
    const auto kept = points(joined);
    int checked = 0;
    for (const Vec3& v : old_thread.vertices)
        if (v.x() < 4.0) {
            EXPECT_TRUE(kept.count({v.x(), v.y(), v.z()})) << "old vertex at x = " << v.x() << " moved";
            ++checked;
        }
    for (const Vec3& v : new_thread.vertices)
        if (v.x() > 12.0) {
            EXPECT_TRUE(kept.count({v.x(), v.y(), v.z()})) << "new vertex at x = " << v.x() << " moved";
            ++checked;
        }
    EXPECT_GT(checked, 50);
}

// A round thread along x over [x0, x0 + 10]: a tube of radius 0.2 (or of radii ry across and rz up)
// with 12 sides, a ring of vertices every 0.125, closed by fans; offset in y and z.
Mesh round_thread(double x0, double dy, double dz, double ry = 0.2, double rz = 0.2) {
    constexpr int sides = 12, rings = 81;
    Mesh m;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j) {
            const double a = 2.0 * M_PI * j / sides;
            m.vertices.emplace_back(x0 + 0.125 * i, dy + ry * std::cos(a), dz + rz * std::sin(a));
        }
    auto at = [](int i, int j) { return i * sides + (j % sides); };
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < sides; ++j) {
            m.faces.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
            m.faces.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
        }
    const int first = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(x0, dy, dz);
    m.vertices.emplace_back(x0 + 10.0, dy, dz);
    for (int j = 0; j < sides; ++j) {
        m.faces.emplace_back(first, at(0, j + 1), at(0, j));
        m.faces.emplace_back(first + 1, at(rings - 1, j), at(rings - 1, j + 1));
    }
    return m;
}

/// The narrowest extent in y or z of a thread's cross-sections (the vertices within 0.03 of a plane
/// x = c, c in [x0, x1] every 0.0625, leaving out a fan centre near the axis through `axis`).
struct Sections {
    double narrowest = std::numeric_limits<double>::infinity();
    int count = 0;
};
Sections sections(const Mesh& m, double x0, double x1, const Vec2& axis) {
    Sections s;
    for (double c = x0; c <= x1; c += 0.0625) {
        double ylo = 1e9, yhi = -1e9, zlo = 1e9, zhi = -1e9;
        int n = 0;
        for (const Vec3& v : m.vertices)
            if (std::abs(v.x() - c) < 0.03 && std::hypot(v.y() - axis.x(), v.z() - axis.y()) > 0.05) {
                ylo = std::min(ylo, v.y());
                yhi = std::max(yhi, v.y());
                zlo = std::min(zlo, v.z());
                zhi = std::max(zhi, v.z());
                ++n;
            }
        if (n < 8) continue;
        s.narrowest = std::min({s.narrowest, yhi - ylo, zhi - zlo});
        ++s.count;
    }
    return s;
}

/// The overlap of an old round thread over [0, 10] and a new one over [6, 16]: the new patch
/// covers x >= 6, the output x < 10.
mq::quilt::Overlap round_threads_overlap() {
    mq::quilt::Overlap ov;
    ov.old_side = [](double x, double) { return x >= 6.0; };
    ov.new_side = [](double x, double) { return x < 10.0; };
    return ov;
}
/// Kernel parameters for round threads (mean edge 0.125), keeping thread widths.
mq::quilt::KernelParams round_threads_params() {
    mq::quilt::KernelParams params;
    params.metric.unit = 0.125;
    params.keep_thread_widths = true;
    return params;
}
/// The stitched element of a plan, or null.
const Mesh* stitched_mesh(const mq::quilt::PatchPlan& plan) {
    for (const auto& ch : plan.changes)
        if (ch.kind == mq::quilt::PatchPlan::Change::Stitched) return &ch.mesh;
    return nullptr;
}

TEST(Stitching, ARoundThreadKeepsItsWidthAtTheSeam) {
    // The seam's relaxation used plain Laplacian steps, which pull a tube in towards its axis: the
    // stitched thread was pinched to about 0.85 of its radius there (a weave lost a few percent of
    // its density to it). Taubin's lambda|mu steps keep the cross-section.
    const Mesh old_thread = round_thread(0.0, 0.0, 0.0);
    const Mesh new_thread = round_thread(6.0, 0.03, 0.01);
    ASSERT_TRUE(mq::quilt::is_closed_oriented(old_thread));
    const mq::quilt::Overlap ov = round_threads_overlap();
    mq::quilt::KernelParams params = round_threads_params();
    Mesh joined;
    std::string why;
    mq::quilt::StitchOutcome outcome = mq::quilt::StitchOutcome::KeepOld;
    ASSERT_TRUE(mq::quilt::stitch_elements(old_thread, new_thread, ov, params, &joined, &why, &outcome)) << why;
    ASSERT_EQ(outcome, mq::quilt::StitchOutcome::Stitched);
    ASSERT_TRUE(mq::quilt::is_closed_oriented(joined));
    const Sections s = sections(joined, 6.0, 10.0, Vec2(0.015, 0.005));
    EXPECT_GT(s.count, 20);
    EXPECT_GT(s.narrowest, 0.95 * 0.4) << "the stitched thread is pinched at its seam";
}

TEST(Stitching, AFlatThreadKeepsItsWidthAtTheSeam) {
    // A tape 0.9 wide and 0.06 thick (a ribbon quilted as a strip, SwatchData::solidified): plain
    // Laplacian steps drew its sides together at the seam, to 0.80 of its width here (and into
    // diamond-shaped pinches at the seams of a quilted ribbon weave, seen in renders). A flat thread's seam gets Taubin's steps without
    // keep_thread_widths (quilt::flat_thread); a round one keeps the plain steps.
    const Mesh old_thread = round_thread(0.0, 0.0, 0.0, 0.45, 0.03);
    const Mesh new_thread = round_thread(6.0, 0.03, 0.005, 0.45, 0.03);
    EXPECT_TRUE(mq::quilt::flat_thread(old_thread));
    EXPECT_FALSE(mq::quilt::flat_thread(round_thread(0.0, 0.0, 0.0)));
    EXPECT_FALSE(mq::quilt::flat_thread(round_thread(0.0, 0.0, 0.0, 0.44, 0.17)));  // the bundled weave's section
    mq::quilt::KernelParams params = round_threads_params();
    params.keep_thread_widths = false;
    Mesh joined;
    std::string why;
    mq::quilt::StitchOutcome outcome = mq::quilt::StitchOutcome::KeepOld;
    ASSERT_TRUE(mq::quilt::stitch_elements(old_thread, new_thread, round_threads_overlap(), params, &joined, &why, &outcome)) << why;
    ASSERT_EQ(outcome, mq::quilt::StitchOutcome::Stitched);
    ASSERT_TRUE(mq::quilt::is_closed_oriented(joined));
    double narrowest = 1e9;
    for (double c = 6.0; c <= 10.0; c += 0.0625) {
        double lo = 1e9, hi = -1e9;
        for (const Vec3& v : joined.vertices)
            if (std::abs(v.x() - c) < 0.03) {
                lo = std::min(lo, v.y());
                hi = std::max(hi, v.y());
            }
        if (hi > lo) narrowest = std::min(narrowest, hi - lo);
    }
    EXPECT_GT(narrowest, 0.9 * 0.9) << "the stitched tape is pinched at its seam";
}

TEST(Merging, ThreadsKeepTheirWidthWhereTheyMeet) {
    // Two threads of one width meeting off each other (0.12 in y, a third of their width, and 0.04
    // in z): the paper's targets (Eq. 5-6) pull each vertex half-way to the partner's nearest point,
    // and drew the thread's sides in (the merged weave's threads came out 5% narrower where
    // patches met). Deformed with whole cross-sections, the stitched thread keeps its width.
    const Mesh old_thread = round_thread(0.0, 0.0, 0.0);
    const Mesh new_thread = round_thread(6.0, 0.12, 0.04);
    const mq::quilt::Overlap ov = round_threads_overlap();
    mq::quilt::KernelParams params = round_threads_params();
    const mq::quilt::PatchPlan plan = mq::quilt::plan_patch({{0, old_thread, 0}}, {{0, new_thread}}, ov, params);
    ASSERT_EQ(plan.correspondences, 1);
    const Mesh* joined = stitched_mesh(plan);
    ASSERT_NE(joined, nullptr) << "the threads were not stitched";
    ASSERT_TRUE(mq::quilt::is_closed_oriented(*joined));
    const mq::Box3 box = mq::bounding_box(*joined);
    EXPECT_NEAR(box.min.x(), 0.0, 1e-9);
    EXPECT_NEAR(box.max.x(), 16.0, 1e-9);
    const Sections s = sections(*joined, 4.0, 12.0, Vec2(0.06, 0.02));
    EXPECT_GT(s.count, 50);
    EXPECT_GT(s.narrowest, 0.95 * 0.4) << "the stitched thread is narrower where the threads met";

    // The paper's targets alone (the default) narrow it.
    params.keep_thread_widths = false;
    const mq::quilt::PatchPlan paper = mq::quilt::plan_patch({{0, old_thread, 0}}, {{0, new_thread}}, ov, params);
    const Mesh* narrowed = stitched_mesh(paper);
    ASSERT_NE(narrowed, nullptr);
    EXPECT_LT(sections(*narrowed, 4.0, 12.0, Vec2(0.06, 0.02)).narrowest, 0.95 * 0.4);
}

TEST(Correspondences, RingsPairOnlyWithRingsOfTheirSize) {
    // A flat ring and a small ring standing on edge through it (Japanese 4-in-1 mail): interlocked
    // rings touch, and share many close vertex-face pairs, but deforming one into the other breaks
    // both. A ring of the flat ring's own size, a little off it, is its partner.
    namespace isect = mq::test::isect;
    const Mesh flat = isect::torus(1.0, 0.12, 32, 8, Vec3(0.0, 0.0, 0.8));
    Eigen::Matrix3d about_x;
    about_x = Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitX());
    const Mesh standing = isect::torus(0.62, 0.1, 20, 8, Vec3(1.3, 0.0, 0.8), about_x);
    const Mesh twin = isect::torus(1.0, 0.12, 32, 8, Vec3(0.05, 0.03, 0.8));
    mq::quilt::Overlap ov;
    ov.old_side = [](double, double) { return true; };
    ov.new_side = [](double, double) { return true; };
    mq::quilt::KernelParams params;
    params.metric.unit = 0.1;
    const std::vector<mq::quilt::OldElement> old{{0, flat, 0}};

    const mq::quilt::PatchPlan through = mq::quilt::plan_patch(old, {{1, standing}}, ov, params);
    EXPECT_EQ(through.correspondences, 0);
    for (const auto& ch : through.changes) {
        EXPECT_EQ(ch.kind, mq::quilt::PatchPlan::Change::Added);  // never merged with the flat ring
        EXPECT_EQ(ch.mesh.vertices, standing.vertices);
    }

    const mq::quilt::PatchPlan beside = mq::quilt::plan_patch(old, {{0, twin}}, ov, params);
    EXPECT_EQ(beside.correspondences, 1);
}

TEST(Merging, ALayeredLoserStaysBesideTheWinnerWhenItKeepsClear) {
    // Two scales (closed slabs 2 x 1.5 x 0.2, blobs) of a layered swatch, the new one lying over the
    // old one's back half as a shingle does: their stitch would make one scale half as long again,
    // so one of them wins. With a layer gap the loser is handed back whole as an addition when it
    // keeps that gap from the winner in 3D; laid through the winner, or without the gap, it is dropped.
    auto slab = [](const Vec3& offset) {
        std::vector<std::array<int, 3>> cells;
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 6; ++j) cells.push_back({i, j, 0});
        Mesh m = shapes::voxels(cells);
        for (Vec3& v : m.vertices) v = Vec3(0.25 * v.x(), 0.25 * v.y(), 0.2 * v.z()) + offset;
        return m;
    };
    const Mesh under = slab(Vec3(0.0, 0.0, 0.0));
    mq::quilt::Overlap ov;
    ov.old_side = [](double x, double) { return x < 1.5; };
    ov.new_side = [](double x, double) { return x >= 1.5; };
    mq::quilt::KernelParams params;
    params.metric.unit = 0.25;
    params.layered = true;
    const std::vector<mq::quilt::OldElement> old{{0, under, 0}};
    auto losers = [&](const Mesh& fresh, double gap) {
        params.layer_gap = gap;
        const mq::quilt::PatchPlan plan = mq::quilt::plan_patch(old, {{0, fresh}}, ov, params);
        EXPECT_EQ(plan.correspondences, 1);
        std::vector<Mesh> kept;
        // The winner of a kept pair stays as it was too (deformed half-way it would move into the loser).
        if (plan.squeezed > 0)
            for (std::size_t k = 0; k < plan.squeezed_from; ++k)
                if (plan.changes[k].old_id == 0) EXPECT_TRUE(plan.changes[k].mesh.vertices == under.vertices || plan.changes[k].mesh.vertices == fresh.vertices);
        for (std::size_t k = plan.squeezed_from; k < plan.squeezed_from + static_cast<std::size_t>(plan.squeezed); ++k) {
            EXPECT_EQ(plan.changes[k].kind, mq::quilt::PatchPlan::Change::Added);
            kept.push_back(plan.changes[k].mesh);
        }
        return kept;
    };

    const Mesh over = slab(Vec3(1.0, 0.0, 0.3));  // 0.1 above the old scale's top
    const std::vector<Mesh> kept = losers(over, 0.05);
    ASSERT_EQ(kept.size(), 1u);
    // Whole and unmoved: it is one of the two scales as they were.
    EXPECT_TRUE(kept[0].vertices == under.vertices || kept[0].vertices == over.vertices);
    EXPECT_FALSE(mq::meshes_intersect(kept[0], kept[0].vertices == under.vertices ? over : under));

    EXPECT_TRUE(losers(over, 0.0).empty());                          // off: dropped, as in the paper
    EXPECT_TRUE(losers(over, 0.2).empty());                          // closer than the gap
    EXPECT_TRUE(losers(slab(Vec3(1.0, 0.0, 0.1)), 0.05).empty());    // through the winner
}
