// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// A voxel grid of the inside of a closed mesh, for fast approximate "is this point inside the
// element?" queries (the ring-hole search of surface quilting rejects most of its tries with it
// before embedding them).

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt::quilt {

/// The solid of a closed, consistently oriented mesh on a regular grid: a voxel is inside when
/// its centre is, by the parity of the mesh's crossings along the vertical line through it (scan
/// conversion: each face adds its height at the centres of the columns its xy shadow covers). The
/// grid's cells are cubes, `cells` along the box's longest side. An open or self-intersecting mesh
/// gives some columns an odd number of crossings; those columns count as outside.
class SolidGrid {
public:
    SolidGrid() = default;
    SolidGrid(const Mesh& m, int cells);

    /// Is `p` in a voxel whose centre lies inside the mesh? False outside the grid.
    bool inside(const Vec3& p) const;
    double cell() const { return h_; }
    bool empty() const { return in_.empty(); }

private:
    Vec3 lo_ = Vec3::Zero();
    double h_ = 0.0;
    int nx_ = 0, ny_ = 0, nz_ = 0;
    std::vector<char> in_;
};

}  // namespace meshquilt::quilt
