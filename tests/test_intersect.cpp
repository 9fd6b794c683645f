// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// Exact intersection tests (core/intersect.h): triangle pairs at the exact boundary of touching,
// meshes, element pairs, self-intersections with shared vertices and edges, and ElementCollider
// against a brute-force oracle.

#include "core/intersect.h"

#include "meshquilt/errors.h"
#include "support/shapes_isect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace meshquilt {
namespace {

namespace sh = test::isect;

Vec3 V(double x, double y, double z) { return {x, y, z}; }
double up(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }
double down(double x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }

Triangle3 shifted(const Triangle3& t, const Vec3& d) { return {t[0] + d, t[1] + d, t[2] + d}; }

// ---------------------------------------------------------------------------------------------
// triangles_intersect: the exact boundary

// The plane x + y + z = 1 holds (0.25, 0.25, 0.5) exactly; a triangle whose apex is that point
// touches, one ulp lower it pierces, one ulp higher it misses. Inexact arithmetic gets at least one
// of these wrong, especially after a large offset.
TEST(TrianglesIntersect, VertexOnFaceIsDecidedExactly) {
    for (const double offset : {0.0, 1048576.0, -3.0e6}) {
        const Vec3 o = Vec3::Constant(offset);
        const Triangle3 plane = shifted({V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)}, o);
        const Triangle3 touch = shifted({V(0.25, 0.25, 0.5), V(0.25, 0.25, 3), V(1, 2, 3)}, o);
        Triangle3 above = touch, below = touch;
        above[0].z() = up(above[0].z());
        below[0].z() = down(below[0].z());
        SCOPED_TRACE(offset);
        EXPECT_TRUE(triangles_intersect(plane, touch));
        EXPECT_TRUE(triangles_intersect(plane, below));
        EXPECT_FALSE(triangles_intersect(plane, above));
        EXPECT_TRUE(triangles_intersect(touch, plane));  // symmetric
        EXPECT_FALSE(triangles_intersect(above, plane));
    }
}

// A point one ulp off the plane x = y, seen from a triangle whose corners are far away: the
// differences p - corner lose that ulp in double arithmetic, so a floating-point orientation is 0
// ("touching") while the exact answer is "apart" (cf. Kettner et al., Classroom examples of
// robustness problems in geometric computations, 2008).
TEST(TrianglesIntersect, ExactWhereFloatingPointCancels) {
    const Triangle3 wall{V(12, 12, -1), V(24, 24, -1), V(-12, -12, 1)};  // in the plane x = y
    const double x = 0.5;
    const Triangle3 off{V(x, up(x), 0), V(x, 3, 0), V(x, 3, 1)};    // y > x everywhere
    const Triangle3 on{V(x, x, 0), V(x, 3, 0), V(x, 3, 1)};         // touches at (x, x, 0)
    const Triangle3 across{V(x, down(x), 0), V(x, 3, 0), V(x, 3, 1)};  // crosses
    EXPECT_FALSE(triangles_intersect(wall, off));
    EXPECT_TRUE(triangles_intersect(wall, on));
    EXPECT_TRUE(triangles_intersect(wall, across));
    EXPECT_FALSE(triangles_intersect(off, wall));
}

TEST(TrianglesIntersect, EdgeTouchesEdgeExactly) {
    const Triangle3 a{V(0, 0, 0), V(2, 0, 0), V(0, 2, 0)};            // hypotenuse on x + y = 2
    const Triangle3 b{V(1, 1, 0), V(2, 2, 1), V(2, 2, -1)};           // touches the hypotenuse at (1,1,0)
    Triangle3 c = b;
    c[0] = V(up(1.0), up(1.0), 0.0);                                  // just outside
    EXPECT_TRUE(triangles_intersect(a, b));
    EXPECT_FALSE(triangles_intersect(a, c));
    const Triangle3 crossing{V(1, -1, 0.5), V(1, 1, -0.5), V(1, 3, 2)};  // pierces a's interior
    EXPECT_TRUE(triangles_intersect(a, crossing));
}

