// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Element deformation, Zhou et al. 2006 Section 2.6 (Eq. 4-6): Laplacian least squares that keeps the
// uniform Laplacian coordinates of every vertex while pulling constrained points to targets.

#include "meshquilt/mesh.h"

#include <array>
#include <vector>

namespace meshquilt::quilt {

/// A soft positional constraint on the point bary[0] w_v0 + bary[1] w_v1 + bary[2] w_v2 (Eq. 6);
/// a vertex constraint (Eq. 5) has v = {i, i, i} and bary = (1, 0, 0).
struct PointConstraint {
    std::array<int, 3> v{0, 0, 0};
    Vec3 bary = Vec3(1, 0, 0);
    Vec3 target = Vec3::Zero();
    static PointConstraint vertex(int i, const Vec3& target) { return {{i, i, i}, Vec3(1, 0, 0), target}; }
};

/// New vertex positions minimising sum_i |L(w_i) - L(v_i)|^2 + mu sum_k |C_k w - c_k|^2 (Eq. 5/6 with
/// the uniform Laplacian of Eq. 4). A tiny regulariser keeps parts without constraints in place.
/// Vertices with `fixed[i]` stay exactly where they are (they leave the system; the Laplacian rows
/// around them keep them as known values). Returns the input positions unchanged when there are no
/// constraints.
std::vector<Vec3> laplacian_deform(const Mesh& mesh, const std::vector<PointConstraint>& constraints, double mu = 1.0,
                                   const std::vector<char>& fixed = {});

}  // namespace meshquilt::quilt
