// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file decorate.h
/// The whole job in one call: check the inputs, quilt the swatch over the base (surface.h) and,
/// when asked, prepare a printable model (print.h). This is what `meshquilt BASE SWATCH` runs and
/// what the Python module and the Blender add-on call.

#include "meshquilt/mesh.h"
#include "meshquilt/print.h"
#include "meshquilt/quilt.h"
#include "meshquilt/surface.h"

#include <optional>
#include <string>
#include <vector>

namespace meshquilt {

struct DecorateOptions {
    /// Scale, height, field, seed, embedding... and the Reporter for progress, cancellation and
    /// log messages (also used by the print step when its own reporter is empty).
    SurfaceQuiltOptions surface;
    /// Make the safe repairs of validate() (degenerate faces, duplicate or non-manifold vertices,
    /// orientation)
    /// instead of refusing such inputs; each repair is listed in `DecorateResult::repairs`.
    bool repair = false;
    /// Names that start every message about the inputs (file paths in the CLI).
    std::string base_name = "base";
    std::string swatch_name = "swatch";
    /// When set, also prepare a printable model: fused (decoration and base as one solid) or
    /// separate (the elements alone, for print-in-place fabrics).
    std::optional<PrintOptions> print;
};

struct DecorateResult {
    /// The decoration: one element per grown element, faces of one element contiguous.
    ElementMesh decoration;
    std::vector<int> source_element;  ///< per element: the swatch element it grew from
    Mesh base;                          ///< the base as validated (and repaired, with `repair`)
    QualityReport report;
    SurfaceQualityReport surface;
    std::vector<std::string> repairs;   ///< repairs made to the inputs (with `repair` only)
    std::vector<std::string> warnings;  ///< about the inputs and the synthesis (also sent to the reporter's log)
    std::optional<PrintResult> print;   ///< with `DecorateOptions::print`
    double seconds = 0.0;               ///< wall time of the whole call
};

/// Validates both meshes (validate(), the swatch must have a thin axis), runs quilt_surface() and,
/// when asked, prepare_print(). Same inputs and seed give identical output. The inputs are never
/// changed.
/// \throw InvalidInput bad meshes or options; the message starts with the mesh's name
/// \throw PrintCheckFailed a print check failed (and `print->force` was not set)
/// \throw Cancelled the reporter asked to stop
DecorateResult decorate(const Mesh& base, const Mesh& swatch, const DecorateOptions& options);

/// The main job's JSON report (see report.h) of a decorate() result; with a print, its report
/// under "print".
std::string report_json(const DecorateResult& result);

}  // namespace meshquilt
