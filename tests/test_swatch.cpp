// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// The swatch as the synthesis sees it (quilt/swatch.h): elements, their genus, the gaps between them.

#include "core/intersect.h"
#include "meshquilt/analysis.h"
#include "meshquilt/io.h"
#include "meshquilt/quilt.h"
#include "quilt/kernel.h"
#include "quilt/swatch.h"
#include "support/checkers.h"
#include "support/paths.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <vector>

namespace mq = meshquilt;
using meshquilt::test::swatch_path;
using mq::Mesh;
using mq::Vec3;
namespace shapes = mq::test::shapes;

// What nudging needs from the swatch: each element's genus (rings interlock, blobs do not) and the
// small gap the swatch leaves between neighbours (5th percentile), which a nudged blob must keep.
TEST(SwatchData, KnowsRingsAndGaps) {
    const auto rings = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path("chainmail")));
    ASSERT_FALSE(rings.elements.empty());
    for (int g : rings.element_genus) EXPECT_EQ(g, 1);
    const auto pebbles = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path("pebbles")));
    ASSERT_EQ(pebbles.element_genus.size(), pebbles.elements.size());
    for (int g : pebbles.element_genus) EXPECT_EQ(g, 0);
    // Two unit cubes 0.3 apart (and a third farther): every nearest gap is 0.3.
    Mesh two = shapes::concat(shapes::cube(1.0), shapes::translated(shapes::cube(1.0), Vec3(1.3, 0.0, 0.0)));
    two = shapes::concat(two, shapes::translated(shapes::cube(1.0), Vec3(2.6, 0.0, 0.0)));
    for (Vec3& v : two.vertices) v.z() *= 0.2;  // a slab
    const auto cubes = mq::quilt::prepare_swatch(two);
    ASSERT_EQ(cubes.elements.size(), 3u);
    EXPECT_NEAR(cubes.near_gap, 0.3, 1e-9);
    EXPECT_EQ(cubes.element_genus, std::vector<int>(3, 0));
    // Touching or intersecting elements leave no gap to keep.
    Mesh overlapping = shapes::translated(shapes::cube(1.0), Vec3(0.5, 0.0, 0.0));
    for (Vec3& v : overlapping.vertices) v.z() *= 0.2;
    const auto touching = mq::quilt::prepare_swatch(shapes::concat(two, overlapping));
    EXPECT_EQ(touching.near_gap, 0.0);
}

namespace {

/// A closed prism `h` high over a star-shaped polygon (counter-clockwise), caps fanned from its centroid.
Mesh prism(const std::vector<mq::Vec2>& polygon, double h) {
    Mesh m;
    const int n = static_cast<int>(polygon.size());
    mq::Vec2 c = mq::Vec2::Zero();
    for (const mq::Vec2& p : polygon) c += p / n;
    for (const mq::Vec2& p : polygon) m.vertices.emplace_back(p.x(), p.y(), 0.0);
    for (const mq::Vec2& p : polygon) m.vertices.emplace_back(p.x(), p.y(), h);
    m.vertices.emplace_back(c.x(), c.y(), 0.0);
    m.vertices.emplace_back(c.x(), c.y(), h);
    for (int k = 0; k < n; ++k) {
        const int k1 = (k + 1) % n;
        m.faces.push_back({k, k1, n + k1});
        m.faces.push_back({k, n + k1, n + k});
        m.faces.push_back({2 * n, k1, k});
        m.faces.push_back({2 * n + 1, n + k, n + k1});
    }
    return m;
}

/// A strand bent round a circular arc: radius `r` (its centre line), `w` wide, `h` high, through
/// `angle` radians in `n` steps.
Mesh arc_strand(double r, double w, double h, double angle, int n) {
    Mesh m;
    for (int k = 0; k <= n; ++k) {
        const double a = angle * k / n;
        for (const double rr : {r - 0.5 * w, r + 0.5 * w})
            for (const double z : {0.0, h}) m.vertices.emplace_back(rr * std::cos(a), rr * std::sin(a), z);
    }
    // Vertex 4k + {0: inner bottom, 1: inner top, 2: outer bottom, 3: outer top}.
    auto quad = [&m](int a, int b, int c, int d) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
    };
    for (int k = 0; k < n; ++k) {
        const int i = 4 * k, j = 4 * (k + 1);
        quad(i + 1, i + 3, j + 3, j + 1);  // top
        quad(i + 0, j + 0, j + 2, i + 2);  // bottom
        quad(i + 2, j + 2, j + 3, i + 3);  // outer wall
        quad(i + 0, i + 1, j + 1, j + 0);  // inner wall
    }
    quad(0, 2, 3, 1);  // first end
    const int e = 4 * n;
    quad(e + 0, e + 1, e + 3, e + 2);  // last end
    return m;
}

}  // namespace

