// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Tangent direction fields on a triangle mesh, per face, with N-fold rotational symmetry: the
// smoothest field (globally optimal, Knöppel et al. 2013: the smallest eigenvector of the
// connection Laplacian, by inverse iteration) or the smoothest field through user constraints
// (one sparse least-squares solve). The field's length is a separate scalar scale, interpolated
// harmonically from the constraints.

#include "meshquilt/mesh.h"
#include "meshquilt/surface.h"
#include "quilt/swatch.h"

#include <array>
#include <string>
#include <vector>

namespace meshquilt::quilt {

/// neighbour[f][k]: the face across the edge (faces[f][k], faces[f][(k+1)%3]); -1 on a boundary
/// or a non-manifold edge.
std::vector<std::array<int, 3>> face_neighbours(const Mesh& mesh);

struct DirectionField {
    int symmetry = 1;
    std::vector<Vec3> direction;  ///< per face: one unit tangent representative of the N directions
    std::vector<double> scale;    ///< per face: local scale factor (1 without user magnitudes)
};

/// The field on `mesh`. Without constraints in `user`: the smoothest N-field, per connected
/// component. `name` prefixes error messages (bad indices, zero vectors).
/// \throw InvalidInput a constraint names a face or vertex that does not exist, or has zero length
DirectionField compute_field(const Mesh& mesh, const std::vector<std::array<int, 3>>& neighbours, int symmetry,
                             const GuidanceField& user, const std::string& name);

/// The rotational symmetry of a swatch's layout, from its elements' principal directions: 2 when
/// elongated elements run mostly one way, 4 when they run two perpendicular ways (a weave) or
/// the elements are round (isotropic: the freest choice).
int detect_symmetry(const SwatchData& swatch);

/// Angle between two directions up to N-fold symmetry, in radians, in [0, pi/N].
double symmetric_angle(const Vec3& a, const Vec3& b, const Vec3& normal, int symmetry);

}  // namespace meshquilt::quilt