TEST(TrianglesIntersect, CoplanarCases) {
    const Triangle3 a{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
    EXPECT_TRUE(triangles_intersect(a, {V(0.2, 0.2, 0), V(2, 0.2, 0), V(0.2, 2, 0)}));  // overlapping
    EXPECT_TRUE(triangles_intersect(a, {V(1, 0, 0), V(2, 0, 0), V(1, 1, 0)}));          // share a corner
    EXPECT_TRUE(triangles_intersect(a, {V(0.5, 0.5, 0), V(1, 1, 0), V(0, 1, 0)}));      // share part of an edge
    EXPECT_FALSE(triangles_intersect(a, {V(up(0.5), up(0.5), 0), V(1, 1, 0), V(up(0.5), 1, 0)}));
    EXPECT_FALSE(triangles_intersect(a, {V(2, 2, 0), V(3, 2, 0), V(2, 3, 0)}));         // apart
}

TEST(TrianglesIntersect, DegenerateFacesAreSegmentsOrPoints) {
    const Triangle3 a{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
    const Triangle3 needle{V(0.2, 0.2, -1), V(0.2, 0.2, 0), V(0.2, 0.2, 1)};  // collinear, pierces
    const Triangle3 needle_off{V(2, 2, -1), V(2, 2, 1), V(2, 2, 0)};
    const Triangle3 dot{V(0.25, 0.25, 0), V(0.25, 0.25, 0), V(0.25, 0.25, 0)};
    const Triangle3 dot_off{V(0.25, 0.25, 1e-300), V(0.25, 0.25, 1e-300), V(0.25, 0.25, 1e-300)};
    EXPECT_TRUE(triangles_intersect(a, needle));
    EXPECT_TRUE(triangles_intersect(needle, a));
    EXPECT_FALSE(triangles_intersect(a, needle_off));
    EXPECT_TRUE(triangles_intersect(a, dot));
    EXPECT_FALSE(triangles_intersect(a, dot_off));
    EXPECT_TRUE(triangles_intersect(needle, {V(0.2, 0.2, 0.5), V(0.2, 0.2, 0.5), V(0.2, 0.2, 0.5)}));
    EXPECT_TRUE(triangles_intersect(needle, {V(0, 0.2, 0.5), V(1, 0.2, 0.5), V(0.5, 0.2, 0.5)}));  // crossing segments
    EXPECT_FALSE(triangles_intersect(needle, {V(0, 0.2, 0.5), V(0.1, 0.2, 0.5), V(0.05, 0.2, 0.5)}));
    EXPECT_TRUE(is_degenerate_triangle(V(0, 0, 0), V(1, 1, 1), V(3, 3, 3)));
    EXPECT_FALSE(is_degenerate_triangle(V(0, 0, 0), V(1, 1, 1), V(3, 3, up(3.0))));
}

TEST(TrianglesIntersect, RejectsNonFinite) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)triangles_intersect({V(nan, 0, 0), V(1, 0, 0), V(0, 1, 0)}, {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}),
                 InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// meshes_intersect

TEST(MeshesIntersect, Tori) {
    const Mesh a = sh::torus(1.0, 0.25);
    EXPECT_FALSE(meshes_intersect(a, sh::torus(1.0, 0.25, 32, 12, V(3, 0, 0))));  // apart
    EXPECT_TRUE(meshes_intersect(a, sh::torus(1.0, 0.25, 32, 12, V(0.5, 0.2, 0.1))));  // overlapping
    // Hopf link: the second ring passes through the first's hole without touching it.
    const Mesh hopf = sh::torus(1.0, 0.25, 32, 12, V(1, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
    EXPECT_FALSE(meshes_intersect(a, hopf));
    EXPECT_FALSE(meshes_intersect(hopf, a));
    // Same link, tubes fat enough to collide.
    EXPECT_TRUE(meshes_intersect(sh::torus(1.0, 0.55), sh::torus(1.0, 0.55, 32, 12, V(1, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2))));
    // A small torus floating inside the big one's hole.
    EXPECT_FALSE(meshes_intersect(a, sh::torus(0.3, 0.1, 24, 8, V(0, 0, 0), sh::rotation(V(0, 1, 0), 0.7))));
    // Identical meshes, and a mesh with itself, intersect.
    EXPECT_TRUE(meshes_intersect(a, a));
    EXPECT_FALSE(meshes_intersect(a, Mesh{}));
}

TEST(MeshesIntersect, TouchingBoxesExactly) {
    const Mesh a = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    EXPECT_TRUE(meshes_intersect(a, sh::cuboid(V(1, 0.5, 0.5), V(2, 2, 2))));         // face contact
    EXPECT_TRUE(meshes_intersect(a, sh::cuboid(V(1, 1, 1), V(2, 2, 2))));             // corner contact
    EXPECT_FALSE(meshes_intersect(a, sh::cuboid(V(up(1.0), 0, 0), V(2, 1, 1))));       // one ulp apart
    EXPECT_FALSE(meshes_intersect(a, sh::cuboid(V(0.25, 0.25, 0.25), V(0.75, 0.75, 0.75))));  // nested, no surface contact
}

TEST(MeshesIntersect, LargeMeshesUseTheParallelPathCorrectly) {
    // 20480 faces each: enough to split the traversal into parallel tasks.
    const Mesh a = sh::icosphere(1.0, 5);
    EXPECT_TRUE(meshes_intersect(a, sh::icosphere(1.0, 5, V(1.9, 0.1, 0))));
    EXPECT_FALSE(meshes_intersect(a, sh::icosphere(1.0, 5, V(2.0001, 0.0, 0))));  // polyhedral spheres lie inside radius 1
    EXPECT_FALSE(meshes_intersect(a, sh::icosphere(0.99, 5)));                    // concentric, inside
}

TEST(MeshesIntersect, RejectsBadInput) {
    Mesh a = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    Mesh bad = a;
    bad.faces[3][1] = 8;
    EXPECT_THROW((void)meshes_intersect(a, bad), InvalidInput);
    bad = a;
    bad.vertices[2].y() = std::numeric_limits<double>::infinity();
    try {
        (void)meshes_intersect(bad, a);
        FAIL() << "no exception";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
    }
}

// ---------------------------------------------------------------------------------------------
// intersecting_element_pairs

/// Brute force: every face pair of every element pair, exact test, no broad phase.
std::vector<std::pair<int, int>> brute_force_pairs(const std::vector<Mesh>& parts) {
    std::vector<std::pair<int, int>> out;
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (std::size_t j = i + 1; j < parts.size(); ++j) {
            if (!bounding_box(parts[i]).overlaps(bounding_box(parts[j]))) continue;  // sound, and independent
            bool hit = false;
            for (const Tri& f : parts[i].faces) {
                const Triangle3 tf{parts[i].vertices[f[0]], parts[i].vertices[f[1]], parts[i].vertices[f[2]]};
                for (const Tri& g : parts[j].faces)
                    if (triangles_intersect(tf, {parts[j].vertices[g[0]], parts[j].vertices[g[1]], parts[j].vertices[g[2]]})) {
                        hit = true;
                        break;
                    }
                if (hit) break;
            }
            if (hit) out.emplace_back(static_cast<int>(i), static_cast<int>(j));
        }
    return out;
}

TEST(IntersectingElementPairs, FindsExactlyTheIntersectingPairs) {
    const std::vector<Mesh> parts = {
        sh::torus(1.0, 0.25),                                                              // 0
        sh::torus(1.0, 0.25, 32, 12, V(0.5, 0.2, 0.1)),                                    // 1: overlaps 0
        sh::torus(1.0, 0.25, 32, 12, V(6, 0, 0)),                                          // 2
        sh::torus(1.0, 0.25, 32, 12, V(7, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2)),      // 3: linked with 2, no contact
        sh::cuboid(V(10, 0, 0), V(11, 1, 1)),                                              // 4
        sh::cuboid(V(11, 1, 1), V(12, 2, 2)),                                              // 5: touches 4 at a corner
        sh::cuboid(V(up(12.0), 0, 0), V(13, 1, 1)),                                        // 6: one ulp from 5
    };
    const auto c = sh::combine(parts);
    const std::vector<std::pair<int, int>> expected{{0, 1}, {4, 5}};
    EXPECT_EQ(intersecting_element_pairs(c.mesh, c.element_of_face), expected);
    EXPECT_EQ(brute_force_pairs(parts), expected);
    const std::vector<std::pair<int, int>> first{{0, 1}};
    EXPECT_EQ(intersecting_element_pairs(c.mesh, c.element_of_face, 1), first);
    EXPECT_TRUE(intersecting_element_pairs(c.mesh, c.element_of_face, 0).empty());
}

TEST(IntersectingElementPairs, KeepsSparseElementIds) {
    const auto c = sh::combine({sh::torus(1.0, 0.25), sh::torus(1.0, 0.25, 32, 12, V(9, 0, 0)),
                                sh::torus(1.0, 0.25, 32, 12, V(0.5, 0.2, 0.1))});
    for (const int big : {900, 1000000}) {  // a small lookup table, or sorting
        auto ids = c.element_of_face;
        for (int& e : ids) e = e == 0 ? 70 : e == 1 ? 5 : big;
        const std::vector<std::pair<int, int>> expected{{70, big}};
        EXPECT_EQ(intersecting_element_pairs(c.mesh, ids), expected);
    }
}

TEST(IntersectingElementPairs, AgreesWithBruteForceOnRandomSpheres) {
    std::mt19937 rng(20060731);
    std::uniform_real_distribution<double> pos(0.0, 4.0), rad(0.2, 0.6);
    std::vector<Mesh> parts;
    for (int k = 0; k < 60; ++k) parts.push_back(sh::icosphere(rad(rng), 1, V(pos(rng), pos(rng), pos(rng))));
    const auto c = sh::combine(parts);
    const auto expected = brute_force_pairs(parts);
    ASSERT_GT(expected.size(), 5U);  // the test means something
    EXPECT_EQ(intersecting_element_pairs(c.mesh, c.element_of_face), expected);
    // Deterministic and a prefix under max_pairs.
    const auto some = intersecting_element_pairs(c.mesh, c.element_of_face, 3);
    EXPECT_EQ(some, (std::vector<std::pair<int, int>>(expected.begin(), expected.begin() + 3)));
}

TEST(IntersectingElementPairs, BigElementsInParallel) {
    // Two 20480-face spheres overlapping; a third well apart. Faces of one element are never
    // tested against each other, so the (closed) spheres do not count as self-intersecting pairs.
    const auto c = sh::combine({sh::icosphere(1.0, 5), sh::icosphere(1.0, 5, V(1.5, 0, 0)), sh::icosphere(1.0, 5, V(0, 5, 0))});
    const std::vector<std::pair<int, int>> expected{{0, 1}};
    EXPECT_EQ(intersecting_element_pairs(c.mesh, c.element_of_face), expected);
}

TEST(IntersectingElementPairs, RejectsBadInput) {
    auto c = sh::combine({sh::torus(1.0, 0.25), sh::torus(1.0, 0.25, 32, 12, V(9, 0, 0))});
    std::vector<int> short_ids(c.element_of_face.begin(), c.element_of_face.end() - 1);
    EXPECT_THROW((void)intersecting_element_pairs(c.mesh, short_ids), InvalidInput);
    auto neg = c.element_of_face;
    neg[5] = -1;
    EXPECT_THROW((void)intersecting_element_pairs(c.mesh, neg), InvalidInput);
    c.mesh.faces[7][2] = -4;
    EXPECT_THROW((void)intersecting_element_pairs(c.mesh, c.element_of_face), InvalidInput);
    EXPECT_TRUE(intersecting_element_pairs(Mesh{}, {}).empty());
}

// ---------------------------------------------------------------------------------------------
// count_self_intersections

Mesh two_triangles(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    // Faces (a, b, c) and (b, a, d) share the edge ab.
    Mesh m;
    m.vertices = {a, b, c, d};
    m.faces = {Tri(0, 1, 2), Tri(1, 0, 3)};
    return m;
}

TEST(CountSelfIntersections, ClosedMeshesHaveNone) {
    EXPECT_EQ(count_self_intersections(sh::torus(1.0, 0.25)), 0);
    EXPECT_EQ(count_self_intersections(sh::torus(1.0, 0.9, 64, 32)), 0);  // a fat torus: its hole is tiny
    EXPECT_EQ(count_self_intersections(sh::icosphere(1.0, 3)), 0);
    EXPECT_EQ(count_self_intersections(sh::cuboid(V(0, 0, 0), V(1, 1, 1))), 0);  // coplanar adjacent faces
    EXPECT_EQ(count_self_intersections(sh::icosphere(1.0, 5)), 0);                // parallel path
}

TEST(CountSelfIntersections, SharedEdge) {
    // Flat (coplanar, opposite sides): fine. Folded flat onto itself (same side): counted.
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.5, -1, 0))), 0);
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.3, 0.2, 0))), 1);
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(2, 1, 0))), 1);
    // Almost folded (one ulp out of the plane) is a valid, very sharp crease.
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.3, 0.2, 1e-300))), 0);
    // Any dihedral angle other than 0 is fine.
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.5, 1, 0.001))), 0);
}

