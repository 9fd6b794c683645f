// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// Cutting threads where they collide (quilt/trim.h: thread_pieces): pieces are closed, oriented,
// free of self-intersections, keep clear of the flagged faces by the margin, and drop what is too
// short. Weaving a thread through crossing threads (quilt::woven) clears them within the height.

#include "core/intersect.h"
#include "meshquilt/io.h"
#include "quilt/kernel.h"
#include "quilt/trim.h"
#include "support/shapes_isect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mq = meshquilt;
namespace quilt = meshquilt::quilt;
using mq::Mesh;
using mq::Tri;
using mq::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A closed tube swept along `centre` (cross-section: half-width `w` along `across`, half-height
/// `h` along z, 8 vertices), capped by a fan at each end; outward when `flip` is false and the
/// centre line runs with x and `across` points to +y (swap for other frames).
Mesh sweep(const std::vector<Vec3>& centre, const std::vector<Vec3>& across, double w, double h, bool flip) {
    Mesh m;
    const int n = 8, rings = static_cast<int>(centre.size());
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < n; ++k) {
            const double a = 2 * kPi * k / n;
            m.vertices.push_back(centre[r] + w * std::cos(a) * across[r] + Vec3(0, 0, h * std::sin(a)));
        }
    const int c0 = static_cast<int>(m.vertices.size());
    m.vertices.push_back(centre.front());
    m.vertices.push_back(centre.back());
    for (int r = 0; r + 1 < rings; ++r)
        for (int k = 0; k < n; ++k) {
            const int a = r * n + k, b = r * n + (k + 1) % n, c = a + n, d = b + n;
            m.faces.emplace_back(a, b, d);
            m.faces.emplace_back(a, d, c);
        }
    for (int k = 0; k < n; ++k) {
        m.faces.emplace_back(c0, (k + 1) % n, k);
        m.faces.emplace_back(c0 + 1, (rings - 1) * n + k, (rings - 1) * n + (k + 1) % n);
    }
    if (flip)
        for (Tri& t : m.faces) std::swap(t[1], t[2]);
    return m;
}

