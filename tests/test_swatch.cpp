// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// The swatch as the synthesis sees it (quilt/swatch.h): elements, their genus, the gaps between them.

#include "meshquilt/io.h"
#include "quilt/swatch.h"
#include "support/paths.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

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