TEST(CountSelfIntersections, SharedVertex) {
    Mesh m;
    m.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0), V(-1, 1, 0), V(1, 1, 1), V(1, -1, 1)};
    m.faces = {Tri(0, 1, 2), Tri(0, 3, 4)};  // coplanar; the second's wedge overlaps the first's
    EXPECT_EQ(count_self_intersections(m), 1);
    m.faces = {Tri(0, 1, 2), Tri(0, 4, 2)};  // shares edge 0-2, lies on the other side: fine
    EXPECT_EQ(count_self_intersections(m), 0);
    m.faces = {Tri(0, 1, 2), Tri(0, 5, 6)};  // only the shared vertex in common
    EXPECT_EQ(count_self_intersections(m), 0);
    m.vertices[6] = V(0.2, 0.2, -1);
    m.faces = {Tri(0, 1, 2), Tri(0, 5, 6)};  // the second pierces the first away from vertex 0
    EXPECT_EQ(count_self_intersections(m), 1);
}

TEST(CountSelfIntersections, FlatGridAndInPlaneFold) {
    // All faces coplanar (decimal, inexact coordinates): neighbours touch only where they share.
    const int n = 12;
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.vertices.push_back(V(0.1 * i, 0.1 * j + 0.03 * i, 0.7 * 0.1 * i - 0.3 * 0.1 * j));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            m.faces.emplace_back(a, b, c);
            m.faces.emplace_back(a, c, d);
        }
    EXPECT_EQ(count_self_intersections(m), 0);
    // In the plane z = 0 (exactly coplanar), slide one vertex past its right neighbour: the fan
    // folds over itself. (In the tilted plane above, rounding makes the faces not exactly coplanar,
    // and then the folded faces may, exactly, pass just above or below each other.)
    for (Vec3& p : m.vertices) p.z() = 0.0;
    EXPECT_EQ(count_self_intersections(m), 0);
    Mesh folded = m;
    const int v = 6 * (n + 1) + 6;
    folded.vertices[static_cast<std::size_t>(v)] += 1.5 * (m.vertices[static_cast<std::size_t>(v) + 1] - m.vertices[static_cast<std::size_t>(v)]);
    EXPECT_GT(count_self_intersections(folded), 0);
}

