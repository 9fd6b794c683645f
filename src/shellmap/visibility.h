// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Directions that see a vertex's faces from outside, for offset directions and for finding folds.

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt::shell {

/// Offset directions must see every face around their vertex with at least this cosine; a vertex
/// where no direction does is on a fold.
constexpr double kMinSeeingCos = 0.1;

/// The unit direction maximising the least cosine with `normals` (unit vectors), starting from
/// `start` (kept if nothing does better): the optimum lies on a normal, or is equidistant from two
/// or three of them, and all such candidates (of the first 16 normals) are tried. Returns that
/// least cosine; *best receives the direction.
double best_visibility(const std::vector<Vec3>& normals, const Vec3& start, Vec3* best);

/// Moves each vertex on a fold of `mesh` (no direction sees all its faces with a cosine of at least
/// `min_cos`) to the mean of its neighbours, repeatedly, until no fold is left or `rounds` pass.
/// When three rounds bring no fewer folds (a vertex at its ring's mean whose ring is folded), the
/// vertices within one more ring of the folds are smoothed with them (up to four rings). Returns
/// the number of distinct vertices moved.
int smooth_folds(Mesh& mesh, double min_cos, int rounds = 10);

}  // namespace meshquilt::shell
