// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// Closest-point queries (core/triangle_index.h) against brute force over every face: random
// triangle soups with degenerate faces, queries far from, near and on the surface, the nearness
// test at the exact boundary, box queries, and the empty index.

#include "core/triangle_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace meshquilt {
namespace {

/// Random triangles in the unit cube, a fifth of them degenerate (a repeated corner, collinear
/// corners, or a needle), sharing vertices now and then as a mesh would.
Mesh soup(int faces, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Mesh m;
    for (int f = 0; f < faces; ++f) {
        const Vec3 a(u(rng), u(rng), u(rng));
        const Vec3 b = a + 0.1 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        Vec3 c = a + 0.1 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        switch (f % 10) {
            case 3: c = b; break;                        // a repeated corner
            case 7: c = a + 2.0 * (b - a); break;        // collinear
            case 9: c = b + 1e-12 * (b - a); break;       // a needle
            default: break;
        }
        const int base = static_cast<int>(m.vertices.size());
        m.vertices.push_back(a);
        m.vertices.push_back(b);
        m.vertices.push_back(c);
        // Every fourth face reuses a corner of the face before it.
        m.faces.push_back(f % 4 == 1 ? Tri(base - 1, base + 1, base + 2) : Tri(base, base + 1, base + 2));
    }
    return m;
}

/// A closed octahedron subdivided twice and pushed onto the unit sphere.
Mesh ball() {
    Mesh m;
    m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int level = 0; level < 2; ++level) {
        std::vector<Tri> faces;
        for (const Tri& t : m.faces) {
            int mid[3];
            for (int k = 0; k < 3; ++k) {
                m.vertices.push_back((0.5 * (m.vertices[static_cast<std::size_t>(t[k])] + m.vertices[static_cast<std::size_t>(t[(k + 1) % 3])])).normalized());
                mid[k] = static_cast<int>(m.vertices.size()) - 1;
            }
            faces.push_back({t[0], mid[0], mid[2]});
            faces.push_back({t[1], mid[1], mid[0]});
            faces.push_back({t[2], mid[2], mid[1]});
            faces.push_back({mid[0], mid[1], mid[2]});
        }
        m.faces = faces;
    }
    return m;
}

double face_distance(const Mesh& m, std::size_t f, const Vec3& p) {
    const Tri& t = m.faces[f];
    return (closest_point_on_triangle(p, m.vertices[static_cast<std::size_t>(t[0])], m.vertices[static_cast<std::size_t>(t[1])],
                                      m.vertices[static_cast<std::size_t>(t[2])], nullptr) -
            p)
        .norm();
}

double brute_distance(const Mesh& m, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < m.faces.size(); ++f) best = std::min(best, face_distance(m, f, p));
    return best;
}

/// Query points: uniform in a box three times the unit cube, the mesh's vertices and face
/// centroids, and points just off the faces (a millionth and a thousandth of the cube along
/// random directions).
std::vector<Vec3> queries(const Mesh& m, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 2.0), d(-1.0, 1.0);
    std::vector<Vec3> q;
    for (int i = 0; i < 1500; ++i) q.emplace_back(u(rng), u(rng), u(rng));
    for (std::size_t v = 0; v < m.vertices.size(); v += 3) q.push_back(m.vertices[v]);
    for (std::size_t f = 0; f < m.faces.size(); f += 2) {
        const Tri& t = m.faces[f];
        const Vec3 c = (m.vertices[static_cast<std::size_t>(t[0])] + m.vertices[static_cast<std::size_t>(t[1])] + m.vertices[static_cast<std::size_t>(t[2])]) / 3.0;
        q.push_back(c);
        q.push_back(c + 1e-6 * Vec3(d(rng), d(rng), d(rng)));
        q.push_back(c + 1e-3 * Vec3(d(rng), d(rng), d(rng)));
    }
    return q;
}

