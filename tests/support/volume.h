// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file volume.h
/// An independent reference for the print tests: the volume of a union of closed bodies by
/// vertical rays (exact along each ray, sampled over a grid in x and y). No OpenVDB, no CGAL.

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt::test {

/// Volume of the union of closed, consistently oriented bodies: on an n x n grid of vertical
/// rays over their common bounding box, each ray's crossings give exact inside intervals per body
/// (winding by facet orientation); the union's length times the cell area is summed.
double union_volume_by_rays(const std::vector<Mesh>& bodies, int n = 400);

}  // namespace meshquilt::test
