// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// Squeezing and growing blobs (quilt/kernel.h: squeeze_clear, push_side) and the coverage raster
// that finds bald spots and wide joints (quilt/fill.h).

#include "core/intersect.h"
#include "meshquilt/io.h"
#include "quilt/fill.h"
#include "quilt/kernel.h"
#include "quilt/swatch.h"
#include "support/paths.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace mq = meshquilt;
namespace quilt = meshquilt::quilt;
using mq::Mesh;
using mq::Vec2;
using mq::Vec3;
namespace shapes = mq::test::shapes;

namespace {

// A block of n x n x 1 unit voxels scaled by `s` and moved to `offset`: a flat stone.
Mesh block(int n, double s, const Vec3& offset) {
    std::vector<std::array<int, 3>> cells;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) cells.push_back({i, j, 0});
    Mesh m = shapes::voxels(cells);
    for (Vec3& v : m.vertices) v = s * v + offset;
    return m;
}

/// A paving whose joints are 0.1 wide, 0.2 at the widest; neighbours 0.8 away are open ground.
quilt::JointSetup test_joints() {
    quilt::JointSetup s;
    s.paving = true;
    s.typical = 0.1;
    s.wide = 0.2;
    s.limit = 0.8;
    return s;
}

}  // namespace

TEST(SqueezeClear, PushesAStoneClearOfItsNeighbourAndKeepsItWhole) {
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));  // [0, 2] x [0, 2]
    Mesh b = block(4, 0.5, Vec3(1.7, 0.2, 0));    // overlaps a by 0.3 along x
    const Mesh before = b;
    ASSERT_TRUE(quilt::squeeze_clear(b, std::vector<const Mesh*>{&a}, 0.1, 0.6, 1.0 / 3.0));
    const mq::Box3 box = mq::bounding_box(b), box0 = mq::bounding_box(before);
    EXPECT_NEAR(box.min.x(), 2.1, 1e-9);              // the swatch's clearance from a, exactly
    EXPECT_NEAR(box.max.x(), box0.max.x(), 1e-12);    // the far side stays
    EXPECT_NEAR(box.min.y(), box0.min.y(), 1e-12);    // nothing moves across the push
    EXPECT_NEAR(box.max.z(), box0.max.z(), 1e-12);
    EXPECT_EQ(b.faces, before.faces);
    EXPECT_TRUE(quilt::is_closed_oriented(b));
    EXPECT_EQ(mq::count_self_intersections(b), 0);
    mq::ElementCollider collider;
    collider.add(a);
    EXPECT_FALSE(collider.collides(b));
    // Orientation kept: every face's xy winding has the sign it had (the map's Jacobian is positive).
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
        auto signed_area = [&](const Mesh& m) {
            const auto& t = m.faces[f];
            const Vec3 p = m.vertices[t[0]], q = m.vertices[t[1]], r = m.vertices[t[2]];
            return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        };
        const double s0 = signed_area(before), s1 = signed_area(b);
        if (std::abs(s0) > 1e-12) EXPECT_GT(s0 * s1, 0.0) << "face " << f;
    }
}

TEST(SqueezeClear, ClearsSeveralNeighboursAndLeavesAFreeStoneAlone) {
    const Mesh left = block(4, 0.5, Vec3(0, 0, 0));
    const Mesh below = block(4, 0.5, Vec3(2.2, -1.8, 0));
    Mesh b = block(4, 0.5, Vec3(1.9, 0.0, 0));  // overlaps `left` by 0.1 and `below` by 0.2
    ASSERT_TRUE(quilt::squeeze_clear(b, std::vector<const Mesh*>{&left, &below}, 0.05, 0.6, 1.0 / 3.0));
    const mq::Box3 box = mq::bounding_box(b);
    EXPECT_GE(box.min.x(), 2.05 - 1e-9);
    EXPECT_GE(box.min.y(), 0.25 - 1e-9);
    // Already clear: unchanged.
    Mesh free = block(4, 0.5, Vec3(5, 5, 0));
    const Mesh free0 = free;
    ASSERT_TRUE(quilt::squeeze_clear(free, std::vector<const Mesh*>{&left, &below}, 0.05, 0.6, 1.0 / 3.0));
    EXPECT_EQ(free.vertices, free0.vertices);
}

