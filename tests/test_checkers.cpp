// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// The shared checkers (tests/support/checkers.h) must pass on good meshes and fail, naming the
// culprit, on broken ones; linking numbers must be exact integers on known links.

#include "support/checkers.h"
#include "support/shapes_isect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace meshquilt::test {
namespace {

namespace sh = isect;
/// Passes if `text` contains `part`; prints both otherwise.
::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

Vec3 V(double x, double y, double z) { return {x, y, z}; }

double signed_volume(const Mesh& m) {
    double v = 0.0;
    for (const Tri& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
    return v;
}

Mesh hopf_partner(double major, double minor, int nu = 32, int nv = 12) {
    return sh::torus(major, minor, nu, nv, V(major, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
}

// ---------------------------------------------------------------------------------------------
// The generators themselves

TEST(ShapesIsect, AreClosedOutwardManifolds) {
    const Mesh t = sh::torus(1.0, 0.25, 48, 16);
    EXPECT_TRUE(is_closed_manifold(t));
    EXPECT_EQ(t.faces.size(), 2U * 48 * 16);
    EXPECT_NEAR(signed_volume(t), 2.0 * M_PI * M_PI * 1.0 * 0.25 * 0.25, 0.03 * signed_volume(t));
    const Mesh s = sh::icosphere(2.0, 3, V(1, 2, 3));
    EXPECT_TRUE(is_closed_manifold(s));
    EXPECT_NEAR(signed_volume(s), 4.0 / 3.0 * M_PI * 8.0, 0.02 * 4.0 / 3.0 * M_PI * 8.0);
    const Mesh c = sh::cuboid(V(0, 0, 0), V(1, 2, 3));
    EXPECT_TRUE(is_closed_manifold(c));
    EXPECT_NEAR(signed_volume(c), 6.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// is_closed_manifold

TEST(CheckerIsClosedManifold, FailsOnEmptyAndBadIndices) {
    EXPECT_FALSE(is_closed_manifold(Mesh{}));
    Mesh m = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    m.faces[5][2] = 8;
    const auto r = is_closed_manifold(m);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "face 5"));
    EXPECT_TRUE(contains(r.message(), "out of range"));
}

TEST(CheckerIsClosedManifold, FailsOnARemovedFace) {
    Mesh m = sh::torus(1.0, 0.25);
    m.faces.erase(m.faces.begin() + 17);
    const auto r = is_closed_manifold(m);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "3 boundary edges"));
}

TEST(CheckerIsClosedManifold, FailsOnAFlippedFace) {
    Mesh m = sh::torus(1.0, 0.25);
    std::swap(m.faces[40][0], m.faces[40][1]);
    const auto r = is_closed_manifold(m);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "3 inconsistently oriented edges"));
    EXPECT_TRUE(contains(r.message(), "faces"));
}

TEST(CheckerIsClosedManifold, FailsOnANonManifoldEdge) {
    // A closed cube plus a closed tetrahedron-like fin glued along one cube edge: every edge has
    // an even number of faces, but the cube edge 0-1 has four.
    Mesh m = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    const int a = static_cast<int>(m.vertices.size());
    m.vertices.push_back(V(0.5, -1, -1));
    m.vertices.push_back(V(0.5, -1.5, -0.5));
    m.faces.emplace_back(0, 1, a);
    m.faces.emplace_back(1, 0, a + 1);
    m.faces.emplace_back(a, 1, a + 1);
    m.faces.emplace_back(0, a, a + 1);
    const auto r = is_closed_manifold(m);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "1 non-manifold edges"));
    EXPECT_TRUE(contains(r.message(), "between vertices 0 and 1, 4 faces"));
}

TEST(CheckerIsClosedManifold, FailsOnAPinchedVertex) {
    // Two cubes sharing only vertex 7 (the corner (1,1,1)): every edge is fine, the vertex is not.
    Mesh m = sh::cuboid(V(0, 0, 0), V(1, 1, 1));
    const Mesh b = sh::cuboid(V(1, 1, 1), V(2, 2, 2));
    const int off = static_cast<int>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (Tri f : b.faces) {
        for (int k = 0; k < 3; ++k) f[k] = f[k] == 0 ? 7 : f[k] + off;  // b's corner 0 is (1,1,1)
        m.faces.push_back(f);
    }
    const auto r = is_closed_manifold(m);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "vertex 7 has 2 separate fans"));
}

