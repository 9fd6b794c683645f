// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// Filling a base's small holes on the synthesis's copy (quilt/holes.h: fill_small_holes): small
// loops get faces over their own vertices, oriented as the faces around them; large loops, long
// loops and loops through one position twice stay open.

#include "meshquilt/analysis.h"
#include "quilt/holes.h"
#include "support/shapes_isect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mq = meshquilt;
namespace quilt = meshquilt::quilt;
using mq::Mesh;
using mq::Tri;
using mq::Vec3;

namespace {

double area(const Mesh& m) {
    double a = 0.0;
    for (const Tri& t : m.faces)
        a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
    return a;
}

double volume(const Mesh& m) {
    double v = 0.0;
    for (const Tri& t : m.faces) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

/// `m` without the faces for which `drop` is true.
template <class Drop>
Mesh without(const Mesh& m, Drop drop) {
    Mesh r = m;
    r.faces.clear();
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        if (!drop(f)) r.faces.push_back(m.faces[f]);
    return r;
}

/// The faces of `m` around vertex `v`, and `m` without them.
std::vector<std::size_t> star(const Mesh& m, int v) {
    std::vector<std::size_t> s;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        if (m.faces[f][0] == v || m.faces[f][1] == v || m.faces[f][2] == v) s.push_back(f);
    return s;
}

// A sphere with a cap cut off (a large hole), three lone triangles and one vertex's star removed
// (small holes): the small ones are filled with faces over their own vertices, oriented as the
// sphere, and the cap stays open.
TEST(FillSmallHoles, FillsSmallLoopsAndLeavesLargeOnes) {
    const Mesh sphere = mq::test::isect::icosphere(1.0, 3);
    std::vector<char> drop(sphere.faces.size(), 0);
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
        Vec3 c = Vec3::Zero();
        for (int k = 0; k < 3; ++k) c += sphere.vertices[sphere.faces[f][k]] / 3.0;
        if (c.z() > 0.8) drop[f] = 1;  // the cap
    }
    // Lone triangles and a star, far from the cap and from each other.
    std::vector<Vec3> at{Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0)};
    for (const Vec3& p : at) {
        std::size_t best = 0;
        double d = 1e9;
        for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
            const double e = (sphere.vertices[sphere.faces[f][0]] - p).norm();
            if (e < d) d = e, best = f;
        }
        drop[best] = 1;
    }
    int pole = 0;
    for (std::size_t v = 0; v < sphere.vertices.size(); ++v)
        if ((sphere.vertices[v] - Vec3(0, -0.6, -0.8)).norm() < (sphere.vertices[static_cast<std::size_t>(pole)] - Vec3(0, -0.6, -0.8)).norm())
            pole = static_cast<int>(v);
    const std::vector<std::size_t> s = star(sphere, pole);
    ASSERT_GE(s.size(), 5U);
    for (const std::size_t f : s) drop[f] = 1;
    Mesh m = without(sphere, [&](std::size_t f) { return drop[f] != 0; });
    const mq::MeshAnalysis before = mq::analyse(m);
    ASSERT_EQ(before.boundary_loops, 5);
    ASSERT_EQ(before.non_manifold_vertices, 0);
    const std::size_t faces_before = m.faces.size();
    const double area_before = area(m);

    const quilt::HoleFilling r = quilt::fill_small_holes(m, 0.5, 100);
    EXPECT_EQ(r.loops, 5);
    EXPECT_EQ(r.filled, 4);
    // Three triangles, and the star's polygon of s.size() vertices in s.size() - 2 triangles.
    EXPECT_EQ(r.faces, static_cast<int>(3 + s.size() - 2));
    EXPECT_EQ(m.faces.size(), faces_before + static_cast<std::size_t>(r.faces));
    EXPECT_EQ(m.vertices.size(), sphere.vertices.size());
    EXPECT_LE(r.largest, 0.5);
    EXPECT_GT(r.largest, 0.1);
    // The old faces keep their places.
    for (std::size_t f = 0; f < faces_before; ++f) EXPECT_EQ(m.faces[f], without(sphere, [&](std::size_t g) { return drop[g] != 0; }).faces[f]);
    const mq::MeshAnalysis after = mq::analyse(m);
    EXPECT_EQ(after.boundary_loops, 1);  // the cap
    EXPECT_EQ(after.inconsistent_edges, 0);
    EXPECT_EQ(after.non_manifold_edges, 0);
    EXPECT_EQ(after.degenerate_faces, 0);
    // The filled faces cover about what was cut (flat over a curved sphere: a little less).
    const double cut = area(sphere) - area_before;
    double cap = 0.0;
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
        Vec3 c = Vec3::Zero();
        for (int k = 0; k < 3; ++k) c += sphere.vertices[sphere.faces[f][k]] / 3.0;
        if (c.z() > 0.8) cap += area(Mesh{sphere.vertices, {sphere.faces[f]}});
    }
    EXPECT_NEAR(area(m) - area_before, cut - cap, 0.05 * (cut - cap));

    // Everything filled when the cap counts as small; the sphere is closed again and outward.
    Mesh all = without(sphere, [&](std::size_t f) { return drop[f] != 0; });
    EXPECT_EQ(quilt::fill_small_holes(all, 10.0, 1000).filled, 5);
    EXPECT_EQ(mq::analyse(all).closed_elements(), 1);
    EXPECT_GT(volume(all), 0.9 * volume(sphere));
    // ... but not when the cap's loop is longer than allowed.
    Mesh few = without(sphere, [&](std::size_t f) { return drop[f] != 0; });
    EXPECT_EQ(quilt::fill_small_holes(few, 10.0, 8).filled, 4);
    // Filled the same way twice: the output is deterministic.
    Mesh again = without(sphere, [&](std::size_t f) { return drop[f] != 0; });
    quilt::fill_small_holes(again, 0.5, 100);
    EXPECT_EQ(again.faces, m.faces);
}

