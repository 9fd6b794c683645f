// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file report.h
/// The quality reports as JSON text: what the CLI's --report writes, what the Python module returns
/// as a dict. Keys are documented in docs/cli.md; they only grow.

#include "meshquilt/print.h"
#include "meshquilt/quilt.h"
#include "meshquilt/surface.h"

#include <string>

namespace meshquilt {

/// The planar report (`meshquilt plane --report`); `total_seconds` is the whole job's wall time.
std::string report_json(const QualityReport& report, double total_seconds);
/// The main job's report (`meshquilt BASE SWATCH --report`): the planar keys, `surface`, and with
/// the shell embedding `stretch_l2_initial`, `stretch_l2_final` and `shell`.
std::string report_json(const QualityReport& report, const SurfaceQualityReport& surface, double total_seconds);
/// The print report (`meshquilt print --report`).
std::string report_json(const PrintReport& report);

}  // namespace meshquilt
