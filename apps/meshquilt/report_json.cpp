// SPDX-License-Identifier: AGPL-3.0-or-later
#include "report_json.h"

namespace meshquilt::cli {

nlohmann::json report_to_json(const QualityReport& r, double total_seconds) {
    nlohmann::json j;
    j["faces"] = r.faces;
    j["vertices"] = r.vertices;
    j["elements"] = r.elements;
    j["elements_closed"] = r.elements_closed;
    j["elements_removed"] = r.elements_removed;
    j["patches"] = r.patches;
    j["elements_stitched"] = r.elements_stitched;
    j["elements_replaced"] = r.elements_replaced;
    j["stitch_failures"] = r.stitch_failures;
    j["collisions_avoided"] = r.collisions_avoided;
    j["elements_crowded_out"] = r.elements_crowded_out;
    j["cell_size"] = r.cell_size;
    j["swatch_density"] = r.swatch_density;
    j["output_density"] = r.output_density;
    j["largest_translation_share"] = r.largest_translation_share;
    nlohmann::json s = nlohmann::json::object();
    for (const auto& [stage, sec] : r.seconds) s[stage] = sec;
    s["total"] = total_seconds;
    j["seconds"] = s;
    return j;
}

}  // namespace meshquilt::cli
