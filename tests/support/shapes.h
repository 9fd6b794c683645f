// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file shapes.h
/// Small meshes with known topology for the io, analysis and CLI tests: closed surfaces of known
/// genus, open surfaces with a known number of boundary loops, and deliberately broken variants.
/// Unless stated, faces are counter-clockwise seen from outside (outward normals).

#include "meshquilt/mesh.h"

#include <array>
#include <vector>

namespace meshquilt::test::shapes {

/// The axis-aligned cube [origin, origin + size]^3: 8 vertices, 12 faces, genus 0, volume size^3.
Mesh cube(double size = 1.0, const Vec3& origin = Vec3::Zero());

/// A torus around the z axis: `major` radius of the centre line, `minor` radius of the tube,
/// `nu` x `nv` quads (each >= 3) split into triangles. Genus 1, closed.
Mesh torus(double major = 2.0, double minor = 0.5, int nu = 24, int nv = 12);

/// An open cylinder (a tube without caps) around the z axis from z = 0 to `height`:
/// `segments` around (>= 3), `rings` along (>= 1). Two boundary loops, genus 0.
Mesh open_cylinder(double radius = 1.0, double height = 2.0, int segments = 16, int rings = 4);

/// A closed capsule around the z axis, as modelling tools build one (a UV sphere stretched at its
/// equator): a tube of `radius` from z = 0 to `length` between two hemispheres, `segments` around
/// (>= 3), `cap_rings` rings of latitude per hemisphere (>= 2) ending in a fan of thin triangles at
/// each pole, `rings` along the tube (>= 1). Genus 0, normals outward.
Mesh capsule(double radius, double length, int segments, int cap_rings, int rings);

/// Each face split into four at its edges' midpoints (shared midpoints shared); the shape is kept.
Mesh subdivided(const Mesh& mesh);

/// A flat square [0, size]^2 in the plane z = 0, `n` x `n` quads split into triangles, normals +z.
/// One boundary loop, genus 0.
Mesh grid(int n = 4, double size = 1.0);

/// The closed outer surface of a union of unit voxels (cells given by their integer minimum
/// corners): every voxel face not shared with another voxel becomes two triangles; corners on the
/// integer lattice are shared. Voxels touching only along an edge or at a corner give a
/// non-manifold edge or vertex, which some tests want.
Mesh voxels(const std::vector<std::array<int, 3>>& cells);

/// A slab of 5 x 3 x 1 voxels with two square holes through it: a closed surface of genus 2.
Mesh double_torus();

/// A square grid of bars as one closed element (genus n^2): the cells of a raster of side `cell`
/// that lie on a bar, extruded to height `h` (top, bottom and the walls between filled and empty
/// cells, vertices shared).
Mesh grid_net(int n, double pitch, double bar, double h, double cell);

/// A plain weave of `n` warp ribbons along x and `n` weft ribbons along y, `pitch` apart, each an
/// open sheet (no thickness) `width` wide over a length of n * pitch, rising and falling by
/// `amplitude` (a cosine) over and under the ribbons it crosses (warp i over weft j where i + j is
/// even), `segments` quads along each ribbon and two across. Faces up (+z normal).
Mesh ribbon_weave(int n, double pitch, double width, double amplitude, int segments);

/// A plain weave of `n` warp threads along x and `n` weft threads along y, `pitch` apart, each a
/// closed tube with an elliptic cross-section (`half_width` across, `half_height` up, `sides`
/// vertices round it) over a length of n * pitch, flat ends, rising and falling by `amplitude` (a
/// cosine) over and under the threads it crosses (warp i over weft j where i + j is even),
/// `segments` cross-sections along each thread. The gap between two crossing threads is
/// 2 (amplitude - half_height) there.
Mesh round_weave(int n, double pitch, double half_width, double half_height, double amplitude, int sides, int segments);

/// A flat disc of `radius` at z = 0 (normal +z) triangulated as a fan: `n` slivers from the centre
/// to the rim, as CAD exporters triangulate a round face. Open.
Mesh fan_disc(double radius, int n);

/// The cube [-size/2, size/2]^3 with each face triangulated as a fan from its centre to `n` points
/// along each of its edges (4n slivers per face, vertices shared along the cube's edges): sharp
/// edges and corners with CAD-like slivers. Closed, genus 0, facing outwards.
Mesh fan_cube(double size, int n);

/// Two copies of `a` and `b` in one mesh (b's indices shifted).
Mesh concat(const Mesh& a, const Mesh& b);

/// `mesh` moved by `offset`.
Mesh translated(Mesh mesh, const Vec3& offset);

/// Every face reversed: an inside-out copy.
Mesh flipped(Mesh mesh);

/// A triangle soup: every face gets its own three vertices (like STL), positions unchanged.
Mesh soup(const Mesh& mesh);

/// `swatch` in its own frame (normalize_swatch) with every element's surface moved outwards along
/// its vertex normals by `by` (quilt::thicken_elements): a thicker wire for a chain mail, so that
/// linked rings intersect (the bundled mail by 0.08: wire radius 0.18 -> about 0.26).
Mesh thickened(const Mesh& swatch, double by);

}  // namespace meshquilt::test::shapes