TEST(CheckerIsClosedManifold, FailsOnDegenerateFaces) {
    Mesh tet;
    tet.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)};
    tet.faces = {Tri(0, 2, 1), Tri(0, 1, 3), Tri(1, 2, 3), Tri(0, 3, 2)};
    EXPECT_TRUE(is_closed_manifold(tet));
    Mesh flat = tet;
    flat.vertices[3] = V(2, 0, 0);  // collinear with vertices 0 and 1
    const auto r = is_closed_manifold(flat);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "face 1"));
    EXPECT_TRUE(contains(r.message(), "degenerate"));
    Mesh repeated = tet;
    repeated.faces[2] = Tri(1, 1, 3);
    EXPECT_TRUE(contains(is_closed_manifold(repeated).message(), "repeats a vertex index"));
}

// ---------------------------------------------------------------------------------------------
// elements_closed, no_element_intersections, split_elements

sh::Combined three_tori() {
    return sh::combine({sh::torus(1.0, 0.25), sh::torus(1.0, 0.25, 32, 12, V(3, 0, 0)), sh::torus(1.0, 0.25, 32, 12, V(6, 0, 0))});
}

TEST(CheckerElementsClosed, PassesOnClosedElements) {
    const auto c = three_tori();
    EXPECT_TRUE(elements_closed(c.mesh, c.element_of_face));
    // A non-contiguous labelling is fine too.
    auto ids = c.element_of_face;
    for (int& e : ids) e = 10 * e + 4;
    EXPECT_TRUE(elements_closed(c.mesh, ids));
}

TEST(CheckerElementsClosed, NamesTheBadElementAndItsCounts) {
    auto c = three_tori();
    const std::size_t f = c.mesh.faces.size() - 5;  // in element 2
    c.mesh.faces.erase(c.mesh.faces.begin() + static_cast<long>(f));
    c.element_of_face.erase(c.element_of_face.begin() + static_cast<long>(f));
    auto r = elements_closed(c.mesh, c.element_of_face);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "1 of 3 elements not closed; first: element 2: 3 boundary edges"));

    c = three_tori();
    std::swap(c.mesh.faces[1000][1], c.mesh.faces[1000][2]);  // element 1 (faces 768..1535)
    r = elements_closed(c.mesh, c.element_of_face);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "element 1: 0 boundary edges, 0 non-manifold edges, 3 inconsistently"));

    // Relabelling one face of element 0 as element 1 opens both.
    c = three_tori();
    c.element_of_face[3] = 1;
    r = elements_closed(c.mesh, c.element_of_face);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "2 of 3 elements not closed; first: element 0: 3 boundary edges"));

    EXPECT_FALSE(elements_closed(c.mesh, std::vector<int>(3, 0)));
}

TEST(CheckerElementsClosed, NonManifoldEdgeInsideAnElement) {
    auto c = three_tori();
    c.mesh.faces.push_back(c.mesh.faces[0]);  // the same face twice in element 0
    c.element_of_face.push_back(0);
    const auto r = elements_closed(c.mesh, c.element_of_face);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "element 0: 0 boundary edges, 3 non-manifold edges"));
}

TEST(CheckerNoElementIntersections, PassesFailsAndAllows) {
    const auto ok = three_tori();
    EXPECT_TRUE(no_element_intersections(ok.mesh, ok.element_of_face));
    const auto bad = sh::combine({sh::torus(1.0, 0.25), sh::torus(1.0, 0.25, 32, 12, V(9, 0, 0)),
                                  sh::torus(1.0, 0.25, 32, 12, V(0.4, 0.3, 0.0))});
    const auto r = no_element_intersections(bad.mesh, bad.element_of_face);
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "1 intersecting element pairs: (0, 2)"));
    EXPECT_TRUE(no_element_intersections(bad.mesh, bad.element_of_face, {{2, 0}}));
    EXPECT_FALSE(no_element_intersections(bad.mesh, std::vector<int>(2, 0)));  // wrong size: fails, no crash
}

