// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file checkers.h
/// Reusable GoogleTest checkers. Each returns an AssertionResult whose failure message names the
/// first offending face, edge, vertex or element, so `EXPECT_TRUE(is_closed_manifold(m))` says
/// what is wrong. Also: element splitting and Gauss linking numbers for ring-like elements.

#include "core/links.h"
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

/// Ring centre lines and linking numbers live in the library (core/links.h).
using meshquilt::linking_number;
using meshquilt::links_once;
using meshquilt::crossing_linking_number;
using meshquilt::shadow_direction;
using meshquilt::ring_centerline;

/// The linking number of the centre lines of two ring-like elements, rounded to an integer.
int rounded_linking(const Mesh& ring_a, const Mesh& ring_b);

/// For ring-like elements: how many other rings each one interlocks with (|linking number| = 1),
/// testing pairs whose vertex centroids are within `reach`. Rings without a link are absent.
std::map<int, int> link_counts(const std::vector<Mesh>& rings, double reach);

}  // namespace meshquilt::test
