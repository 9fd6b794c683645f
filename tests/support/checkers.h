// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file checkers.h
/// Reusable GoogleTest checkers. Each returns an AssertionResult whose failure message names the
/// first offending face, edge, vertex or element, so `EXPECT_TRUE(is_closed_manifold(m))` says
/// what is wrong. Also: element splitting and Gauss linking numbers for ring-like elements.

#include "meshquilt/mesh.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>
#include <vector>

namespace meshquilt::test {

/// Every face has three distinct in-range indices and non-zero area (exact test); every edge is
/// used by exactly two faces, in opposite directions; the faces around every vertex form a single
/// fan. Unreferenced vertices are ignored. A mesh without faces fails.
::testing::AssertionResult is_closed_manifold(const Mesh& mesh);

/// Each element (faces with the same id) is closed and edge-manifold on its own: every edge of the
/// element is used by exactly two of its faces, in opposite directions, and no face repeats an
/// index. The failure names the first bad element and its counts of boundary, non-manifold and
/// inconsistently oriented edges (with a first example), and how many elements fail.
::testing::AssertionResult elements_closed(const Mesh& mesh, const std::vector<int>& element_of_face);

/// No two distinct elements intersect or touch (exact), except the pairs in `allowed` (either
/// order). The failure lists the first offending pairs.
::testing::AssertionResult no_element_intersections(const Mesh& mesh, const std::vector<int>& element_of_face,
                                                    const std::vector<std::pair<int, int>>& allowed = {});

/// No two faces of `mesh` intersect other than at a properly shared vertex or edge (exact; see
/// count_self_intersections in core/intersect.h).
::testing::AssertionResult no_self_intersections(const Mesh& mesh);

/// One mesh per element id 0..max id (empty for unused ids), each with only the vertices it uses,
/// in order of first use; faces keep their order.
std::vector<Mesh> split_elements(const Mesh& mesh, const std::vector<int>& element_of_face);

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

/// The linking number of the centre lines of two ring-like elements, rounded to an integer.
int rounded_linking(const Mesh& ring_a, const Mesh& ring_b);

/// For ring-like elements: how many other rings each one interlocks with (|linking number| = 1),
/// testing pairs whose vertex centroids are within `reach`. Rings without a link are absent.
std::map<int, int> link_counts(const std::vector<Mesh>& rings, double reach);

}  // namespace meshquilt::test