TEST(CheckerNoSelfIntersections, PassesAndFails) {
    EXPECT_TRUE(no_self_intersections(sh::torus(1.0, 0.25)));
    const auto r = no_self_intersections(sh::torus(0.5, 1.0));  // spindle torus
    EXPECT_FALSE(r);
    EXPECT_TRUE(contains(r.message(), "pairs of faces intersect"));
}

TEST(CheckerSplitElements, RoundTrip) {
    const auto c = three_tori();
    const auto parts = split_elements(c.mesh, c.element_of_face);
    ASSERT_EQ(parts.size(), 3U);
    for (const Mesh& p : parts) {
        EXPECT_EQ(p.vertices.size(), 32U * 12);
        EXPECT_EQ(p.faces.size(), 2U * 32 * 12);
        EXPECT_TRUE(is_closed_manifold(p));
    }
    EXPECT_EQ(parts[1].vertices[0], c.mesh.vertices[32 * 12]);
    auto ids = c.element_of_face;
    for (int& e : ids) e = e == 1 ? 4 : e;
    const auto sparse = split_elements(c.mesh, ids);
    ASSERT_EQ(sparse.size(), 5U);
    EXPECT_TRUE(sparse[1].empty());
    EXPECT_EQ(sparse[4].faces.size(), 2U * 32 * 12);
}

// ---------------------------------------------------------------------------------------------
// Linking numbers

std::vector<Vec3> circle(const Vec3& c, const Vec3& u, const Vec3& v, int n = 64) {
    std::vector<Vec3> pts;
    for (int k = 0; k < n; ++k) {
        const double t = 2.0 * M_PI * k / n;
        pts.push_back(c + std::cos(t) * u + std::sin(t) * v);
    }
    return pts;
}

double distance_to_integer(double x) { return std::abs(x - std::round(x)); }