// Strands (quilt::is_strand): closed genus-0 elements whose footprint is several times longer than
// wide but which are no threads (bent: knot work, a winding cord). They are never squeezed or shrunk
// to fit. slenderness is the footprint's area over the square of the widest disc inside it.
TEST(SwatchData, KnowsStrands) {
    std::vector<mq::Vec2> circle, square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 64; ++k) circle.emplace_back(std::cos(2 * M_PI * k / 64), std::sin(2 * M_PI * k / 64));
    EXPECT_NEAR(mq::quilt::slenderness(prism(circle, 0.3)), M_PI / 4, 0.06);
    EXPECT_NEAR(mq::quilt::slenderness(prism(square, 0.3)), 1.0, 0.08);
    // A half ring 2 pi long and 0.4 wide: 15.7, less on the raster (6 pixels across the strand).
    const Mesh half_ring = arc_strand(2.0, 0.4, 0.2, M_PI, 24);
    ASSERT_TRUE(mq::quilt::is_closed_oriented(half_ring));
    EXPECT_NEAR(mq::quilt::slenderness(half_ring), 2 * M_PI / 0.4, 0.2 * 2 * M_PI / 0.4);
    EXPECT_TRUE(mq::quilt::is_strand(half_ring));
    // A quarter ring 2 wide at radius 3 (4.7 long): 2.4, a blob; 1.5 wide (6.3 long): a strand.
    EXPECT_FALSE(mq::quilt::is_strand(arc_strand(3.0, 2.0, 0.3, 0.5 * M_PI, 24)));
    EXPECT_TRUE(mq::quilt::is_strand(arc_strand(4.0, 1.5, 0.3, 0.5 * M_PI, 24)));
    EXPECT_FALSE(mq::quilt::is_strand(prism(circle, 0.3)));
    // A straight bar is a thread (quilt::is_elongated), not a strand; a ring is neither.
    Mesh bar = shapes::cube(1.0);
    for (Vec3& v : bar.vertices) v = Vec3(6.0 * v.x(), 0.4 * v.y(), 0.2 * v.z());
    EXPECT_FALSE(mq::quilt::is_strand(bar));
    EXPECT_FALSE(mq::quilt::is_strand(shapes::torus(2.0, 0.2)));
    // The bundled swatches: only the knots hold strands, so nothing changes for the others.
    for (const char* name : {"weave", "chainmail", "pebbles", "rivets", "cobbles", "scales"}) {
        const auto s = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path(name)));
        ASSERT_EQ(s.element_strand.size(), s.elements.size()) << name;
        EXPECT_EQ(std::count(s.element_strand.begin(), s.element_strand.end(), 1), 0) << name;
    }
    const auto knots = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path("knots")));
    const auto strands = std::count(knots.element_strand.begin(), knots.element_strand.end(), 1);
    EXPECT_GE(10 * strands, 8 * static_cast<long>(knots.elements.size())) << strands << " of " << knots.elements.size();
}