/// A closed thread along x (or y with `along_y`): an elliptic tube (half-widths 0.4 across, 0.15 in
/// height) from 0 to `length`, `rings` cross-sections, a little wavy so no two cross-sections
/// share an x.
Mesh thread(double length, int rings, bool along_y = false) {
    std::vector<Vec3> centre, across;
    for (int r = 0; r < rings; ++r) {
        const double x = length * r / (rings - 1);
        centre.push_back(along_y ? Vec3(0.05 * std::sin(x), x, 0.2) : Vec3(x, 0.05 * std::sin(x), 0.2));
        across.push_back(along_y ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
    }
    return sweep(centre, across, 0.4, 0.15, along_y);  // the swap of x and y mirrors it
}

double volume(const Mesh& m) {
    double v = 0.0;
    for (const Tri& t : m.faces) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

void expect_whole(const Mesh& piece) {
    EXPECT_TRUE(quilt::is_closed_oriented(piece));
    EXPECT_EQ(mq::count_self_intersections(piece), 0);
    EXPECT_GT(volume(piece), 0.0);
}

TEST(ThreadPieces, WithoutFlagsTheThreadStaysWhole) {
    const Mesh m = thread(10.0, 41);
    ASSERT_TRUE(quilt::is_closed_oriented(m));
    ASSERT_GT(volume(m), 0.0);
    const auto pieces = quilt::thread_pieces(m, std::vector<char>(m.faces.size(), 0), {0.3, 2.0});
    ASSERT_EQ(pieces.size(), 1U);
    EXPECT_EQ(pieces[0].vertices, m.vertices);
    EXPECT_TRUE(quilt::thread_pieces(m, {}, {0.3, 2.0}).empty());  // flags of the wrong size
}

// A crossing bar collides with the middle of the thread: the two ends come out closed, clear of the
// bar, and together hold the thread's volume but the blocked span.
TEST(ThreadPieces, CutsAroundACrossingBarAndCapsBothPieces) {
    for (const bool along_y : {false, true}) {
        SCOPED_TRACE(along_y ? "along y" : "along x");
        const Mesh m = thread(10.0, 41, along_y);
        const Mesh bar = along_y ? mq::test::isect::cuboid(Vec3(-2, 4.9, 0.1), Vec3(2, 5.3, 0.3))
                                 : mq::test::isect::cuboid(Vec3(4.9, -2, 0.1), Vec3(5.3, 2, 0.3));
        mq::ElementCollider collider;
        collider.add(bar);
        const std::vector<char> bad = collider.colliding_faces(m);
        ASSERT_GT(std::count(bad.begin(), bad.end(), 1), 0);
        const double margin = 0.3;
        const auto pieces = quilt::thread_pieces(m, bad, {margin, 2.0});
        ASSERT_EQ(pieces.size(), 2U);
        const int axis = along_y ? 1 : 0;
        double kept = 0.0;
        for (const Mesh& p : pieces) {
            expect_whole(p);
            EXPECT_FALSE(collider.collides(p));
            kept += volume(p);
            const mq::Box3 b = mq::bounding_box(p);
            // Each piece ends the margin before the blocked span, give or take the half spacing of
            // cross-sections (0.25) by which the cut moves to lie midway between vertices.
            if (b.min[axis] < 1.0) EXPECT_NEAR(b.max[axis], 4.75 - margin, 0.13);
            else EXPECT_NEAR(b.min[axis], 5.5 + margin, 0.13);
        }
        // The tube's cross-section is about pi * 0.4 * 0.15 (an inscribed 8-gon: 0.9 of it).
        const double section = volume(m) / 10.0;
        EXPECT_NEAR(kept, volume(m) - section * (5.5 - 4.75 + 2 * margin), 0.15 * section);
    }
}

// A deformed strand (tests/data/trim/README.md) on which thread_pieces crashed the process in CGAL
// 5.5.1's clip (a segmentation fault, not an exception): its only free span long enough lay between
// two neighbouring vertex coordinates, under long faces, so both cuts moved to the same gap and the
// clipping box had no width. Such a span is now passed over.
TEST(ThreadPieces, ADeformedStrandDoesNotCrashTheClip) {
    const std::string path = std::string(MQ_TEST_DATA_DIR) + "/trim/strand_clip.obj";
    const Mesh m = mq::read_mesh(path);
    ASSERT_EQ(m.faces.size(), 116u);
    std::vector<char> bad(m.faces.size(), 1);
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("# Faces not flagged (0-based):", 0) == 0) {
            std::istringstream free(line.substr(line.find(':') + 1));
            for (int f; free >> f;) bad[static_cast<std::size_t>(f)] = 0;
        }
    ASSERT_GT(std::count(bad.begin(), bad.end(), 0), 0);
    for (const Mesh& piece : quilt::thread_pieces(m, bad, {0.25, 0.64})) EXPECT_TRUE(quilt::is_closed_oriented(piece));
}

// The longest free span bounds the pieces: measured as thread_pieces measures spans.
TEST(ThreadPieces, LongestFreeSpanBoundsEveryPiece) {
    const Mesh m = thread(10.0, 41);
    EXPECT_NEAR(quilt::longest_free_span(m, std::vector<char>(m.faces.size(), 0), 0.3), 10.0, 1e-9);
    EXPECT_EQ(quilt::longest_free_span(m, std::vector<char>(m.faces.size(), 1), 0.3), 0.0);
    EXPECT_EQ(quilt::longest_free_span(Mesh(), {}, 0.3), 0.0);
    EXPECT_EQ(quilt::longest_free_span(m, {}, 0.3), 0.0);  // flags of the wrong size
    // Faces between cross-sections 19 and 22 (x = 4.75 to 5.5) flagged, 0.3 margin: free are
    // [0, 4.45] and [5.8, 10].
    std::vector<char> bad(m.faces.size(), 0);
    for (int r = 19; r < 22; ++r)
        for (int k = 0; k < 16; ++k) bad[static_cast<std::size_t>(r * 16 + k)] = 1;
    const double longest = quilt::longest_free_span(m, bad, 0.3);
    EXPECT_NEAR(longest, 4.45, 1e-9);
    const auto pieces = quilt::thread_pieces(m, bad, {0.3, 1.0});
    ASSERT_EQ(pieces.size(), 2U);
    for (const Mesh& p : pieces) EXPECT_LE(mq::bounding_box(p).size().x(), longest + 1e-9);
    EXPECT_TRUE(quilt::thread_pieces(m, bad, {0.3, longest + 0.01}).empty());
}

TEST(ThreadPieces, DropsPiecesShorterThanTheMinimum) {
    const Mesh m = thread(10.0, 41);
    std::vector<char> bad(m.faces.size(), 0);
    // Flag the faces between cross-sections 6 and 7 (x = 1.5 to 1.75): the piece before is 1.5 long.
    for (int k = 0; k < 16; ++k) bad[static_cast<std::size_t>(6 * 16 + k)] = 1;
    auto pieces = quilt::thread_pieces(m, bad, {0.2, 2.0});
    ASSERT_EQ(pieces.size(), 1U);
    EXPECT_GT(mq::bounding_box(pieces[0]).min.x(), 1.75);
    expect_whole(pieces[0]);
    pieces = quilt::thread_pieces(m, bad, {0.2, 1.0});
    EXPECT_EQ(pieces.size(), 2U);
    // Everything flagged: nothing left.
    EXPECT_TRUE(quilt::thread_pieces(m, std::vector<char>(m.faces.size(), 1), {0.2, 1.0}).empty());
}

/// A hairpin: a closed tube (radius 0.3 across, 0.15 in height) along x from 0 to 8 at y = 0,
/// round a half circle of radius 1, and back along y = 2.
Mesh hairpin() {
    std::vector<Vec3> centre, across;
    for (int i = 0; i <= 32; ++i) centre.emplace_back(0.25 * i, 0.0, 0.3), across.emplace_back(0, 1, 0);
    for (int i = 1; i < 16; ++i) {
        const double a = -kPi / 2 + kPi * i / 16;
        centre.emplace_back(8.0 + std::cos(a), 1.0 + std::sin(a), 0.3);
        across.emplace_back(-std::cos(a), -std::sin(a), 0);
    }
    for (int i = 0; i <= 32; ++i) centre.emplace_back(8.0 - 0.25 * i, 2.0, 0.3), across.emplace_back(0, -1, 0);
    Mesh m = sweep(centre, across, 0.3, 0.15, false);
    if (volume(m) < 0)
        for (Tri& t : m.faces) std::swap(t[1], t[2]);
    return m;
}

// A span across a bent thread can hold two separate parts of it: each comes out as its own piece.
TEST(ThreadPieces, ABentThreadCutAcrossBothLegsGivesTwoPieces) {
    const Mesh m = hairpin();
    ASSERT_TRUE(quilt::is_closed_oriented(m));
    ASSERT_EQ(mq::count_self_intersections(m), 0);
    std::vector<char> bad(m.faces.size(), 0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)  // the bend and the last stretch of both legs
        for (int k = 0; k < 3; ++k) bad[f] = static_cast<char>(bad[f] | (m.vertices[m.faces[f][k]].x() > 7.0));
    const auto pieces = quilt::thread_pieces(m, bad, {0.1, 2.0});
    ASSERT_EQ(pieces.size(), 2U);
    double y[2];
    for (int i = 0; i < 2; ++i) {
        expect_whole(pieces[static_cast<std::size_t>(i)]);
        const mq::Box3 b = mq::bounding_box(pieces[static_cast<std::size_t>(i)]);
        EXPECT_LT(b.max.x(), 7.0);
        EXPECT_GT(b.size().x(), 6.0);
        y[i] = 0.5 * (b.min.y() + b.max.y());
    }
    EXPECT_NEAR(std::abs(y[0] - y[1]), 2.0, 0.1);  // one piece per leg
}

// A strand is cut across itself, not across an axis of the plane: a bar over one leg of a hairpin
// cuts that leg only (thread_pieces, cutting across the hairpin's axis, cuts both legs). The two
// pieces are whole, clear of the bar by the margin along the strand, and hold the hairpin's volume
// but the blocked length.
TEST(StrandPieces, CutsAcrossTheStrandWhereItCrosses) {
    const Mesh m = hairpin();
    const Mesh bar = mq::test::isect::cuboid(Vec3(3.8, -1.0, 0.2), Vec3(4.2, 0.8, 0.4));
    mq::ElementCollider collider;
    collider.add(bar);
    const std::vector<char> bad = collider.colliding_faces(m);
    ASSERT_GT(std::count(bad.begin(), bad.end(), 1), 0);
    const double margin = 0.3;
    EXPECT_EQ(quilt::thread_pieces(m, bad, {margin, 1.0}).size(), 3U);  // both legs cut
    const auto pieces = quilt::strand_pieces(m, bad, {margin, 1.0});
    ASSERT_EQ(pieces.size(), 2U);
    double kept = 0.0;
    int whole_upper_leg = 0;
    for (const Mesh& p : pieces) {
        expect_whole(p);
        EXPECT_FALSE(collider.collides(p));
        kept += volume(p);
        const mq::Box3 b = mq::bounding_box(p);
        if (b.max.y() > 1.5) {  // the rest: the upper leg whole, the bend, the lower leg from the bar on
            ++whole_upper_leg;
            EXPECT_LT(b.min.x(), 0.05);
            for (const Vec3& v : p.vertices)
                if (v.y() < 0.5) EXPECT_GT(v.x(), 4.2 + margin - 0.15);
        } else {  // the lower leg up to the bar
            EXPECT_LT(b.min.x(), 0.05);
            EXPECT_NEAR(b.max.x(), 3.8 - margin, 0.15);
        }
    }
    EXPECT_EQ(whole_upper_leg, 1);
    const double section = volume(hairpin()) / (16.0 + kPi);  // per unit of length, about
    EXPECT_NEAR(kept, volume(m) - section * (0.4 + 2 * margin), 0.35 * section);
}

// Without flags a strand stays whole; flags over the whole strand leave nothing; a piece shorter than
// the minimum is dropped; a compact element (no two distinct ends) gives no pieces.
TEST(StrandPieces, KeepsWholeDropsShortAndRefusesBlobs) {
    const Mesh m = hairpin();
    const auto whole = quilt::strand_pieces(m, std::vector<char>(m.faces.size(), 0), {0.3, 1.0});
    ASSERT_EQ(whole.size(), 1U);
    EXPECT_EQ(whole[0].vertices, m.vertices);
    EXPECT_TRUE(quilt::strand_pieces(m, std::vector<char>(m.faces.size(), 1), {0.3, 1.0}).empty());
    std::vector<char> bad(m.faces.size(), 0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)  // the lower leg from x = 1.5 to 2
        for (int k = 0; k < 3; ++k) {
            const Vec3& v = m.vertices[m.faces[f][k]];
            bad[f] = static_cast<char>(bad[f] | (v.y() < 0.5 && v.x() > 1.5 && v.x() < 2.0));
        }
    const auto pieces = quilt::strand_pieces(m, bad, {0.2, 2.0});  // the stub before x = 1.3 is too short
    ASSERT_EQ(pieces.size(), 1U);  // the rest: the lower leg from x = 2.2, the bend and the upper leg
    for (const Vec3& v : pieces[0].vertices)
        if (v.y() < 0.5) EXPECT_GT(v.x(), 2.0);
    EXPECT_LT(mq::bounding_box(pieces[0]).min.x(), 0.05);
    const Mesh cube = mq::test::isect::cuboid(Vec3(0, 0, 0), Vec3(1, 1, 1));
    std::vector<char> one(cube.faces.size(), 0);
    one[0] = 1;
    EXPECT_TRUE(quilt::strand_pieces(cube, one, {0.1, 0.2}).empty());
}

/// A flat star (height 0.2) of `arms` arms, half-width 0.15, reaching 3 from the origin, round a
/// small hub: each arm's top and bottom are ladders of 30 steps, the hub a fan from the origin, the
/// outline's walls quads; closed, oriented outwards.
Mesh star(int arms) {
    std::vector<mq::Vec2> outline;  // per arm: one side outwards (31 points), the other back
    const int steps = 30, per_arm = 2 * (steps + 1);
    for (int a = 0; a < arms; ++a) {
        const double t = 2 * kPi * a / arms;
        const mq::Vec2 u(std::cos(t), std::sin(t)), w(-std::sin(t), std::cos(t));
        const double hub = arms > 2 ? 0.15 / std::tan(kPi / arms) + 0.01 : 0.01;
        for (int k = 0; k <= steps; ++k) outline.push_back((hub + (3.0 - hub) * k / steps) * u - 0.15 * w);
        for (int k = steps; k >= 0; --k) outline.push_back((hub + (3.0 - hub) * k / steps) * u + 0.15 * w);
    }
    const int n = static_cast<int>(outline.size());
    Mesh m;
    for (const double z : {0.0, 0.2})
        for (const mq::Vec2& p : outline) m.vertices.emplace_back(p.x(), p.y(), z);
    m.vertices.emplace_back(0, 0, 0);
    m.vertices.emplace_back(0, 0, 0.2);
    auto top = [&](int a, int b, int c) {
        m.faces.emplace_back(n + a, n + b, n + c);
        m.faces.emplace_back(c, b, a);
    };
    for (int a = 0; a < arms; ++a) {
        const int o = a * per_arm;
        auto side1 = [&](int k) { return o + k; };                  // outwards, on the right of the arm
        auto side2 = [&](int k) { return o + per_arm - 1 - k; };    // the left side, at step k
        for (int k = 0; k < steps; ++k) {
            top(side1(k), side1(k + 1), side2(k + 1));
            top(side1(k), side2(k + 1), side2(k));
        }
        const int next = ((a + 1) % arms) * per_arm;
        m.faces.emplace_back(2 * n + 1, n + side1(0), n + side2(0));  // the hub, on top and below
        m.faces.emplace_back(side2(0), side1(0), 2 * n);
        m.faces.emplace_back(2 * n + 1, n + side2(0), n + next);
        m.faces.emplace_back(next, side2(0), 2 * n);
    }
    for (int i = 0; i < n; ++i) {  // walls
        const int j = (i + 1) % n;
        m.faces.emplace_back(i, j, n + j);
        m.faces.emplace_back(i, n + j, n + i);
    }
    if (volume(m) < 0)
        for (Tri& t : m.faces) std::swap(t[1], t[2]);
    return m;
}

// A branching element (three arms: a snowflake's or a star's shape) is not a strand to cut: cut
// across its "length" between two arm tips, the third arm would go with whichever piece holds the
// hub. It gives no pieces; two arms (a bar through the hub) are cut as any strand.
TEST(StrandPieces, ABranchingElementIsNotCut) {
    for (const int arms : {2, 3}) {
        SCOPED_TRACE(arms);
        const Mesh m = star(arms);
        ASSERT_TRUE(quilt::is_closed_oriented(m));
        ASSERT_GT(volume(m), 0.0);
        std::vector<char> bad(m.faces.size(), 0);
        for (std::size_t f = 0; f < m.faces.size(); ++f)  // the first arm from 1.5 to 1.8 out
            for (int k = 0; k < 3; ++k) {
                const Vec3& v = m.vertices[m.faces[f][k]];
                bad[f] = static_cast<char>(bad[f] | (std::abs(v.y()) < 0.2 && v.x() > 1.5 && v.x() < 1.8));
            }
        ASSERT_GT(std::count(bad.begin(), bad.end(), 1), 0);
        const auto pieces = quilt::strand_pieces(m, bad, {0.1, 0.5});
        if (arms == 3) {
            EXPECT_TRUE(pieces.empty());
            continue;
        }
        ASSERT_EQ(pieces.size(), 2U);
        for (const Mesh& p : pieces) {
            expect_whole(p);
            for (const Vec3& v : p.vertices) EXPECT_FALSE(v.x() > 1.55 && v.x() < 1.75) << v.transpose();
        }
    }
}

// A thread that passes through itself (here a thread along x and a second closed tube across it, in
// one mesh) is outside CGAL's clip precondition: its corefinement once crashed (a Truchet knot on a
// genus-16 plate). It gives no pieces, even where the part to keep is clean, and never crashes.
TEST(ThreadPieces, AThreadThatIntersectsItselfGivesNoPieces) {
    Mesh m = thread(10.0, 41);
    std::vector<Vec3> centre, across;
    for (int r = 0; r <= 20; ++r) centre.emplace_back(5.0, -2.0 + 0.2 * r, 0.2), across.emplace_back(1, 0, 0);
    const Mesh cross = sweep(centre, across, 0.3, 0.1, true);
    const int base = static_cast<int>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), cross.vertices.begin(), cross.vertices.end());
    for (const Tri& t : cross.faces) m.faces.emplace_back(t[0] + base, t[1] + base, t[2] + base);
    ASSERT_TRUE(quilt::is_closed_oriented(m));
    ASSERT_GT(mq::count_self_intersections(m), 0);
    std::vector<char> bad(m.faces.size(), 0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)  // the thread's first two units
        for (int k = 0; k < 3; ++k) bad[f] = static_cast<char>(bad[f] | (m.vertices[m.faces[f][k]].x() < 2.0));
    EXPECT_TRUE(quilt::thread_pieces(m, bad, {0.2, 1.0}).empty());
    // The same cut of the thread alone keeps the rest, so the flags leave a piece to keep.
    const Mesh alone = thread(10.0, 41);
    EXPECT_EQ(quilt::thread_pieces(alone, std::vector<char>(bad.begin(), bad.begin() + static_cast<std::ptrdiff_t>(alone.faces.size())), {0.2, 1.0}).size(), 1U);
}

}  // namespace