TEST(SqueezeClear, RefusesAPushBeyondItsLimits) {
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));
    Mesh deep = block(4, 0.5, Vec3(1.0, 0.0, 0));  // overlaps by half its width
    EXPECT_FALSE(quilt::squeeze_clear(deep, std::vector<const Mesh*>{&a}, 0.1, 0.6, 1.0 / 3.0));
    Mesh shallow = block(4, 0.5, Vec3(1.5, 0.0, 0));  // a push of 0.6 of 2 is allowed, 30% of the area is not
    EXPECT_FALSE(quilt::squeeze_clear(shallow, std::vector<const Mesh*>{&a}, 0.1, 0.8, 0.45));
    shallow = block(4, 0.5, Vec3(1.5, 0.0, 0));
    EXPECT_TRUE(quilt::squeeze_clear(shallow, std::vector<const Mesh*>{&a}, 0.1, 0.6, 0.45));
}

TEST(PushSide, GrowsASideOutwardAndKeepsTheFarSide) {
    Mesh m = block(4, 0.5, Vec3(0, 0, 0));
    quilt::push_side(m, Vec2(-1, 0), -2.0, 0.0, -0.3);  // axis -x: the side at x = 2 moves out by 0.3
    const mq::Box3 box = mq::bounding_box(m);
    EXPECT_NEAR(box.max.x(), 2.3, 1e-12);
    EXPECT_NEAR(box.min.x(), 0.0, 1e-12);
    EXPECT_TRUE(quilt::is_closed_oriented(m));
    EXPECT_EQ(mq::count_self_intersections(m), 0);
}

TEST(Coverage, DistanceTransformIsExact) {
    // Random small triangles; every pixel's distance is compared with a brute-force search.
    quilt::Coverage cov(0.0, 0.0, 6.0, 4.0, 0.1);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> x(0.0, 6.0), y(0.0, 4.0);
    Mesh m;
    for (int k = 0; k < 12; ++k) {
        const Vec3 c(x(rng), y(rng), 0.0);
        const int base = static_cast<int>(m.vertices.size());
        m.vertices.push_back(c);
        m.vertices.push_back(c + Vec3(0.25, 0.0, 0.0));
        m.vertices.push_back(c + Vec3(0.0, 0.25, 0.0));
        m.faces.push_back({base, base + 1, base + 2});
    }
    cov.add(m);
    const std::vector<double> d = cov.empty_distance();
    std::vector<Vec2> covered;
    for (int j = 0; j < cov.ny(); ++j)
        for (int i = 0; i < cov.nx(); ++i)
            if (cov.covered(i, j)) covered.push_back(cov.centre(i, j));
    ASSERT_GT(covered.size(), 12u);
    for (int j = 0; j < cov.ny(); ++j)
        for (int i = 0; i < cov.nx(); ++i) {
            double best = std::numeric_limits<double>::infinity();
            for (const Vec2& p : covered) best = std::min(best, (p - cov.centre(i, j)).norm());
            ASSERT_NEAR(d[static_cast<std::size_t>(j) * cov.nx() + i], best, 1e-9) << i << "," << j;
        }
    // A window holding every covered pixel within the spot's reach agrees with the whole raster there.
    const std::vector<double> w = cov.empty_distance(10, 5, 40, 30);
    for (int j = 5; j <= 30; ++j)
        for (int i = 10; i <= 40; ++i) EXPECT_GE(w[static_cast<std::size_t>(j - 5) * 31 + (i - 10)], d[static_cast<std::size_t>(j) * cov.nx() + i] - 1e-12);
    // Nothing covered: every distance is "infinite".
    const quilt::Coverage empty(0.0, 0.0, 1.0, 1.0, 0.1);
    for (double v : empty.empty_distance()) EXPECT_EQ(v, std::numeric_limits<double>::max());
}