// Layered swatches (quilt::SwatchData::layered): elements that overlap in projection and keep apart
// in 3D only, as overlapping scales do. Only the scales are layered among the bundled swatches; the
// chain mail's rings overlap in projection too, but they are rings, not blobs.
TEST(SwatchData, KnowsLayeredSwatches) {
    for (const char* name : {"weave", "chainmail", "pebbles", "rivets", "cobbles"})
        EXPECT_FALSE(mq::quilt::prepare_swatch(mq::read_mesh(swatch_path(name))).layered) << name;
    const auto scales = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path("scales")));
    EXPECT_TRUE(scales.elements_disjoint);
    EXPECT_TRUE(scales.layered);
    // Two flat plates, the second lifted over the first's far half: layered; side by side: not.
    Mesh plate = shapes::cube(1.0);
    for (Vec3& v : plate.vertices) v.z() *= 0.1;
    const Mesh over = shapes::translated(plate, Vec3(0.5, 0.0, 0.3));
    EXPECT_TRUE(mq::quilt::prepare_swatch(shapes::concat(plate, over)).layered);
    const Mesh beside = shapes::translated(plate, Vec3(1.2, 0.0, 0.0));
    EXPECT_FALSE(mq::quilt::prepare_swatch(shapes::concat(plate, beside)).layered);
    EXPECT_NEAR(mq::quilt::projected_overlap_share(plate, over), 0.5, 0.05);
    EXPECT_EQ(mq::quilt::projected_overlap_share(plate, beside), 0.0);
}

// A swatch that is one connected net (a grid of bars) is known by its largest element covering
// most of the swatch's footprint; the bundled swatches' elements (rings, threads, blobs, scales)
// cover at most a thread's share.
TEST(SwatchData, KnowsANetSpansTheSwatch) {
    for (const char* name : {"weave", "chainmail", "pebbles", "rivets", "cobbles", "scales"}) {
        const auto sw = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path(name)));
        EXPECT_GT(sw.largest_element_cover, 0.0) << name;
        EXPECT_FALSE(sw.spans_swatch()) << name << ": its largest element covers " << sw.largest_element_cover;
    }
    const auto net = mq::quilt::prepare_swatch(shapes::grid_net(8, 1.25, 0.25, 0.3, 0.125));
    ASSERT_EQ(net.elements.size(), 1u);
    EXPECT_NEAR(net.largest_element_cover, 1.0, 1e-9);
    EXPECT_TRUE(net.spans_swatch());
}

// Threads modelled as open sheets (a ribbon weave) are quilted as closed strips: an open element
// is never stitched, so ribbons stayed as short as a patch's piece of them (planar: 0.75 of the
// density, on the eight at scale 0.2: 0.47-0.57). Open elements that are no threads (caps,
// leaves) and closed threads are left as they are.
TEST(SwatchData, MakesOpenThreadsClosedStrips) {
    const Mesh ribbons = shapes::ribbon_weave(4, 1.25, 0.9, 0.2, 40);
    const auto sw = mq::quilt::prepare_swatch(ribbons);
    ASSERT_EQ(sw.elements.size(), 8u);
    EXPECT_EQ(sw.solidified, 8);
    EXPECT_NEAR(sw.solidify_thickness, mq::quilt::SwatchData::kSolidifyShare * 0.9, 0.01 * 0.9);
    EXPECT_NE(sw.solidify_warning().find("8 threads are open sheets"), std::string::npos) << sw.solidify_warning();
    for (std::size_t e = 0; e < sw.elements.size(); ++e) {
        SCOPED_TRACE(e);
        const Mesh& m = sw.elements[e];
        EXPECT_TRUE(sw.element_closed[e]);
        EXPECT_TRUE(mq::quilt::is_closed_oriented(m));
        EXPECT_EQ(sw.element_genus[e], 0);
        EXPECT_TRUE(mq::quilt::is_elongated(m));
        EXPECT_EQ(mq::count_self_intersections(m), 0);
        // Both sides of the sheet (0.9 x 5, a little more where it rises and falls) and a rim of
        // the strip's thickness.
        const double area = mq::quilt::mesh_area(m);
        EXPECT_GT(area, 2.0 * 0.9 * 5.0);
        EXPECT_LT(area, 2.0 * 0.9 * 5.0 * 1.1 + 2.0 * 5.9 * sw.solidify_thickness);
        // Its middle is where the sheet was: the strip lies within half its thickness of it.
        double lo = 1e9, hi = -1e9;
        for (const Vec3& v : m.vertices) {
            lo = std::min(lo, v.z());
            hi = std::max(hi, v.z());
        }
        EXPECT_NEAR(hi - lo, 0.4 + sw.solidify_thickness, 0.01);
    }
    EXPECT_TRUE(sw.elements_disjoint);
    EXPECT_EQ(sw.intersecting_pairs, 0);
    EXPECT_NEAR(sw.box.size().x(), 5.0, 0.05);
    EXPECT_NEAR(sw.box.size().y(), 5.0, 0.05);

    // Not threads: the open caps stay open.
    const auto caps = mq::quilt::prepare_swatch(mq::read_mesh(std::string(MQ_TEST_DATA_DIR) + "/planar/open_caps.obj"));
    EXPECT_EQ(caps.solidified, 0);
    EXPECT_TRUE(caps.solidify_warning().empty());
    EXPECT_TRUE(std::none_of(caps.element_closed.begin(), caps.element_closed.end(), [](char c) { return c != 0; }));
    // Closed threads are threads already.
    const Mesh weave = mq::read_mesh(swatch_path("weave"));
    const auto closed = mq::quilt::prepare_swatch(weave);
    EXPECT_EQ(closed.solidified, 0);
    EXPECT_EQ(closed.mesh.faces.size(), weave.faces.size());
}