namespace {

/// A straight tube along y at `x` from y = -2 to 2 (41 cross-sections), centred at height `z`,
/// half-width 0.4, half-height 0.15: a crossing thread at one height.
Mesh crossing_at(double x, double z, double half_height = 0.15) {
    std::vector<Vec3> centre, across;
    for (int r = 0; r <= 40; ++r) {
        centre.emplace_back(x, -2.0 + 0.1 * r, z);
        across.emplace_back(1, 0, 0);
    }
    return sweep(centre, across, 0.4, half_height, true);
}

/// A straight thread along x from 0 to 10 (101 cross-sections) at height 0.5, half-width 0.4,
/// half-height 0.2.
Mesh straight_thread() {
    std::vector<Vec3> centre, across;
    for (int r = 0; r <= 100; ++r) {
        centre.emplace_back(0.1 * r, 0.0, 0.5);
        across.emplace_back(0, 1, 0);
    }
    return sweep(centre, across, 0.4, 0.2, false);
}

/// The lowest and highest heights of `m`'s vertices within 0.05 of x.
std::pair<double, double> heights_at(const Mesh& m, double x) {
    double lo = 2.0, hi = -1.0;
    for (const Vec3& v : m.vertices)
        if (std::fabs(v.x() - x) < 0.05) {
            lo = std::min(lo, v.z());
            hi = std::max(hi, v.z());
        }
    return {lo, hi};
}

}  // namespace