TEST(CountSelfIntersections, FoldedFaceInAClosedMesh) {
    // Push one torus vertex through the opposite side of the tube: its faces now cross others.
    Mesh m = sh::torus(1.0, 0.25, 32, 12);
    const Vec3 c(1, 0, 0);  // centre of the tube's cross-section at vertex 0 (u = 0, v = 0)
    m.vertices[0] = c - 2.0 * (m.vertices[0] - c);
    EXPECT_GT(count_self_intersections(m), 0);
    // A spindle torus (tube radius > ring radius) passes through itself.
    EXPECT_GT(count_self_intersections(sh::torus(0.5, 1.0, 32, 16)), 10);
    EXPECT_EQ(count_self_intersections(sh::torus(0.5, 1.0, 32, 16), 3), 3);  // capped
}

TEST(SelfIntersectingFaces, FlagsExactlyTheFacesOfTheCountedPairs) {
    EXPECT_EQ(self_intersecting_faces(sh::torus(1.0, 0.25)), std::vector<char>(sh::torus(1.0, 0.25).faces.size(), 0));
    // The torus with one vertex pushed through the tube: flagged faces are those of the pairs that
    // count_self_intersections counts, checked pair by pair here.
    Mesh m = sh::torus(1.0, 0.25, 32, 12);
    const Vec3 c(1, 0, 0);
    m.vertices[0] = c - 2.0 * (m.vertices[0] - c);
    const std::vector<char> flags = self_intersecting_faces(m);
    ASSERT_EQ(flags.size(), m.faces.size());
    std::vector<char> expected(m.faces.size(), 0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (std::size_t g = f + 1; g < m.faces.size(); ++g) {
            Mesh pair;
            pair.vertices = m.vertices;
            pair.faces = {m.faces[f], m.faces[g]};
            if (count_self_intersections(pair) > 0) expected[f] = expected[g] = 1;
        }
    EXPECT_EQ(flags, expected);
    EXPECT_GT(std::count(flags.begin(), flags.end(), 1), 2);
    // Every face that touches vertex 0 crosses something; faces far from it do not.
    EXPECT_EQ(flags[m.faces.size() / 2], 0);
}

TEST(CountSelfIntersections, DuplicatedFaceAndTJunction) {
    Mesh m = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    m.faces.push_back(m.faces[4]);
    EXPECT_EQ(count_self_intersections(m), 1);
    Mesh t;
    t.vertices = {V(0, 0, 0), V(2, 0, 0), V(1, 1, 0), V(1, 0, 0), V(1, -1, 0), V(1, 0, 1)};
    t.faces = {Tri(0, 1, 2), Tri(3, 4, 5)};  // vertex 3 lies on edge 0-1 without being shared
    EXPECT_EQ(count_self_intersections(t), 1);
}

TEST(CountSelfIntersections, UnweldedVerticesCountAsShared) {
    // A triangle soup (every face has its own copies of its corners) is judged by geometry.
    const Mesh welded = sh::torus(1.0, 0.25, 24, 8);
    Mesh soup;
    for (const Tri& f : welded.faces) {
        const int n = static_cast<int>(soup.vertices.size());
        for (int k = 0; k < 3; ++k) soup.vertices.push_back(welded.vertices[f[k]]);
        soup.faces.emplace_back(n, n + 1, n + 2);
    }
    EXPECT_EQ(count_self_intersections(soup), 0);
    Mesh fat = sh::torus(0.5, 1.0, 24, 8);
    EXPECT_GT(count_self_intersections(fat), 0);
}

TEST(CountSelfIntersections, IgnoresUnusedVertices) {
    Mesh m = sh::torus(1.0, 0.25);
    m.vertices.push_back(V(std::numeric_limits<double>::quiet_NaN(), 0, 0));  // unused, not finite
    m.vertices.push_back(m.vertices[0]);                                      // unused duplicate
    EXPECT_EQ(count_self_intersections(m), 0);
    EXPECT_TRUE(meshes_intersect(m, sh::torus(1.0, 0.25, 32, 12, V(0.5, 0, 0))));
}

TEST(CountSelfIntersections, DegenerateFaces) {
    // A sliver whose third corner lies on the shared edge adds nothing beyond the edge.
    EXPECT_EQ(count_self_intersections(two_triangles(V(0, 0, 0), V(1, 0, 0), V(0.5, 1, 0), V(0.5, 0, 0))), 0);
    // A collinear face sharing a vertex, pointing into the other face: overlap beyond the vertex.
    Mesh m;
    m.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.2, 0.2, 0), V(0.4, 0.4, 0), V(-1, -1, 0)};
    m.faces = {Tri(0, 1, 2), Tri(0, 3, 4)};
    EXPECT_EQ(count_self_intersections(m), 1);
    m.faces = {Tri(0, 1, 2), Tri(0, 5, 5)};  // points away: only the vertex in common
    EXPECT_EQ(count_self_intersections(m), 0);
    m.faces = {Tri(0, 1, 2), Tri(0, 5, 3)};  // collinear through vertex 0: one half away, one half in
    EXPECT_EQ(count_self_intersections(m), 1);
    // A collinear face piercing an unrelated face.
    m.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.2, 0.2, 0.5)};
    m.faces = {Tri(0, 1, 2), Tri(3, 4, 5)};
    EXPECT_EQ(count_self_intersections(m), 1);
}