TEST(Coverage, LargestEmptyDiscAreaDensityAndMask) {
    // Two 1 x 1 stones 1.0 apart along x: the widest empty disc between them has radius 0.5.
    const Mesh m = shapes::concat(block(2, 0.5, Vec3(0, 0, 0)), block(2, 0.5, Vec3(2, 0, 0)));
    const double r = quilt::largest_empty_radius(m, 1.2, 0.2, 1.8, 0.8, 0.02);
    EXPECT_NEAR(r, 0.5, 0.03);
    // Each stone has area 2 x 1 + 4 x 0.5 = 4; over a disc holding the whole 5 x 3 raster, 8 / 15.
    quilt::Coverage cov(-1.0, -1.0, 4.0, 2.0, 0.02);
    cov.add(m);
    EXPECT_NEAR(cov.area_density(Vec2(1.5, 0.5), 10.0), 8.0 / 15.0, 1e-9);
    EXPECT_NEAR(cov.area_density(Vec2(1.5, 0.5), 0.4), 0.0, 1e-12);  // the gap between them
    // With a mask (the ground of a surface patch), only its pixels count: [-0.5, 3.5] x [-0.5, 1.5]
    // here, area 8, holding both stones.
    quilt::Coverage ground(-1.0, -1.0, 4.0, 2.0, 0.02);
    Mesh sheet;
    sheet.vertices = {Vec3(-0.5, -0.5, 0), Vec3(3.5, -0.5, 0), Vec3(3.5, 1.5, 0), Vec3(-0.5, 1.5, 0)};
    sheet.faces = {{0, 1, 2}, {0, 2, 3}};
    ground.add(sheet);
    EXPECT_NEAR(cov.area_density(Vec2(1.5, 0.5), 10.0, &ground), 1.0, 1e-9);
    EXPECT_NEAR(ground.covered_share(Vec2(1.5, 0.5), 10.0), 8.0 / 15.0, 1e-9);
    EXPECT_NEAR(ground.covered_share(Vec2(1.5, 0.5), 0.5), 1.0, 1e-12);
    EXPECT_NEAR(ground.covered_share(Vec2(-0.9, 1.9), 0.05), 0.0, 1e-12);
    // Beyond the mask counts as covered: distances end at its border.
    auto distance_at = [&](double x, double y) {
        return cov.empty_distance()[static_cast<std::size_t>(cov.row(y)) * static_cast<std::size_t>(cov.nx()) + static_cast<std::size_t>(cov.column(x))];
    };
    EXPECT_NEAR(distance_at(1.5, 1.2), std::hypot(0.5, 0.2), 0.03);  // to the nearer stone's corner
    cov.cover_outside(ground);
    EXPECT_EQ(distance_at(1.5, 1.8), 0.0);
    EXPECT_NEAR(distance_at(1.5, 1.2), 0.3, 0.03);  // to the mask's border
    EXPECT_NEAR(distance_at(1.5, 0.5), 0.5, 0.03);  // between the stones, as before
}

TEST(Coverage, ProjectedDensityIgnoresHeight) {
    // A stone flattened to a tenth of its height keeps its projected area density (top and bottom
    // faces: 2 x 1 per stone); by 3D area it would lose the sides' share.
    Mesh tall = block(2, 0.5, Vec3(0, 0, 0));
    Mesh flat = tall;
    for (Vec3& v : flat.vertices) v.z() *= 0.1;
    quilt::Coverage a(-1.0, -1.0, 2.0, 2.0, 0.02, true), b(-1.0, -1.0, 2.0, 2.0, 0.02, true), c(-1.0, -1.0, 2.0, 2.0, 0.02);
    a.add(tall);
    b.add(flat);
    c.add(flat);
    EXPECT_NEAR(a.area_density(Vec2(0.5, 0.5), 10.0), 2.0 / 9.0, 1e-9);
    EXPECT_NEAR(b.area_density(Vec2(0.5, 0.5), 10.0), 2.0 / 9.0, 1e-9);
    EXPECT_NEAR(c.area_density(Vec2(0.5, 0.5), 10.0), 2.2 / 9.0, 1e-9);  // 3D: sides of height 0.05
}

