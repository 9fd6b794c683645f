// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
#include "meshquilt/quilt.h"

#include <nlohmann/json.hpp>

namespace meshquilt::cli {
/// The quality report as JSON; `total_seconds` is the wall time of the whole command.
nlohmann::json report_to_json(const QualityReport& r, double total_seconds);
}  // namespace meshquilt::cli