// ---------------------------------------------------------------------------------------------
// ElementCollider

struct Sphere {
    Vec3 c;
    double r;
    Mesh mesh;
};

/// Oracle: exact face-pair tests, skipping pairs whose circumscribed spheres are apart (sound,
/// since an icosphere lies inside its sphere).
bool brute_collide(const Sphere& a, const Sphere& b) {
    if ((a.c - b.c).norm() > a.r + b.r) return false;
    for (const Tri& f : a.mesh.faces)
        for (const Tri& g : b.mesh.faces)
            if (triangles_intersect({a.mesh.vertices[f[0]], a.mesh.vertices[f[1]], a.mesh.vertices[f[2]]},
                                    {b.mesh.vertices[g[0]], b.mesh.vertices[g[1]], b.mesh.vertices[g[2]]}))
                return true;
    return false;
}

std::vector<Sphere> random_spheres(std::mt19937& rng, int n, double lo, double hi) {
    std::uniform_real_distribution<double> pos(0.0, 6.0), rad(lo, hi);
    std::vector<Sphere> out;
    for (int k = 0; k < n; ++k) {
        Sphere s{V(pos(rng), pos(rng), pos(rng)), rad(rng), {}};
        s.mesh = sh::icosphere(s.r, 1, s.c);
        out.push_back(std::move(s));
    }
    return out;
}