namespace {
Mesh turned(Mesh m, double degrees) {
    const double c = std::cos(degrees * M_PI / 180.0), s = std::sin(degrees * M_PI / 180.0);
    for (Vec3& v : m.vertices) v = Vec3(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
    return m;
}
}  // namespace

// A weave turned in its plane has no thread whose xy box is long, so none would be known as a
// thread (quilt::is_elongated): the swatch is turned back so that its threads run along x and y
// (planar quilting of the bundled weave turned by 30 degrees: 0.46 of the density before, 0.91
// after). Swatches whose threads run along their axes, and threads that run diagonally across a
// swatch cut square around them, are left as they are.
TEST(SwatchData, TurnsAWeaveWhoseThreadsRunAtAnAngle) {
    const Mesh weave = mq::read_mesh(swatch_path("weave"));
    const auto straight = mq::quilt::prepare_swatch(weave);
    EXPECT_EQ(straight.turn, 0.0);
    EXPECT_TRUE(straight.turn_warning().empty());
    for (double degrees : {30.0, -20.0, 60.0}) {
        SCOPED_TRACE(degrees);
        const auto sw = mq::quilt::prepare_swatch(turned(weave, degrees));
        // Turned back modulo 90 degrees (60 comes back as -30 more: the threads run along y and x).
        const double back = degrees > 45.0 ? 90.0 - degrees : -degrees;
        EXPECT_NEAR(sw.turn * 180.0 / M_PI, back, 0.5);
        EXPECT_NE(sw.turn_warning().find("it was turned in its plane"), std::string::npos);
        ASSERT_EQ(sw.elements.size(), 14u);
        for (const Mesh& e : sw.elements) EXPECT_TRUE(mq::quilt::is_elongated(e));
        EXPECT_NEAR(sw.box.size().x() * sw.box.size().y(), straight.box.size().x() * straight.box.size().y(),
                    0.02 * straight.box.size().x() * straight.box.size().y());
        EXPECT_NEAR(sw.box.min.x(), 0.0, 1e-12);
        EXPECT_NEAR(sw.box.min.y(), 0.0, 1e-12);
    }
    for (const char* name : {"chainmail", "pebbles", "rivets", "cobbles", "scales"})
        EXPECT_EQ(mq::quilt::prepare_swatch(mq::read_mesh(swatch_path(name))).turn, 0.0) << name;
    // Planar quilting says so, and its threads come out along x and y: stitched across the
    // placements, the longest run more than a swatch along one axis.
    mq::PlanarQuiltOptions po;
    po.width = 16.0;
    po.height = 16.0;
    const mq::QuiltResult q = mq::quilt_plane(turned(weave, 30.0), po);
    EXPECT_TRUE(std::any_of(q.warnings.begin(), q.warnings.end(), [](const std::string& w) {
        return w.find("threads run at 30 degrees") != std::string::npos;
    }));
    double longest = 0.0;
    for (const Mesh& e : mq::test::split_elements(q.mesh, q.element_of_face)) {
        const Vec3 d = mq::bounding_box(e).size();
        longest = std::max({longest, d.x(), d.y()});
        EXPECT_TRUE(mq::quilt::is_elongated(e));
    }
    EXPECT_GT(longest, 11.0);
    // Five bars along the diagonal of a 10 x 10 square, cut to it: threads at 45 degrees, but turned
    // the square's box would grow (to about 14 x 13), so they stay.
    Mesh bars;
    for (double d : {-6.0, -3.0, 0.0, 3.0, 6.0}) {
        const double length = 2.0 * (5.0 * std::sqrt(2.0) - std::fabs(d)) - 0.4;
        Mesh bar = shapes::cube(1.0);
        for (Vec3& v : bar.vertices) v = Vec3((v.x() - 0.5) * length, (v.y() - 0.5) * 0.5, v.z() * 0.3);
        bar = turned(bar, 45.0);
        bars = shapes::concat(bars, shapes::translated(bar, Vec3(5.0 - d / std::sqrt(2.0), 5.0 + d / std::sqrt(2.0), 0.0)));
    }
    const auto diagonal = mq::quilt::prepare_swatch(bars);
    ASSERT_EQ(diagonal.elements.size(), 5u);
    EXPECT_EQ(diagonal.turn, 0.0);
}

// A swatch whose elements intersect is quilted thinned: moved inwards along the normals by twice
// the least that parts them, which thickening undoes.
TEST(SwatchData, ThinsIntersectingElementsApartAndThickensThemBack) {
    const Mesh thick = shapes::thickened(mq::read_mesh(swatch_path("chainmail")), 0.08);
    int n = 0;
    const std::vector<int> comp = mq::connected_components(thick, &n);
    const auto pairs = mq::intersecting_element_pairs(thick, comp);
    ASSERT_GE(pairs.size(), 36u) << "the thickened rings should meet the rings they link with";
    const auto sw = mq::quilt::prepare_swatch(thick);
    EXPECT_EQ(sw.intersecting_pairs, static_cast<int>(pairs.size()));
    // The bundled mail (0.08 thinner) is disjoint, so the least parting thinning is below 0.08.
    EXPECT_GT(sw.thinned, 0.0);
    EXPECT_LT(sw.thinned, 0.16);
    EXPECT_TRUE(sw.elements_disjoint);
    EXPECT_TRUE(mq::intersecting_element_pairs(sw.mesh, comp, 1).empty());
    EXPECT_EQ(mq::count_self_intersections(sw.mesh, 1), 0);
    ASSERT_EQ(sw.elements.size(), 36u);
    for (int g : sw.element_genus) EXPECT_EQ(g, 1);
    // The box (footprint and thickness) stays the input's.
    const mq::Box3 box = mq::bounding_box(thick);
    EXPECT_LT((sw.box.min - box.min).norm() + (sw.box.max - box.max).norm(), 1e-12);
    EXPECT_NE(sw.intersect_warning().find("thinned by"), std::string::npos) << sw.intersect_warning();
    // Thickened back, every vertex returns to where it was (vertex normals of a tube's offset are
    // nearly its own), and the wire is as thick as before: the volume comes back.
    Mesh back = sw.mesh;
    mq::quilt::thicken_elements(&back, comp, std::vector<double>(static_cast<std::size_t>(n), sw.thinned));
    ASSERT_EQ(back.vertices.size(), thick.vertices.size());
    double worst = 0.0;
    for (std::size_t v = 0; v < back.vertices.size(); ++v) worst = std::max(worst, (back.vertices[v] - thick.vertices[v]).norm());
    EXPECT_LT(worst, 0.05 * sw.thinned);
    auto volume = [](const Mesh& m) {
        double v = 0.0;
        for (const auto& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
        return v;
    };
    EXPECT_LT(volume(sw.mesh), 0.8 * volume(thick));
    EXPECT_NEAR(volume(back), volume(thick), 0.01 * volume(thick));

    EXPECT_FALSE(sw.tight);

    // A tight mail (the wire 0.04 thicker: rings 0.05 apart, the bundled mail's 0.15) is thinned to
    // kThinGap of a ring's xy diagonal: grown by less than half of that, the thinned rings still
    // miss each other; grown by a little more, they meet.
    const Mesh tight_mail = shapes::thickened(mq::read_mesh(swatch_path("chainmail")), 0.04);
    ASSERT_TRUE(mq::intersecting_element_pairs(tight_mail, comp, 1).empty());
    const auto tight = mq::quilt::prepare_swatch(tight_mail);
    EXPECT_TRUE(tight.tight);
    EXPECT_EQ(tight.intersecting_pairs, 0);
    EXPECT_GT(tight.thinned, 0.0);
    EXPECT_LT(tight.thinned, 0.04);
    EXPECT_NE(tight.intersect_warning().find("rings stand closer than"), std::string::npos) << tight.intersect_warning();
    const mq::Box3 rb = mq::bounding_box(tight.elements[0]);
    const double half_gap = 0.5 * mq::quilt::SwatchData::kThinGap * std::hypot(rb.size().x(), rb.size().y());
    Mesh grown = tight.mesh;
    mq::quilt::thicken_elements(&grown, comp, std::vector<double>(static_cast<std::size_t>(n), 0.9 * half_gap));
    EXPECT_TRUE(mq::intersecting_element_pairs(grown, comp, 1).empty());
    grown = tight.mesh;
    mq::quilt::thicken_elements(&grown, comp, std::vector<double>(static_cast<std::size_t>(n), 1.2 * half_gap));
    EXPECT_FALSE(mq::intersecting_element_pairs(grown, comp, 1).empty());

    // Disjoint swatches are left as they are.
    for (const char* name : {"chainmail", "pebbles", "weave"}) {
        const auto plain = mq::quilt::prepare_swatch(mq::read_mesh(swatch_path(name)));
        EXPECT_EQ(plain.intersecting_pairs, 0) << name;
        EXPECT_EQ(plain.thinned, 0.0) << name;
        EXPECT_FALSE(plain.tight) << name;
        EXPECT_TRUE(plain.intersect_warning().empty()) << name;
    }
    // Two slabs overlapping by 0.7 of their width: no thinning within a quarter of their 0.2
    // thickness parts them, so the swatch stays as it is, and says so.
    Mesh deep = shapes::concat(shapes::cube(1.0), shapes::translated(shapes::cube(1.0), Vec3(0.3, 0.0, 0.0)));
    for (Vec3& v : deep.vertices) v.z() *= 0.2;
    const auto stuck = mq::quilt::prepare_swatch(deep);
    EXPECT_EQ(stuck.intersecting_pairs, 1);
    EXPECT_EQ(stuck.thinned, 0.0);
    EXPECT_FALSE(stuck.elements_disjoint);
    EXPECT_NE(stuck.intersect_warning().find("cannot be thinned apart"), std::string::npos) << stuck.intersect_warning();
}

namespace {
std::vector<char> rings_of(const mq::quilt::SwatchData& sw) {
    std::vector<char> ring(sw.elements.size());
    for (std::size_t s = 0; s < ring.size(); ++s) ring[s] = sw.element_genus[s] > 0;
    return ring;
}

// The same mesh with its vertices and faces listed in another order, and each face's corners
// turned: what a swatch merged from an STL soup or written by another modeller looks like.
Mesh shuffled(const Mesh& m, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<int> order(m.vertices.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    Mesh out;
    std::vector<int> where(m.vertices.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        where[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
        out.vertices.push_back(m.vertices[static_cast<std::size_t>(order[i])]);
    }
    for (const auto& f : m.faces) {
        const int k = static_cast<int>(rng() % 3);
        out.faces.push_back({where[static_cast<std::size_t>(f[k])], where[static_cast<std::size_t>(f[(k + 1) % 3])],
                             where[static_cast<std::size_t>(f[(k + 2) % 3])]});
    }
    std::shuffle(out.faces.begin(), out.faces.end(), rng);
    return out;
}

// Mending continues a chain mail's lattice from any standing ring (quilt::ring_lattice): a ring on
// the swatch's border must propose the neighbours beyond that border too, not only those back inside
// the swatch, and every proposal must be where the lattice has a ring.
void expect_lattice_continues_past_border(const mq::quilt::SwatchData& sw) {
    const auto lattice = mq::quilt::ring_lattice(sw, rings_of(sw));
    const std::size_t S = sw.elements.size();
    ASSERT_GT(lattice.spacing, 0.0);
    ASSERT_EQ(lattice.next.size(), S);
    // In the swatch itself, an interior ring has the most neighbours (4-in-1 mail: 2 in its row, 4
    // it links with); rings on the border have fewer.
    std::size_t most = 0, fewer = 0;
    std::vector<std::size_t> own(S, 0);
    for (std::size_t s = 0; s < S; ++s) {
        for (std::size_t t = 0; t < S; ++t)
            own[s] += t != s && (lattice.centre[s] - lattice.centre[t]).norm() < 1.5 * lattice.spacing;
        most = std::max(most, own[s]);
    }
    EXPECT_EQ(most, 6u);
    // Two kinds of ring: the rows alternate their tilt, and every other row is a translate.
    ASSERT_EQ(lattice.kind.size(), S);
    EXPECT_EQ(std::set<int>(lattice.kind.begin(), lattice.kind.end()).size(), 2u);
    EXPECT_EQ(std::count(lattice.kind.begin(), lattice.kind.end(), -1), 0);
    int shifted = 0;
    for (std::size_t s = 0; s < S; ++s) {
        fewer += own[s] < most;
        // Every ring proposes as many neighbours as an interior one, each at a distinct place
        // between one and 1.5 spacings away.
        ASSERT_EQ(lattice.next[s].size(), most) << "ring " << s;
        std::vector<mq::Vec2> at;
        for (const auto& n : lattice.next[s]) {
            ASSERT_GE(n.source, 0);
            const mq::Vec2 c = lattice.centre[static_cast<std::size_t>(n.source)] + n.shift;
            const double d = (c - lattice.centre[s]).norm();
            EXPECT_GE(d, lattice.spacing * (1.0 - 1e-9));
            EXPECT_LT(d, 1.5 * lattice.spacing);
            for (const mq::Vec2& q : at) EXPECT_GT((q - c).norm(), 0.1 * lattice.spacing) << "ring " << s << " proposes one place twice";
            at.push_back(c);
            if (n.shift.norm() == 0.0) continue;
            ++shifted;
            // A shifted neighbour lies beyond the swatch: where no swatch ring is.
            for (std::size_t u = 0; u < S; ++u) EXPECT_GT((lattice.centre[u] - c).norm(), 0.1 * lattice.spacing);
        }
        // A ring the swatch surrounds keeps its own neighbours.
        if (own[s] == most)
            for (const auto& n : lattice.next[s]) EXPECT_EQ(n.shift.norm(), 0.0);
    }
    EXPECT_GT(fewer, 0u);
    // The shifted ones are exactly those the swatch's border lacks.
    int lacking = 0;
    for (std::size_t s = 0; s < S; ++s) lacking += static_cast<int>(most - own[s]);
    EXPECT_EQ(shifted, lacking);
}
}  // namespace

TEST(RingLattice, ContinuesPastTheSwatchBorder) {
    expect_lattice_continues_past_border(mq::quilt::prepare_swatch(mq::read_mesh(swatch_path("chainmail"))));
}

// Rings are of one kind by their shape, not by the order their vertices and faces are listed in:
// the bundled mail with every ring's vertices and faces in an order of their own has the same two
// kinds and continues past its border the same way.
TEST(RingLattice, KnowsTranslatesInAnyVertexOrder) {
    const Mesh mail = mq::read_mesh(swatch_path("chainmail"));
    for (unsigned seed : {1u, 2u}) {
        SCOPED_TRACE(seed);
        const auto sw = mq::quilt::prepare_swatch(shuffled(mail, seed));
        ASSERT_EQ(sw.elements.size(), 36u);
        expect_lattice_continues_past_border(sw);
    }
    // A ring moved off its plane's height, or one vertex moved by a hundredth of the spacing, is of
    // a kind of its own.
    const auto sw = mq::quilt::prepare_swatch(mail);
    for (double lift : {0.0, 0.05}) {
        Mesh two = sw.elements[0];
        Mesh other = shapes::translated(sw.elements[12], Vec3(0.0, 0.0, lift));
        if (lift == 0.0) other.vertices[5].x() += 0.0125;
        two = shapes::concat(two, shapes::translated(other, Vec3(0.0, 4.0, 0.0)));
        const auto pair = mq::quilt::prepare_swatch(two);
        ASSERT_EQ(pair.elements.size(), 2u);
        const auto lattice = mq::quilt::ring_lattice(pair, rings_of(pair));
        ASSERT_EQ(lattice.kind.size(), 2u);
        EXPECT_NE(lattice.kind[0], lattice.kind[1]) << "lift " << lift;
        // Unchanged, the same two rings are one kind.
        const auto same = mq::quilt::prepare_swatch(shapes::concat(sw.elements[0], shapes::translated(sw.elements[12], Vec3(0.0, 4.0, 0.0))));
        const auto same_lattice = mq::quilt::ring_lattice(same, rings_of(same));
        ASSERT_EQ(same_lattice.kind.size(), 2u);
        EXPECT_EQ(same_lattice.kind[0], same_lattice.kind[1]);
    }
}

// Rings that are no translates of one another (three tori of different sizes in a row) share no
// neighbours: each keeps those the swatch has; elements that are no rings get none.
TEST(RingLattice, UnlikeRingsKeepTheSwatchNeighbours) {
    Mesh row = shapes::torus(1.0, 0.2);
    row = shapes::concat(row, shapes::translated(shapes::torus(0.9, 0.2), Vec3(2.5, 0.0, 0.0)));
    row = shapes::concat(row, shapes::translated(shapes::torus(0.8, 0.2), Vec3(5.0, 0.0, 0.0)));
    Mesh cube = shapes::cube(0.4);
    for (Vec3& v : cube.vertices) v = Vec3(v.x() + 7.0, v.y(), v.z());
    const auto sw = mq::quilt::prepare_swatch(shapes::concat(row, cube));
    ASSERT_EQ(sw.elements.size(), 4u);
    const auto lattice = mq::quilt::ring_lattice(sw, rings_of(sw));
    ASSERT_NEAR(lattice.spacing, 2.5, 1e-6);
    std::size_t total = 0;
    for (std::size_t s = 0; s < sw.elements.size(); ++s) {
        if (sw.element_genus[s] == 0) EXPECT_TRUE(lattice.next[s].empty());
        for (const auto& n : lattice.next[s]) EXPECT_EQ(n.shift.norm(), 0.0);
        total += lattice.next[s].size();
    }
    EXPECT_EQ(total, 4u);  // the middle ring's two neighbours, and each end ring's one
    // Each ring is its own kind; the cube is of none.
    ASSERT_EQ(lattice.kind.size(), sw.elements.size());
    std::set<int> kinds;
    for (std::size_t s = 0; s < sw.elements.size(); ++s) {
        if (sw.element_genus[s] == 0) EXPECT_EQ(lattice.kind[s], -1);
        else EXPECT_TRUE(kinds.insert(lattice.kind[s]).second) << "ring " << s << " shares a kind";
    }
    EXPECT_EQ(kinds.size(), 3u);
}
