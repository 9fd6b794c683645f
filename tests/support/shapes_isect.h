// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file shapes_isect.h
/// Small closed test meshes (tori, icospheres) and helpers to place and combine them, for the
/// intersection and checker tests. All faces are counter-clockwise seen from outside.

#include "meshquilt/mesh.h"

#include <Eigen/Geometry>

#include <vector>

namespace meshquilt::test::isect {

/// Rotation by `angle` radians about `axis` (need not be unit length).
Eigen::Matrix3d rotation(const Vec3& axis, double angle);

/// A torus around the z axis (before `rotation`): `major` is the distance from the centre to the
/// tube's centre line, `minor` the tube radius. `nu` segments around the ring, `nv` around the
/// tube (each >= 3): nu * nv vertices, 2 nu nv faces, genus 1. Then rotated and moved to `center`.
Mesh torus(double major, double minor, int nu = 32, int nv = 12, const Vec3& center = Vec3::Zero(),
           const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity());

/// An icosphere: 20 * 4^subdivisions faces, vertices on the sphere (up to rounding).
Mesh icosphere(double radius, int subdivisions = 1, const Vec3& center = Vec3::Zero());

/// The axis-aligned box [lo, hi] as 12 triangles (8 vertices).
Mesh cuboid(const Vec3& lo, const Vec3& hi);

/// `mesh` with every vertex mapped to rotation * v + translation.
Mesh transformed(const Mesh& mesh, const Eigen::Matrix3d& rotation, const Vec3& translation);

/// Several meshes in one, element k being parts[k] (the library's concatenate).
using Combined = ElementMesh;
inline Combined combine(const std::vector<Mesh>& parts) { return concatenate(parts); }

}  // namespace meshquilt::test::isect