TEST(Woven, PassesOverAndUnderIrregularCrossingThreadsWithinTheHeight) {
    // A thread along x at mid height (0.3-0.7 of [0, 1]) meets six crossing threads, low or high in
    // no regular order and at irregular spacings: straight, it cuts through every one of them.
    const Mesh straight = straight_thread();
    ASSERT_TRUE(quilt::is_closed_oriented(straight));
    const std::vector<std::pair<double, double>> at = {{1.3, 0.25}, {2.9, 0.25}, {4.2, 0.75}, {6.1, 0.25}, {7.4, 0.75}, {8.8, 0.75}};
    std::vector<Mesh> crossing;
    for (const auto& [x, z] : at) crossing.push_back(crossing_at(x, z));
    std::vector<const Mesh*> ptrs;
    for (const Mesh& c : crossing) {
        ASSERT_TRUE(mq::meshes_intersect(straight, c));
        ptrs.push_back(&c);
    }
    const Mesh w = quilt::woven(straight, 0, ptrs, 0.8, 0.0, 1.0);
    // Woven: it clears every crossing thread, stays within the height, keeps its xy and stays whole.
    ASSERT_EQ(w.vertices.size(), straight.vertices.size());
    EXPECT_EQ(w.faces, straight.faces);
    for (std::size_t v = 0; v < w.vertices.size(); ++v) {
        EXPECT_EQ(w.vertices[v].x(), straight.vertices[v].x());
        EXPECT_EQ(w.vertices[v].y(), straight.vertices[v].y());
        EXPECT_GE(w.vertices[v].z(), -1e-9);
        EXPECT_LE(w.vertices[v].z(), 1.0 + 1e-9);
    }
    for (std::size_t k = 0; k < crossing.size(); ++k) EXPECT_FALSE(mq::meshes_intersect(w, crossing[k])) << "crossing thread " << k;
    expect_whole(w);
    // Over a low thread, under a high one.
    for (const auto& [x, z] : at) {
        const auto [lo, hi] = heights_at(w, x);
        if (z < 0.5) EXPECT_GT(lo, z + 0.15) << "over the thread at x = " << x;
        else EXPECT_LT(hi, z - 0.15) << "under the thread at x = " << x;
    }
    // Nothing to weave through: the thread itself.
    const Mesh same = quilt::woven(straight, 0, {}, 0.8, 0.0, 1.0);
    EXPECT_EQ(same.vertices, straight.vertices);
}