void expect_agrees_with_brute_force(const ElementColliderOptions& options, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const auto placed = random_spheres(rng, 80, 0.2, 0.7);
    const auto queries = random_spheres(rng, 40, 0.2, 0.9);
    ElementCollider collider(options);
    for (std::size_t k = 0; k < placed.size(); ++k) ASSERT_EQ(collider.add(placed[k].mesh), static_cast<int>(k));
    std::set<int> removed;
    std::size_t checked_hits = 0;
    for (int round = 0; round < 2; ++round) {
        for (std::size_t q = 0; q < queries.size(); ++q) {
            std::vector<int> expected;
            for (std::size_t k = 0; k < placed.size(); ++k)
                if (!removed.count(static_cast<int>(k)) && brute_collide(queries[q], placed[k])) expected.push_back(static_cast<int>(k));
            checked_hits += expected.size();
            EXPECT_EQ(collider.colliding(queries[q].mesh), expected) << "query " << q << " round " << round;
            EXPECT_EQ(collider.collides(queries[q].mesh), !expected.empty());
            // Per face: flagged exactly when it touches a face of a stored element.
            std::vector<char> faces(queries[q].mesh.faces.size(), 0);
            for (int k : expected)
                for (std::size_t f = 0; f < faces.size(); ++f) {
                    const Tri& a = queries[q].mesh.faces[f];
                    const Mesh& pm = placed[static_cast<std::size_t>(k)].mesh;
                    for (const Tri& b : pm.faces)
                        if (triangles_intersect({queries[q].mesh.vertices[a[0]], queries[q].mesh.vertices[a[1]], queries[q].mesh.vertices[a[2]]},
                                                {pm.vertices[b[0]], pm.vertices[b[1]], pm.vertices[b[2]]})) {
                            faces[f] = 1;
                            break;
                        }
                }
            EXPECT_EQ(collider.colliding_faces(queries[q].mesh), faces) << "query " << q << " round " << round;
            if (!expected.empty()) {  // ignoring a hit drops exactly that one
                std::vector<int> rest(expected.begin() + 1, expected.end());
                EXPECT_EQ(collider.colliding(queries[q].mesh, {expected.front(), 9999}), rest);
            }
        }
        for (int k = 0; k < 80; k += 2) {  // then remove every other element and check again
            collider.remove(k);
            removed.insert(k);
        }
        collider.remove(0);  // twice: no-op
        collider.remove(-3);
        EXPECT_EQ(collider.size(), 40U);
    }
    EXPECT_GT(checked_hits, 20U);  // the scene has real collisions
}

