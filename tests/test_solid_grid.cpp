// labels: unit
// SPDX-License-Identifier: AGPL-3.0-or-later
// The voxel solid of a closed mesh (quilt/solid_grid.h), which the ring-hole search of surface
// quilting uses to refuse tries before embedding them: inside where the mesh is, outside its
// holes and around it, for meshes whose vertices sit on the grid, and nothing for an open mesh.

#include "quilt/solid_grid.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mq = meshquilt;
namespace quilt = meshquilt::quilt;
namespace shapes = meshquilt::test::shapes;
using mq::Vec3;

namespace {

// Distance from p to the centre circle of a torus around z (major R): inside the tube when below
// the minor radius.
double tube_distance(const Vec3& p, double R) {
    const double rho = std::hypot(p.x(), p.y());
    return std::hypot(rho - R, p.z());
}

}  // namespace

TEST(SolidGrid, TorusInsideIsItsTubeAndItsHoleIsEmpty) {
    const double R = 2.0, r = 0.5;
    const mq::Mesh t = shapes::torus(R, r, 64, 24);
    const quilt::SolidGrid g(t, 64);
    ASSERT_FALSE(g.empty());
    const double h = g.cell();
    EXPECT_NEAR(h, 2.0 * (R + r) / 64.0, 1e-9);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    int tested = 0, wrong = 0;
    for (int k = 0; k < 20000; ++k) {
        const Vec3 p(u(rng), u(rng), 0.4 * u(rng));
        const double d = tube_distance(p, R);
        // The polygon mesh lies within r (1 - cos(pi / 24)) of the smooth tube, and a voxel
        // answers for its centre: points within a cell and that of the surface may go either way.
        if (std::fabs(d - r) < 1.8 * h) continue;
        ++tested;
        wrong += g.inside(p) != (d < r);
    }
    EXPECT_GT(tested, 10000);
    EXPECT_EQ(wrong, 0);
    EXPECT_FALSE(g.inside(Vec3::Zero()));  // the hole
    EXPECT_TRUE(g.inside(Vec3(R, 0.0, 0.0)));
    EXPECT_TRUE(g.inside(Vec3(0.0, -R, 0.1)));
    EXPECT_FALSE(g.inside(Vec3(10.0, 0.0, 0.0)));  // beyond the grid
}

TEST(SolidGrid, CubeOnTheGridIsWhole) {
    // The cube's corners and faces lie exactly on column boundaries: every column inside must
    // still count two crossings.
    const mq::Mesh c = shapes::cube(2.0);
    const quilt::SolidGrid g(c, 8);
    ASSERT_FALSE(g.empty());
    int inside = 0;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 8; ++k) inside += g.inside(Vec3((i + 0.5) * 0.25, (j + 0.5) * 0.25, (k + 0.5) * 0.25));
    EXPECT_EQ(inside, 512);
    EXPECT_FALSE(g.inside(Vec3(-0.1, 1.0, 1.0)));
    EXPECT_FALSE(g.inside(Vec3(1.0, 1.0, 2.1)));
}

TEST(SolidGrid, OpenAndEmptyMeshesHoldNothing) {
    const quilt::SolidGrid open(shapes::open_cylinder(1.0, 2.0, 16, 4), 32);
    int inside = 0;
    for (double z = 0.05; z < 2.0; z += 0.1) inside += open.inside(Vec3(0.0, 0.0, z)) + open.inside(Vec3(0.5, 0.2, z));
    EXPECT_EQ(inside, 0);  // a tube along z: no column crosses it an even number of times inside
    EXPECT_TRUE(quilt::SolidGrid(mq::Mesh{}, 32).empty());
    EXPECT_FALSE(quilt::SolidGrid(mq::Mesh{}, 32).inside(Vec3::Zero()));
}