TEST(Woven, IsSquashedWhereACrossingThreadLeavesLessRoomThanItsThickness) {
    // A crossing thread 0.44 high in the middle of the height [0, 1] leaves 0.28 above and below
    // it: too little for the thread's 0.4, enough for 0.7 of it. The thread passes squashed there
    // (as pressed threads do) and keeps its whole thickness a width away.
    const Mesh straight = straight_thread();
    const Mesh tight = crossing_at(5.0, 0.5, 0.22);
    ASSERT_TRUE(mq::meshes_intersect(straight, tight));
    const Mesh w = quilt::woven(straight, 0, {&tight}, 0.8, 0.0, 1.0);
    EXPECT_FALSE(mq::meshes_intersect(w, tight));
    expect_whole(w);
    const auto [lo, hi] = heights_at(w, 5.0);
    EXPECT_GE(lo, -1e-9);
    EXPECT_LE(hi, 1.0 + 1e-9);
    EXPECT_GE(hi - lo, quilt::kMinSquash * 0.4 - 1e-9);
    EXPECT_LT(hi - lo, 0.3);
    for (double x : {2.0, 8.0}) {
        const auto [l, h] = heights_at(w, x);
        EXPECT_NEAR(h - l, 0.4, 1e-9) << "whole at x = " << x;
    }
    // Where the room is below kMinSquash of the thickness (0.1 of 0.4 here), it is not squashed
    // further: it still meets the crossing thread, and the caller cuts it there.
    const Mesh blocking = crossing_at(5.0, 0.5, 0.4);
    const Mesh b = quilt::woven(straight, 0, {&blocking}, 0.8, 0.0, 1.0);
    EXPECT_TRUE(mq::meshes_intersect(b, blocking));
    const auto [blo, bhi] = heights_at(b, 5.0);
    EXPECT_NEAR(bhi - blo, quilt::kMinSquash * 0.4, 1e-6);
}