void expect_agrees_with_brute_force(const Mesh& m, unsigned seed) {
    const TriangleIndex index(m);
    for (const Vec3& p : queries(m, seed)) {
        const double want = brute_distance(m, p);
        const ClosestHit hit = index.closest(p);
        ASSERT_GE(hit.face, 0);
        ASSERT_LT(hit.face, static_cast<int>(m.faces.size()));
        // The same distance as the best face's, exactly, and the reported face has it.
        EXPECT_EQ(hit.distance, want) << "at " << p.transpose();
        EXPECT_EQ(face_distance(m, static_cast<std::size_t>(hit.face), p), want);
        EXPECT_NEAR((hit.point - p).norm(), want, 1e-15);
        const Tri& t = m.faces[static_cast<std::size_t>(hit.face)];
        const Vec3 from_bary = hit.bary[0] * m.vertices[static_cast<std::size_t>(t[0])] + hit.bary[1] * m.vertices[static_cast<std::size_t>(t[1])] +
                               hit.bary[2] * m.vertices[static_cast<std::size_t>(t[2])];
        EXPECT_LT((from_bary - hit.point).norm(), 1e-12);
        // within() at the boundary: a distance exactly r is within r; one ulp less is not.
        EXPECT_TRUE(index.within(p, want));
        EXPECT_TRUE(index.within(p, 2.0 * want + 1e-9));
        if (want > 0.0) {
            EXPECT_FALSE(index.within(p, std::nextafter(want, 0.0))) << "at " << p.transpose();
            EXPECT_FALSE(index.within(p, 0.5 * want));
        }
    }
}

TEST(TriangleIndex, ClosestAgreesWithBruteForceOnSoups) {
    expect_agrees_with_brute_force(soup(60, 1), 11);
    expect_agrees_with_brute_force(soup(700, 2), 12);
}

TEST(TriangleIndex, ClosestAgreesWithBruteForceOnAClosedMesh) { expect_agrees_with_brute_force(ball(), 13); }

TEST(TriangleIndex, FacesInBoxAreThoseWhoseBoxesMeetIt) {
    const Mesh m = soup(500, 3);
    const TriangleIndex index(m);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.2, 1.2), s(0.0, 0.3);
    for (int i = 0; i < 300; ++i) {
        const Vec3 lo(u(rng), u(rng), u(rng));
        const Box3 box{lo, lo + Vec3(s(rng), s(rng), i % 10 == 0 ? 0.0 : s(rng))};  // some flat boxes
        std::vector<int> want;
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            Box3 fb;
            for (int k = 0; k < 3; ++k) fb.extend(m.vertices[static_cast<std::size_t>(m.faces[f][k])]);
            if (fb.overlaps(box, 0.0)) want.push_back(static_cast<int>(f));
        }
        EXPECT_EQ(index.faces_in_box(box), want) << "box " << i;
    }
}

TEST(TriangleIndex, EmptyIndexAnswersNothing) {
    const TriangleIndex index{Mesh{}};
    EXPECT_TRUE(index.empty());
    const ClosestHit hit = index.closest(Vec3(1, 2, 3));
    EXPECT_EQ(hit.face, -1);
    EXPECT_TRUE(std::isinf(hit.distance));
    EXPECT_FALSE(index.within(Vec3(1, 2, 3), 1e300));
    EXPECT_TRUE(index.faces_in_box(Box3{Vec3::Constant(-1e9), Vec3::Constant(1e9)}).empty());
}

TEST(TriangleIndex, OneFaceAndFacesAtOnePoint) {
    // A single face, and many faces stacked on the same spot (every split ties).
    Mesh one;
    one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    one.faces = {{0, 1, 2}};
    const TriangleIndex i1(one);
    EXPECT_EQ(i1.closest(Vec3(0.25, 0.25, 2.0)).distance, 2.0);
    EXPECT_EQ(i1.closest(Vec3(0.25, 0.25, 2.0)).face, 0);
    Mesh stack;
    stack.vertices = one.vertices;
    for (int k = 0; k < 100; ++k) stack.faces.push_back({0, 1, 2});
    stack.faces.insert(stack.faces.begin(), Tri(1, 1, 1));  // a point face, first, and far
    stack.faces.push_back({0, 0, 0});                       // a point face at the nearest corner, last
    const TriangleIndex i2(stack);
    EXPECT_EQ(i2.closest(Vec3(-1, 0, 0)).distance, 1.0);
    EXPECT_EQ(i2.closest(Vec3(-1, 0, 0)).face, 1);  // the lowest index among the nearest, whatever the tree
    EXPECT_EQ(i2.faces_in_box(Box3{Vec3(0.5, 0.5, -1), Vec3(2, 2, 1)}).size(), 100u);  // the stack, not the two points
}

}  // namespace
}  // namespace meshquilt
