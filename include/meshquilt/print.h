// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file print.h
/// Export for 3D printing, in millimetres. Two modes:
///  - `Fused`: the elements and the base united into one watertight, edge-manifold,
///    outward-oriented solid through an OpenVDB narrow-band level set (meshToLevelSet of every
///    closed body, an unsigned-distance shell around an open base, union, adaptive volumeToMesh,
///    quads split along their shorter diagonal).
///  - `Separate`: every element its own closed body, as for print-in-place fabrics (chain mail);
///    the smallest clearance between two bodies and the thinnest feature are measured exactly
///    (triangle-triangle distances; inward rays) and checked against the printer's limits.
/// The model is scaled so its largest dimension is `size_mm` (or one unit is `unit_mm`) and moved
/// so its bounding box starts at the origin (the print bed is z = 0).

#include "meshquilt/errors.h"
#include "meshquilt/mesh.h"
#include "meshquilt/reporter.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace meshquilt {

enum class PrintMode { Fused, Separate };

struct PrintOptions {
    PrintMode mode = PrintMode::Fused;
    /// The largest dimension of the whole model in millimetres; or, when 0, `unit_mm`.
    double size_mm = 0.0;
    /// Millimetres per model unit (used when `size_mm` is 0). One of the two must be positive.
    double unit_mm = 0.0;
    /// Thinnest feature the printer makes; thinner ones are violations in separate mode and
    /// warnings in fused mode.
    double min_thickness_mm = 0.8;
    /// Smallest gap between two bodies that stays open in a print-in-place fabric (separate mode).
    double min_clearance_mm = 0.3;
    /// Fused mode: voxel edge in mm; 0 derives it from the thinnest feature (docs/print.md).
    double voxel_mm = 0.0;
    /// Fused mode: volumeToMesh adaptivity in [0, 1]; 0 keeps every voxel's polygon.
    double adaptivity = 0.2;
    /// Fused mode: the base grows outward by this much (mm) so elements resting on it, or nearly,
    /// join it instead of printing as loose pieces; 0 keeps the base exact.
    double attach_mm = 0.2;
    /// An open base becomes a sheet this thick (mm), centred on its surface.
    double base_thickness_mm = 2.0;
    /// Fused mode: refuse voxel grids whose narrow band would exceed this many voxels (about 30
    /// bytes each while meshing); a derived voxel size is coarsened to fit instead.
    std::uint64_t max_voxels = 200'000'000;
    /// Write even when a check fails (the violations stay in the report).
    bool force = false;
    Reporter reporter;
};

/// A place where a print limit is not met.
struct PrintViolation {
    enum class Kind { Clearance, Thickness } kind = Kind::Clearance;
    double value_mm = 0.0;   ///< the clearance or thickness found
    Vec3 location;           ///< mm, in the output's coordinates
    int body_a = -1;         ///< the body (its index in the output)
    int body_b = -1;         ///< clearance: the other body
};

struct PrintReport {
    PrintMode mode = PrintMode::Fused;
    double mm_per_unit = 0.0;
    Vec3 size_mm = Vec3::Zero();       ///< bounding box of the output
    int input_bodies = 0;              ///< closed decoration elements (+ the base)
    int bodies = 0;                    ///< bodies written (1 in fused mode unless parts are apart)
    int open_base_thickened = 0;       ///< 1 when an open base was made a sheet
    std::size_t triangles = 0;
    std::size_t vertices = 0;
    double volume_mm3 = 0.0;           ///< enclosed volume of the output
    // Watertightness of the output, counted on the written mesh (all 0 for a good file).
    int boundary_edges = 0;
    int non_manifold_edges = 0;
    int inconsistent_edges = 0;
    int inside_out_bodies = 0;
    int degenerate_faces = 0;          ///< (near) zero area; reported, not an error
    // Fused mode.
    double voxel_mm = 0.0;
    bool voxel_derived = false;
    std::uint64_t voxels_estimated = 0;
    std::uint64_t voxels_active = 0;
    int voids_filled = 0;              ///< enclosed air pockets (e.g. under elements) filled
    int scraps_dropped = 0;            ///< closed parts under 1% of a voxel's volume, dropped
    int loose_bodies = 0;              ///< fused: parts besides the largest (warned about)
    // Checks (both modes measure; separate mode enforces).
    double min_thickness_mm = 0.0;     ///< thinnest feature found (inward ray from a face)
    Vec3 min_thickness_at = Vec3::Zero();
    int min_thickness_body = -1;
    double min_clearance_mm = -1.0;    ///< smallest gap between two bodies; -1 with fewer than two
    Vec3 min_clearance_at = Vec3::Zero();
    int min_clearance_bodies[2] = {-1, -1};
    int intersecting_pairs = 0;        ///< pairs of bodies that touch or cut each other
    std::vector<PrintViolation> violations;  ///< at most one per body pair / body, worst first
    bool checks_passed = true;
    double seconds_prepare = 0.0, seconds_voxelise = 0.0, seconds_mesh = 0.0, seconds_checks = 0.0;
};

struct PrintResult {
    /// The printable model in mm: one element per body (fused: the solid's connected parts).
    ElementMesh model;
    PrintReport report;
    std::vector<std::string> warnings;
};

/// Thrown by prepare_print() when a check fails without `force`: an InvalidInput (exit code 2)
/// that keeps the full report, so callers can still show every violation.
struct PrintCheckFailed : InvalidInput {
    PrintCheckFailed(const std::string& message, PrintReport r) : InvalidInput(message), report(std::move(r)) {}
    PrintReport report;
};

/// Turns a decoration (and optionally its base) into a printable model. `decoration` may hold
/// the base already (as written by `--with-base`): its connected components are the bodies; each
/// must be closed. `base` may be null; it may be open (it is then thickened). `name` starts every
/// message (usually the decoration's path).
/// \throw InvalidInput open or non-manifold bodies, bad options, a voxel grid beyond
///        `max_voxels`, and (without `force`) failed checks; thrown before heavy work where possible.
/// \throw PrintCheckFailed (an InvalidInput) a check failed and `force` is false.
PrintResult prepare_print(const Mesh& decoration, const Mesh* base, const PrintOptions& options,
                          const std::string& name = "decoration");

/// Separate-mode checks on its own: thinnest feature and smallest clearance between the bodies
/// of `model` (in whatever units it is in; thresholds in the same units).
struct BodyChecks {
    double min_thickness = 0.0;
    Vec3 min_thickness_at = Vec3::Zero();
    int min_thickness_body = -1;
    double min_clearance = -1.0;
    Vec3 min_clearance_at = Vec3::Zero();
    int min_clearance_bodies[2] = {-1, -1};
    int intersecting_pairs = 0;
    std::vector<PrintViolation> violations;
};
BodyChecks check_bodies(const ElementMesh& model, double min_thickness, double min_clearance);

}  // namespace meshquilt