TEST(Coverage, ManyMeshesAtOnceGiveTheSameRaster) {
    // Random overlapping triangles of mixed size and orientation, some off the raster, some
    // degenerate: added one mesh at a time and all at once, the rasters agree pixel by pixel
    // (coverage, distances and area densities alike, to the bit).
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> x(-1.0, 7.0), y(-1.0, 5.0), d(-0.6, 0.6);
    std::vector<Mesh> meshes(40);
    for (Mesh& m : meshes)
        for (int k = 0; k < 6; ++k) {
            const Vec3 c(x(rng), y(rng), d(rng));
            const int base = static_cast<int>(m.vertices.size());
            m.vertices.push_back(c);
            m.vertices.push_back(c + Vec3(d(rng), d(rng), d(rng)));
            m.vertices.push_back(k == 5 ? c : c + Vec3(d(rng), d(rng), d(rng)));  // the last one degenerate
            m.faces.push_back({base, base + 1, base + 2});
        }
    meshes.emplace_back();  // an empty one
    for (bool projected : {false, true}) {
        quilt::Coverage one(0.0, 0.0, 6.0, 4.0, 0.05, projected), all(0.0, 0.0, 6.0, 4.0, 0.05, projected);
        std::vector<const Mesh*> ptrs;
        for (const Mesh& m : meshes) {
            one.add(m);
            ptrs.push_back(&m);
        }
        all.add(ptrs);
        int covered = 0;
        for (int j = 0; j < one.ny(); ++j)
            for (int i = 0; i < one.nx(); ++i) {
                ASSERT_EQ(one.covered(i, j), all.covered(i, j)) << i << "," << j;
                covered += one.covered(i, j) ? 1 : 0;
            }
        EXPECT_GT(covered, 100);
        EXPECT_LT(covered, one.nx() * one.ny());
        EXPECT_EQ(one.empty_distance(), all.empty_distance());
        for (double r : {0.1, 0.7, 3.0})
            for (const Vec2& c : {Vec2(1.0, 1.0), Vec2(3.0, 2.0), Vec2(5.5, 3.5)}) EXPECT_EQ(one.area_density(c, r), all.area_density(c, r));
    }
}

TEST(HullSides, ClearanceAlongEachSide) {
    const std::vector<Vec2> square = quilt::xy_hull(block(2, 0.5, Vec3(0, 0, 0)));  // [0, 1]^2
    const std::vector<std::vector<Vec2>> others{quilt::xy_hull(block(2, 0.5, Vec3(1.5, 0.2, 0)))};
    const std::vector<std::size_t> sides = quilt::hull_sides(square);
    ASSERT_EQ(sides.size(), 4u);
    int facing = 0;
    for (std::size_t s : sides) {
        const Vec2 a = square[s], b = square[(s + 1) % square.size()];
        const double f = quilt::side_clearance(square, s, others, 10.0);
        if (a.x() == 1.0 && b.x() == 1.0) {  // the side facing the other stone
            EXPECT_NEAR(f, 0.5, 1e-12);
            ++facing;
        } else {
            EXPECT_EQ(f, 10.0);
        }
    }
    EXPECT_EQ(facing, 1);
}

TEST(Joints, OnlyAPavingHasJointsToClose) {
    // The bundled swatches: cobbles' joints are about a tenth of a stone, pebbles' and rivets' half
    // of one or more; chain mail and the weave have no blob.
    const quilt::JointSetup cobbles = quilt::prepare_joints(quilt::prepare_swatch(mq::read_mesh(mq::test::swatch_path("cobbles"))));
    EXPECT_TRUE(cobbles.paving);
    EXPECT_GT(cobbles.typical, 0.0);
    EXPECT_GE(cobbles.wide, cobbles.typical);
    EXPECT_DOUBLE_EQ(cobbles.limit, quilt::kJointReach * cobbles.wide);
    for (const char* name : {"pebbles", "rivets", "chainmail", "weave"})
        EXPECT_FALSE(quilt::prepare_joints(quilt::prepare_swatch(mq::read_mesh(mq::test::swatch_path(name)))).paving) << name;
}

