// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file solid.h
/// Inside/outside tests against closed meshes for the shell-map tests (CGAL's
/// Side_of_triangle_mesh and AABB distances; independent of the code under test).

#include "meshquilt/mesh.h"

#include <memory>
#include <vector>

namespace meshquilt::test {

/// A closed, outward-oriented mesh as a solid.
class Solid {
public:
    explicit Solid(const Mesh& closed);
    ~Solid();
    /// Strictly inside and farther than `margin` from the surface.
    [[nodiscard]] bool inside(const Vec3& p, double margin = 0.0) const;
    /// Distance to the surface.
    [[nodiscard]] double distance(const Vec3& p) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace meshquilt::test