TEST(ElementCollider, AgreesWithBruteForceOnRandomSpheres) {
    expect_agrees_with_brute_force({}, 7);
    expect_agrees_with_brute_force({}, 8);
}

TEST(ElementCollider, TinyCellsAndOversizedElementsGiveTheSameAnswers) {
    ElementColliderOptions tiny;
    tiny.cell_size = 0.05;  // most elements cover too many cells and go to the oversized list
    expect_agrees_with_brute_force(tiny, 7);
    ElementColliderOptions coarse;
    coarse.cell_size = 100.0;  // everything in one cell
    expect_agrees_with_brute_force(coarse, 9);
}

TEST(ElementCollider, QueriesFromAnIdOnCompleteEarlierAnswers) {
    // What a candidate met before some elements went in (first_id 0), those of them still stored,
    // and what it meets from next_id() of that time on, are what it meets now.
    std::mt19937 rng(11);
    const auto placed = random_spheres(rng, 80, 0.2, 0.7);
    const auto queries = random_spheres(rng, 40, 0.2, 0.9);
    ElementCollider collider;
    EXPECT_EQ(collider.next_id(), 0);
    for (std::size_t k = 0; k < 40; ++k) ASSERT_EQ(collider.add(placed[k].mesh), static_cast<int>(k));
    const int since = collider.next_id();
    ASSERT_EQ(since, 40);
    std::vector<std::vector<int>> before;
    std::vector<std::vector<char>> before_faces;
    for (const Sphere& q : queries) {
        before.push_back(collider.colliding(q.mesh));
        before_faces.push_back(collider.colliding_faces(q.mesh));
        EXPECT_TRUE(collider.colliding(q.mesh, {}, since).empty());  // nothing from there on yet
        EXPECT_FALSE(collider.collides(q.mesh, {}, since));
    }
    for (std::size_t k = 40; k < placed.size(); ++k) ASSERT_EQ(collider.add(placed[k].mesh), static_cast<int>(k));
    for (int k = 0; k < 80; k += 3) collider.remove(k);  // old and new ones go
    for (int k = 0; k < 80; ++k) EXPECT_EQ(collider.contains(k), k % 3 != 0) << k;
    EXPECT_FALSE(collider.contains(-1));
    EXPECT_FALSE(collider.contains(80));
    std::size_t joined = 0, kept_faces = 0;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        const Mesh& m = queries[q].mesh;
        std::vector<int> expect;
        for (int id : before[q])
            if (collider.contains(id)) expect.push_back(id);
        const std::vector<int> later = collider.colliding(m, {}, since);
        for (int id : later) EXPECT_GE(id, since);
        joined += later.size();
        expect.insert(expect.end(), later.begin(), later.end());
        EXPECT_EQ(collider.colliding(m), expect) << "query " << q;
        EXPECT_EQ(collider.collides(m, {}, since), !later.empty()) << "query " << q;
        if (!later.empty()) {  // ignoring still works from an id on
            EXPECT_EQ(collider.colliding(m, {later.front()}, since), std::vector<int>(later.begin() + 1, later.end()));
        }
        // Faces: where none of the earlier hits went, the earlier faces and the later ones make up
        // the whole answer.
        if (std::all_of(before[q].begin(), before[q].end(), [&](int id) { return collider.contains(id); })) {
            std::vector<char> faces = collider.colliding_faces(m, {}, static_cast<std::size_t>(-1), since);
            for (std::size_t f = 0; f < faces.size(); ++f) faces[f] = static_cast<char>(faces[f] | before_faces[q][f]);
            EXPECT_EQ(faces, collider.colliding_faces(m)) << "query " << q;
            ++kept_faces;
        }
        EXPECT_TRUE(collider.colliding(m, {}, collider.next_id()).empty());
        EXPECT_EQ(collider.colliding(m, {}, -5), collider.colliding(m));
    }
    EXPECT_GT(joined, 5U);       // later elements were met
    EXPECT_GT(kept_faces, 10U);  // and the face answers were compared
}