TEST(Joints, ASideGrowsIntoAWideJointAndLeavesTheTypicalOne) {
    quilt::JointSetup setup = test_joints();
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));                                    // [0, 2] x [0, 2]
    const std::vector<std::vector<Vec2>> right{quilt::xy_hull(block(4, 0.5, Vec3(2.5, 0, 0)))};  // a joint of 0.5
    int asked = 0;
    Mesh grown;
    ASSERT_TRUE(quilt::grow_into_joints(a, right, setup, quilt::mesh_area(a), [&](const Mesh&) { return ++asked > 0; }, &grown));
    EXPECT_EQ(asked, 1);
    const mq::Box3 box = mq::bounding_box(grown);
    EXPECT_NEAR(box.max.x(), 2.4, 1e-9);  // the typical joint is left
    EXPECT_NEAR(box.min.x(), 0.0, 1e-12);
    EXPECT_NEAR(box.min.y(), 0.0, 1e-12);
    EXPECT_NEAR(box.max.y(), 2.0, 1e-12);
    EXPECT_TRUE(quilt::is_closed_oriented(grown));
    EXPECT_EQ(mq::count_self_intersections(grown), 0);

    // Refused at full growth: half of it is offered next, then a quarter.
    std::vector<double> offered;
    ASSERT_TRUE(quilt::grow_into_joints(
        a, right, setup, quilt::mesh_area(a),
        [&](const Mesh& g) {
            offered.push_back(mq::bounding_box(g).max.x());
            return offered.size() == 3;
        },
        &grown));
    ASSERT_EQ(offered.size(), 3u);
    EXPECT_NEAR(offered[1], 2.2, 1e-9);
    EXPECT_NEAR(offered[2], 2.1, 1e-9);
    EXPECT_NEAR(mq::bounding_box(grown).max.x(), 2.1, 1e-9);
}

TEST(Joints, NarrowJointsOpenGroundAndTheAreaCapLeaveAStoneAlone) {
    quilt::JointSetup setup = test_joints();
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));
    Mesh grown;
    auto never = [](const Mesh&) -> bool { ADD_FAILURE() << "nothing to grow, nothing to accept"; return false; };
    // A joint narrower than the swatch's wide ones, and a neighbour beyond the limit (open ground).
    EXPECT_FALSE(quilt::grow_into_joints(a, {quilt::xy_hull(block(4, 0.5, Vec3(2.15, 0, 0)))}, setup, quilt::mesh_area(a), never, &grown));
    EXPECT_FALSE(quilt::grow_into_joints(a, {quilt::xy_hull(block(4, 0.5, Vec3(3.0, 0, 0)))}, setup, quilt::mesh_area(a), never, &grown));
    // A stone already at its swatch element's area may not grow by 30% more.
    EXPECT_FALSE(quilt::grow_into_joints(a, {quilt::xy_hull(block(4, 0.5, Vec3(2.5, 0, 0)))}, setup, 0.7 * quilt::mesh_area(a), never, &grown));
    // Not a paving: nothing.
    setup.paving = false;
    EXPECT_FALSE(quilt::grow_into_joints(a, {quilt::xy_hull(block(4, 0.5, Vec3(2.5, 0, 0)))}, setup, quilt::mesh_area(a), never, &grown));
}