TEST(CheckerLinkingNumber, ExactOnPolygons) {
    const auto a = circle(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
    const auto hopf = circle(V(1, 0, 0), V(1, 0, 0), V(0, 0, 1), 37);
    const double lk = linking_number(a, hopf);
    EXPECT_NEAR(std::abs(lk), 1.0, 1e-9);
    EXPECT_NEAR(linking_number(hopf, a), lk, 1e-9);  // symmetric
    std::vector<Vec3> reversed(hopf.rbegin(), hopf.rend());
    EXPECT_NEAR(linking_number(a, reversed), -lk, 1e-9);  // orientation flips the sign

    // Unlinked: apart, side by side in one plane, and a ring that passes near but not through.
    EXPECT_NEAR(linking_number(a, circle(V(5, 0, 0), V(1, 0, 0), V(0, 0, 1))), 0.0, 1e-9);
    EXPECT_NEAR(linking_number(a, circle(V(2.5, 0, 0), V(1, 0, 0), V(0, 1, 0))), 0.0, 1e-9);
    EXPECT_NEAR(linking_number(a, circle(V(2.1, 0, 0), V(1, 0, 0), V(0, 0, 1))), 0.0, 1e-9);

    // A curve winding twice around a's core while going once along it: |Lk| = 2.
    std::vector<Vec3> twice;
    for (int k = 0; k < 200; ++k) {
        const double t = 2.0 * M_PI * k / 200;
        const double rho = 1.0 + 0.3 * std::cos(2 * t);
        twice.push_back(V(rho * std::cos(t), rho * std::sin(t), 0.3 * std::sin(2 * t)));
    }
    EXPECT_NEAR(std::abs(linking_number(a, twice)), 2.0, 1e-9);
    EXPECT_THROW((void)linking_number({V(0, 0, 0), V(1, 0, 0)}, a), std::invalid_argument);
}

TEST(CheckerLinkingNumber, CrossingCountIsTheRoundedGaussIntegral) {
    // The fixed cases of ExactOnPolygons, sign included.
    const auto a = circle(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
    const auto hopf = circle(V(1, 0, 0), V(1, 0, 0), V(0, 0, 1), 37);
    const std::vector<Vec3> reversed(hopf.rbegin(), hopf.rend());
    for (const auto& b : {hopf, reversed, circle(V(5, 0, 0), V(1, 0, 0), V(0, 0, 1)), circle(V(2.5, 0, 0), V(1, 0, 0), V(0, 1, 0)),
                          circle(V(2.1, 0, 0), V(1, 0, 0), V(0, 0, 1))}) {
        EXPECT_EQ(crossing_linking_number(a, b), std::lround(linking_number(a, b)));
        EXPECT_EQ(crossing_linking_number(b, a), std::lround(linking_number(b, a)));
    }
    EXPECT_EQ(std::abs(crossing_linking_number(a, hopf)), 1);
    EXPECT_EQ(crossing_linking_number(a, reversed), -crossing_linking_number(a, hopf));
    std::vector<Vec3> twice;
    for (int k = 0; k < 200; ++k) {
        const double t = 2.0 * M_PI * k / 200;
        const double rho = 1.0 + 0.3 * std::cos(2 * t);
        twice.push_back(V(rho * std::cos(t), rho * std::sin(t), 0.3 * std::sin(2 * t)));
    }
    EXPECT_EQ(std::abs(crossing_linking_number(a, twice)), 2);
    EXPECT_THROW((void)crossing_linking_number({V(0, 0, 0), V(1, 0, 0)}, a), std::invalid_argument);

    // Axis-aligned rings, whose rows of vertices line up with each other (a modelled chain).
    const Mesh r0 = sh::torus(1.0, 0.2);
    const Mesh r1 = sh::torus(1.0, 0.2, 32, 12, V(1.3, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
    const Mesh r2 = sh::torus(1.0, 0.2, 32, 12, V(2.6, 0, 0));
    EXPECT_TRUE(links_once(ring_centerline(r0), ring_centerline(r1)));
    EXPECT_TRUE(links_once(ring_centerline(r1), ring_centerline(r2)));
    EXPECT_FALSE(links_once(ring_centerline(r0), ring_centerline(r2)));

    // Random pairs of bumpy closed curves near each other, linked or not, with any number of
    // vertices: wherever the Gauss integral is clearly an integer (the curves keep apart), the
    // count agrees with it.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto bumpy = [&](int n) {
        const Vec3 c(0.8 * unit(rng), 0.8 * unit(rng), 0.8 * unit(rng));
        const Vec3 u = V(unit(rng), unit(rng), unit(rng)).normalized();
        const Vec3 v = u.cross(V(unit(rng), unit(rng), unit(rng))).normalized();
        const double r = 1.0 + 0.3 * unit(rng), wobble = 0.3 * unit(rng), phase = M_PI * unit(rng);
        std::vector<Vec3> pts;
        for (int k = 0; k < n; ++k) {
            const double t = 2.0 * M_PI * k / n;
            pts.push_back(c + r * (std::cos(t) * u + std::sin(t) * v) + wobble * std::sin(3 * t + phase) * u.cross(v));
        }
        return pts;
    };
    int compared = 0, linked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const auto p = bumpy(3 + trial % 60), q = bumpy(3 + (7 * trial) % 50);
        const double lk = linking_number(p, q);
        if (distance_to_integer(lk) > 1e-3) continue;
        ++compared;
        linked += std::lround(lk) != 0;
        ASSERT_EQ(crossing_linking_number(p, q), std::lround(lk)) << "trial " << trial;
        ASSERT_EQ(links_once(p, q), std::abs(std::lround(lk)) == 1) << "trial " << trial;
    }
    EXPECT_GT(compared, 1900);
    EXPECT_GT(linked, 200);
}

TEST(CheckerLinkingNumber, CrossingCountWhereShadowsMeetAtVertices) {
    // A Hopf link whose second ring has its vertices near the first ring's shadow moved onto the
    // line through a vertex of the first along the shadow direction: the shadows meet at vertices,
    // which no orientation can call, yet the rings keep apart and the count is still the link.
    const Vec3 d = shadow_direction();
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    const auto a = circle(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
    auto b = circle(V(1, 0, 0), V(1, 0, 0), V(0, 0, 1), 37);
    int snapped = 0;
    for (Vec3& q : b)
        for (const Vec3& p : a) {
            const Vec3 off = q - p;
            const Vec3 across = off - off.dot(d) * d;
            if (across.norm() < 0.1 && std::abs(off.dot(d)) > 0.2) {
                q = p + off.dot(d) * d;
                ++snapped;
                break;
            }
        }
    ASSERT_GT(snapped, 0);
    const double lk = linking_number(a, b);
    ASSERT_LT(distance_to_integer(lk), 1e-6);
    EXPECT_EQ(std::abs(std::lround(lk)), 1);
    EXPECT_EQ(crossing_linking_number(a, b), std::lround(lk));
    EXPECT_EQ(crossing_linking_number(b, a), std::lround(linking_number(b, a)));
    EXPECT_TRUE(links_once(a, b));
}

TEST(CheckerLinkingNumber, HopfLinkOfToriIsOne) {
    const Mesh a = sh::torus(1.0, 0.25);
    const Mesh b = hopf_partner(1.0, 0.25);
    const double lk = linking_number(ring_centerline(a), ring_centerline(b));
    EXPECT_LT(distance_to_integer(lk), 1e-6);
    EXPECT_EQ(std::abs(rounded_linking(a, b)), 1);
    EXPECT_EQ(rounded_linking(a, sh::torus(1.0, 0.25, 32, 12, V(3, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2))), 0);
    // The centre line of a torus is its core circle.
    for (const Vec3& p : ring_centerline(a)) {
        EXPECT_NEAR(std::hypot(p.x(), p.y()), 1.0, 0.01);
        EXPECT_NEAR(p.z(), 0.0, 1e-9);
    }
}

TEST(CheckerLinkingNumber, ThreeRingChain) {
    const Mesh a = sh::torus(1.0, 0.2);
    const Mesh b = sh::torus(1.0, 0.2, 32, 12, V(1.3, 0, 0), sh::rotation(V(1, 0, 0), M_PI / 2));
    const Mesh c = sh::torus(1.0, 0.2, 32, 12, V(2.6, 0, 0), sh::rotation(V(0, 0, 1), 0.4));
    EXPECT_EQ(std::abs(rounded_linking(a, b)), 1);
    EXPECT_EQ(std::abs(rounded_linking(b, c)), 1);
    EXPECT_EQ(rounded_linking(a, c), 0);
    const auto chain = sh::combine({a, b, c});
    EXPECT_TRUE(no_element_intersections(chain.mesh, chain.element_of_face));  // linked, never touching
    EXPECT_TRUE(elements_closed(chain.mesh, chain.element_of_face));
}

TEST(CheckerLinkingNumber, BentAndTiltedRings) {
    // Bend ring a (z += 0.2 x^2), tilt and squash ring b: still a Hopf link.
    Mesh a = sh::torus(1.0, 0.2, 48, 12);
    for (Vec3& p : a.vertices) p.z() += 0.2 * p.x() * p.x();
    Mesh b = hopf_partner(1.0, 0.2, 40, 10);
    for (Vec3& p : b.vertices) p = V(1, 0, 0) + sh::rotation(V(0, 0, 1), 0.3) * Vec3(0.8 * (p.x() - 1), p.y(), p.z());
    const double lk = linking_number(ring_centerline(a), ring_centerline(b));
    EXPECT_LT(distance_to_integer(lk), 1e-6);
    EXPECT_EQ(std::abs(rounded_linking(a, b)), 1);
    // Fewer bins than ring segments still gives a good centre line.
    EXPECT_EQ(std::abs(static_cast<int>(std::lround(linking_number(ring_centerline(a, 12), ring_centerline(b, 12))))), 1);
}

}  // namespace
}  // namespace meshquilt::test