TEST(ElementCollider, FirstCollidingFacesFlagOneFacePerElementAndGroup) {
    // Per element met and group of faces that meets it: exactly one flag, on a face that
    // colliding_faces flags too. Asked of all elements at once: a flag on a face meeting each
    // element in each group that meets it, and no more flags than such pairs.
    std::mt19937 rng(5);
    const auto placed = random_spheres(rng, 60, 0.2, 0.6);
    const auto queries = random_spheres(rng, 30, 0.8, 1.4);
    ElementCollider collider;
    for (const Sphere& p : placed) collider.add(p.mesh);
    std::size_t met = 0, split = 0;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        const Mesh& m = queries[q].mesh;
        std::vector<int> group(m.faces.size());  // by slabs along x
        for (std::size_t f = 0; f < m.faces.size(); ++f)
            group[f] = static_cast<int>(std::floor((m.vertices[static_cast<std::size_t>(m.faces[f][0])].x() - queries[q].c.x()) / 0.5));
        const std::vector<char> all = collider.first_colliding_faces(m, group);
        const std::vector<char> full = collider.colliding_faces(m);
        std::size_t pairs = 0;
        for (int id : collider.colliding(m)) {
            std::vector<int> others;
            for (int k = 0; k < static_cast<int>(placed.size()); ++k)
                if (k != id) others.push_back(k);
            const std::vector<char> mine = collider.colliding_faces(m, others);
            const std::vector<char> first = collider.first_colliding_faces(m, group, others);
            std::map<int, int> flags, meets;  // per group
            for (std::size_t f = 0; f < m.faces.size(); ++f) {
                if (first[f]) {
                    EXPECT_TRUE(mine[f]) << "query " << q << " element " << id << " face " << f;
                    ++flags[group[f]];
                }
                if (mine[f]) ++meets[group[f]];
            }
            for (const auto& [g, n] : meets) {
                EXPECT_EQ(flags[g], 1) << "query " << q << " element " << id << " group " << g;
                bool flagged = false;
                for (std::size_t f = 0; f < m.faces.size(); ++f) flagged = flagged || (group[f] == g && mine[f] && all[f]);
                EXPECT_TRUE(flagged) << "query " << q << " element " << id << " group " << g;
            }
            pairs += meets.size();
            for (const auto& [g, n] : flags) EXPECT_GT(meets[g], 0) << "query " << q << " element " << id << " group " << g;
            ++met;
            split += meets.size() > 1 ? 1U : 0U;
            // One group: one face per element.
            const std::vector<char> one = collider.first_colliding_faces(m, {}, others);
            EXPECT_EQ(std::count(one.begin(), one.end(), 1), 1) << "query " << q << " element " << id;
        }
        EXPECT_LE(static_cast<std::size_t>(std::count(all.begin(), all.end(), 1)), pairs) << "query " << q;
        for (std::size_t f = 0; f < m.faces.size(); ++f)
            if (all[f]) EXPECT_TRUE(full[f]) << "query " << q << " face " << f;
    }
    EXPECT_GT(met, 20U);   // elements were met
    EXPECT_GT(split, 5U);  // and often by several groups
    const Mesh& m = queries.front().mesh;
    EXPECT_THROW((void)collider.first_colliding_faces(m, std::vector<int>(m.faces.size() + 1, 0)), InvalidInput);
}

TEST(ElementCollider, HugeElementAndTouching) {
    ElementCollider collider;
    const int small = collider.add(sh::cuboid(V(0, 0, 0), V(1, 1, 1)));  // fixes the cell size at 1
    const int huge = collider.add(sh::cuboid(V(-100, -100, -100), V(100, 100, 5)));
    const int far = collider.add(sh::cuboid(V(50, 50, 50), V(51, 51, 51)));
    EXPECT_EQ(collider.colliding(sh::cuboid(V(1, 0, 0), V(2, 1, 1))), (std::vector<int>{small}));    // touches small only
    EXPECT_EQ(collider.colliding(sh::cuboid(V(99, 0, 0), V(101, 1, 1))), (std::vector<int>{huge}));  // crosses huge's side
    EXPECT_EQ(collider.colliding(sh::cuboid(V(50.5, 50.5, 50.5), V(52, 52, 52))), (std::vector<int>{far}));
    EXPECT_TRUE(collider.colliding(sh::cuboid(V(up(1.0), 2, 2), V(3, 3, 3))).empty());  // inside huge, no contact
    EXPECT_EQ(collider.box(small).max, V(1, 1, 1));
    EXPECT_TRUE(collider.box(42).empty());
    collider.remove(huge);
    EXPECT_TRUE(collider.colliding(sh::cuboid(V(99, 0, 0), V(101, 1, 1))).empty());
    EXPECT_EQ(collider.add(Mesh{}), 3);  // empty elements are accepted and never collide
    EXPECT_TRUE(collider.colliding(Mesh{}).empty());
    Mesh bad = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    bad.faces[0][0] = 99;
    EXPECT_THROW((void)collider.add(bad), InvalidInput);
    EXPECT_THROW((void)collider.colliding(bad), InvalidInput);
}

TEST(ElementCollider, LinkedRingsDoNotCollide) {
    // The chain-mail case: rings whose boxes overlap heavily but whose surfaces stay apart.
    ElementCollider collider;
    const int a = collider.add(sh::torus(1.0, 0.2, 48, 16));
    const Mesh linked = sh::torus(1.0, 0.2, 48, 16, V(1, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
    EXPECT_TRUE(collider.colliding(linked).empty());
    const Mesh too_close = sh::torus(1.0, 0.2, 48, 16, V(0.3, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
    EXPECT_EQ(collider.colliding(too_close), (std::vector<int>{a}));
}

}  // namespace
}  // namespace meshquilt