namespace {

/// The least distance from the xy projection of `m`'s vertices to the convex polygon `poly` (0 inside).
double least_distance(const Mesh& m, const std::vector<Vec2>& poly) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& v : m.vertices) {
        const Vec2 p = v.head<2>();
        bool inside = true;
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 a = poly[i], e = poly[(i + 1) % poly.size()] - a;
            if (e.x() * (p - a).y() - e.y() * (p - a).x() < 0.0) inside = false;
            const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
            d = std::min(d, (a + t * e - p).norm());
        }
        best = std::min(best, inside ? 0.0 : d);
    }
    return best;
}

}  // namespace

TEST(Gaps, AStoneGrowsIntoTheHoleWhereThreeMeetAndKeepsItsJoints) {
    // Stone a = [0, 2]^2 with narrow joints (0.1) to a stone on its right and one above; both end
    // short of a's top right corner, and a third stands diagonally beyond it: a hole about 0.8 wide.
    // Below a and left of it is open ground.
    quilt::JointSetup setup = test_joints();
    setup.reach = 1.5;
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));
    const std::vector<std::vector<Vec2>> around{quilt::xy_hull(block(4, 0.3, Vec3(2.1, 0.0, 0))),   // [2.1, 3.3] x [0, 1.2]
                                                quilt::xy_hull(block(4, 0.3, Vec3(0.0, 2.1, 0))),   // [0, 1.2] x [2.1, 3.3]
                                                quilt::xy_hull(block(4, 0.5, Vec3(2.6, 2.6, 0)))};  // [2.6, 4.6]^2
    double before = std::numeric_limits<double>::infinity();
    for (const auto& o : around) before = std::min(before, least_distance(a, o));
    ASSERT_NEAR(before, 0.1, 1e-9);
    Mesh grown;
    int asked = 0;
    ASSERT_TRUE(quilt::grow_into_gaps(a, around, setup, quilt::mesh_area(a), [&](const Mesh&) { return ++asked > 0; }, &grown));
    EXPECT_EQ(asked, 1);
    EXPECT_TRUE(quilt::is_closed_oriented(grown));
    EXPECT_EQ(mq::count_self_intersections(grown), 0);
    // Into the hole: the corner (at the half diagonal, sqrt 2, from the centre) moved out along the
    // diagonal, by at most kGapRadialShare of that radius: x + y grows by at most 2 kGapRadialShare.
    const mq::Box3 box = mq::bounding_box(grown);
    EXPECT_GT(box.max.x(), 2.2);
    EXPECT_GT(box.max.y(), 2.2);
    double corner = 0.0;
    for (const Vec3& v : grown.vertices) corner = std::max(corner, v.x() + v.y());
    EXPECT_GT(corner, 4.4);
    EXPECT_LE(corner, 4.0 + 2.0 * quilt::kGapRadialShare + 1e-9);
    // Every neighbour keeps at least the typical joint (up to the sampling of directions) ...
    for (const auto& o : around) EXPECT_GT(least_distance(grown, o), 0.9 * setup.typical);
    // ... and the sides facing narrow joints, the far sides and the height stay where they were.
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
        const Vec3& p = a.vertices[i];
        const Vec3& q = grown.vertices[i];
        EXPECT_DOUBLE_EQ(q.z(), p.z());
        if (p.y() <= 1.0 + 1e-12 || p.x() <= 1.0 + 1e-12) {
            EXPECT_NEAR((q - p).norm(), 0.0, 0.05 * (1.0 + std::abs(p.x() - 1.0) + std::abs(p.y() - 1.0))) << p.transpose();
        }
    }
    EXPECT_GT(quilt::mesh_area(grown), quilt::mesh_area(a));
    EXPECT_LE(quilt::mesh_area(grown), quilt::kMaxGrowth * quilt::mesh_area(a));

    // Refused at full growth: three quarters, then half of the move is offered next.
    std::vector<double> offered;
    ASSERT_TRUE(quilt::grow_into_gaps(
        a, around, setup, quilt::mesh_area(a),
        [&](const Mesh& g) {
            double c = 0.0;
            for (const Vec3& v : g.vertices) c = std::max(c, v.x() + v.y());
            offered.push_back(c);
            return offered.size() == 3;
        },
        &grown));
    ASSERT_EQ(offered.size(), 3u);
    EXPECT_GT(offered[0], offered[1]);
    EXPECT_GT(offered[1], offered[2]);
    EXPECT_NEAR(offered[2] - 4.0, 0.5 * (offered[0] - 4.0), 1e-9);  // half the move
}

