// SPDX-License-Identifier: AGPL-3.0-or-later
// Interlocking rings: a ring's centre line and the Gauss linking number of two closed curves. Used
// by the surface stage to tell which rings of a chain mail hold on to their neighbours, and by the
// tests.
#pragma once

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt {

/// The centre line of a ring-like element (a torus, a chain link, even somewhat bent): the vertices
/// used by faces are projected onto the element's PCA plane, binned by angle around their centroid,
/// and averaged (in 3D) per bin. Returns one point per non-empty bin, in angular order, as a closed
/// polygon (the last point connects back to the first).
std::vector<Vec3> ring_centerline(const Mesh& ring, int bins = 48);

/// Gauss linking number of two closed polygons (each given by its vertices; the closing segment is
/// implied), by the exact formula for polygonal curves (Klenin & Langowski 2000, Eq. 4-5): the
/// sum over segment pairs of the signed solid angle of the quadrilateral they span, over 4 pi.
/// Within rounding of an integer for curves that do not intersect. The sign depends on the
/// orientations of the curves. \throw std::invalid_argument fewer than 3 points in a curve
double linking_number(const std::vector<Vec3>& closed_a, const std::vector<Vec3>& closed_b);

/// The same linking number, counted in a projection: half the sum over the crossings of the two
/// polygons' shadows along a fixed generic direction of the signs of the crossings, which for a
/// pair of segments is the sign of the Gauss integrand (the integer the Gauss integral is within
/// rounding of, without its square roots and arc sines). Each crossing is
/// decided by floating-point orientations held to an error bound; when one is too close to call
/// (a shadow's vertex on the other's edge, two segments nearly meeting in space), the answer is the
/// Gauss integral's, rounded. \throw std::invalid_argument fewer than 3 points in a curve
int crossing_linking_number(const std::vector<Vec3>& closed_a, const std::vector<Vec3>& closed_b);

/// The unit direction crossing_linking_number casts its shadows along.
Vec3 shadow_direction();

/// Do two rings interlock once, given their centre lines (|crossing_linking_number| is 1)? False
/// when either line has fewer than 3 points (a degenerate ring links nothing).
bool links_once(const std::vector<Vec3>& line_a, const std::vector<Vec3>& line_b);

}  // namespace meshquilt
