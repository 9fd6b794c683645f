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
    bool inside(const Vec3& p) const {
        if (in_.empty()) return false;
        const Vec3 q = (p - lo_) / h_;
        if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.z() >= 0.0)) return false;
        const auto i = static_cast<long>(q.x()), j = static_cast<long>(q.y()), k = static_cast<long>(q.z());
        if (i >= nx_ || j >= ny_ || k >= nz_) return false;
        return in_[(static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i)) * static_cast<std::size_t>(nz_) + static_cast<std::size_t>(k)] != 0;
    }
    double cell() const { return h_; }
    bool empty() const { return in_.empty(); }

private:
    Vec3 lo_ = Vec3::Zero();
    double h_ = 0.0;
    int nx_ = 0, ny_ = 0, nz_ = 0;
    std::vector<char> in_;
};

}  // namespace meshquilt::quilt