// The hole's far side is two stones whose joint runs along the diagonal, straight away from a's
// corner: the ray along it passes through the joint and meets nothing, but the rays beside it
// (kGapConeHalfAngle) meet the two stones, so the hole is no open ground and the corner grows
// (with the single ray it stayed: checked to fail).
TEST(Gaps, AJointBeyondTheHoleDoesNotMakeItOpenGround) {
    quilt::JointSetup setup = test_joints();
    setup.reach = 3.0;  // the rays 30 degrees off the diagonal meet the far stones about 2.3 from the corner
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));
    const std::vector<std::vector<Vec2>> around{quilt::xy_hull(block(4, 0.3, Vec3(2.1, 0.0, 0))),  // [2.1, 3.3] x [0, 1.2]
                                                quilt::xy_hull(block(4, 0.3, Vec3(0.0, 2.1, 0))),  // [0, 1.2] x [2.1, 3.3]
                                                {Vec2(2.6, 2.7), Vec2(4.5, 4.6), Vec2(2.6, 4.6)},  // above y = x + 0.1
                                                {Vec2(2.7, 2.6), Vec2(4.6, 2.6), Vec2(4.6, 4.5)}}; // below y = x - 0.1
    Mesh grown;
    ASSERT_TRUE(quilt::grow_into_gaps(a, around, setup, quilt::mesh_area(a), [](const Mesh&) { return true; }, &grown));
    double corner = 0.0;
    for (const Vec3& v : grown.vertices) corner = std::max(corner, v.x() + v.y());
    EXPECT_GT(corner, 4.4);
    for (const auto& o : around) EXPECT_GT(least_distance(grown, o), 0.9 * setup.typical);
}

TEST(Gaps, NarrowJointsOpenGroundAndNoPavingLeaveAStoneAlone) {
    quilt::JointSetup setup = test_joints();
    setup.reach = 1.5;
    const Mesh a = block(4, 0.5, Vec3(0, 0, 0));
    Mesh grown;
    auto never = [](const Mesh&) -> bool { ADD_FAILURE() << "nothing to grow, nothing to accept"; return false; };
    // Narrow joints all round (a ring of four stones 0.1 away): nothing to grow.
    const std::vector<std::vector<Vec2>> ring{quilt::xy_hull(block(4, 0.5, Vec3(2.1, 0, 0))), quilt::xy_hull(block(4, 0.5, Vec3(-2.1, 0, 0))),
                                              quilt::xy_hull(block(4, 0.5, Vec3(0, 2.1, 0))), quilt::xy_hull(block(4, 0.5, Vec3(0, -2.1, 0)))};
    EXPECT_FALSE(quilt::grow_into_gaps(a, ring, setup, quilt::mesh_area(a), never, &grown));
    // Nothing within reach: open ground (a frontier, or the base's boundary), not a gap.
    EXPECT_FALSE(quilt::grow_into_gaps(a, {quilt::xy_hull(block(4, 0.5, Vec3(3.6, 3.6, 0)))}, setup, quilt::mesh_area(a), never, &grown));
    EXPECT_FALSE(quilt::grow_into_gaps(a, {}, setup, quilt::mesh_area(a), never, &grown));
    // Every growth over the area cap: refused without asking.
    const std::vector<std::vector<Vec2>> hole{quilt::xy_hull(block(4, 0.5, Vec3(2.6, 2.6, 0)))};
    EXPECT_FALSE(quilt::grow_into_gaps(a, hole, setup, 0.7 * quilt::mesh_area(a), never, &grown));
    // Not a paving: nothing.
    setup.paving = false;
    EXPECT_FALSE(quilt::grow_into_gaps(a, hole, setup, quilt::mesh_area(a), never, &grown));
}