// Two triangles removed that share only a vertex: two holes that touch, both filled. Once that
// vertex is split (one copy per fan), their loop passes twice through one position: it stays
// open. A closed mesh has nothing to fill.
TEST(FillSmallHoles, LeavesLoopsThroughOnePointTwiceAndClosedMeshes) {
    const Mesh sphere = mq::test::isect::icosphere(1.0, 2);
    Mesh closed = sphere;
    const quilt::HoleFilling none = quilt::fill_small_holes(closed, 1.0, 100);
    EXPECT_EQ(none.loops, 0);
    EXPECT_EQ(closed.faces, sphere.faces);
    // Around vertex 0: faces 0 and 2 of its star do not share an edge (a star has at least 5).
    const std::vector<std::size_t> s0 = star(sphere, 0);
    ASSERT_GE(s0.size(), 5U);
    const std::size_t a = s0[0];
    std::size_t b = sphere.faces.size();
    for (std::size_t i = 1; i < s0.size() && b == sphere.faces.size(); ++i) {
        int shared = 0;
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) shared += sphere.faces[a][j] == sphere.faces[s0[i]][k];
        if (shared == 1) b = s0[i];
    }
    ASSERT_LT(b, sphere.faces.size());
    Mesh m = without(sphere, [&](std::size_t f) { return f == a || f == b; });
    ASSERT_EQ(mq::analyse(m).non_manifold_vertices, 1);
    // As they are, the two holes are two loops through the shared vertex: both filled, and the
    // sphere is whole again.
    Mesh touching = m;
    const quilt::HoleFilling both = quilt::fill_small_holes(touching, 1.0, 100);
    EXPECT_EQ(both.loops, 2);
    EXPECT_EQ(both.filled, 2);
    EXPECT_EQ(both.faces, 2);
    const mq::MeshAnalysis whole = mq::analyse(touching);
    EXPECT_EQ(whole.closed_elements(), 1);
    EXPECT_EQ(whole.non_manifold_vertices, 0);
    EXPECT_GT(volume(touching), 0.0);
    // Split first, they are one loop through one position twice.
    EXPECT_EQ(mq::split_non_manifold_vertices(m), 1);
    const std::size_t faces = m.faces.size();
    const quilt::HoleFilling r = quilt::fill_small_holes(m, 1.0, 100);
    EXPECT_EQ(r.loops, 1);
    EXPECT_EQ(r.filled, 0);
    EXPECT_EQ(m.faces.size(), faces);
}

}  // namespace
