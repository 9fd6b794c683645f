// SPDX-License-Identifier: AGPL-3.0-or-later
// The quality reports as JSON (report.h).

#include "meshquilt/report.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace meshquilt {

namespace {
nlohmann::json planar(const QualityReport& r, double total_seconds) {
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
    j["elements_squeezed"] = r.elements_squeezed;
    j["losers_kept"] = r.losers_kept;
    j["strand_pieces"] = r.strand_pieces;
    j["bald_spots_filled"] = r.bald_spots_filled;
    j["joints_closed"] = r.joints_closed;
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


nlohmann::json point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json print(const PrintReport& r) {
    nlohmann::json violations = nlohmann::json::array();
    for (const PrintViolation& v : r.violations) {
        nlohmann::json j = {{"kind", v.kind == PrintViolation::Kind::Clearance ? "clearance" : "thickness"},
                            {"value_mm", v.value_mm},
                            {"location_mm", point(v.location)},
                            {"body", v.body_a}};
        if (v.kind == PrintViolation::Kind::Clearance) j["other_body"] = v.body_b;
        violations.push_back(j);
    }
    nlohmann::json j = {{"mode", r.mode == PrintMode::Fused ? "fused" : "separate"},
                        {"mm_per_unit", r.mm_per_unit},
                        {"size_mm", point(r.size_mm)},
                        {"input_bodies", r.input_bodies},
                        {"bodies", r.bodies},
                        {"open_base_thickened", r.open_base_thickened != 0},
                        {"triangles", r.triangles},
                        {"vertices", r.vertices},
                        {"volume_mm3", r.volume_mm3},
                        {"boundary_edges", r.boundary_edges},
                        {"non_manifold_edges", r.non_manifold_edges},
                        {"inconsistent_edges", r.inconsistent_edges},
                        {"inside_out_bodies", r.inside_out_bodies},
                        {"degenerate_faces", r.degenerate_faces},
                        {"min_thickness_mm", std::isfinite(r.min_thickness_mm) ? nlohmann::json(r.min_thickness_mm) : nlohmann::json(nullptr)},
                        {"min_thickness_location_mm", point(r.min_thickness_at)},
                        {"checks_passed", r.checks_passed},
                        {"violations", violations},
                        {"seconds", {{"prepare", r.seconds_prepare}, {"voxelise", r.seconds_voxelise}, {"mesh", r.seconds_mesh}, {"checks", r.seconds_checks}}}};
    if (r.mode == PrintMode::Separate) {
        j["min_clearance_mm"] = r.min_clearance_mm >= 0.0 ? nlohmann::json(r.min_clearance_mm) : nlohmann::json(nullptr);
        j["min_clearance_location_mm"] = point(r.min_clearance_at);
        j["min_clearance_bodies"] = {r.min_clearance_bodies[0], r.min_clearance_bodies[1]};
        j["intersecting_pairs"] = r.intersecting_pairs;
    }
    if (r.voxel_mm > 0.0) {
        j["voxel_mm"] = r.voxel_mm;
        j["voxel_derived"] = r.voxel_derived;
        j["voxels_estimated"] = r.voxels_estimated;
        j["voxels_active"] = r.voxels_active;
        j["voids_filled"] = r.voids_filled;
        j["scraps_dropped"] = r.scraps_dropped;
        j["loose_bodies"] = r.loose_bodies;
    }
    return j;
}

}  // namespace

std::string report_json(const QualityReport& report, double total_seconds) { return planar(report, total_seconds).dump(2) + "\n"; }

std::string report_json(const QualityReport& report, const SurfaceQualityReport& s, double total_seconds) {
    nlohmann::json j = planar(report, total_seconds);
        j["surface"] = {{"base_faces", s.base_faces},
                        {"base_faces_processed", s.base_faces_processed},
                        {"coverage", s.base_faces ? static_cast<double>(s.base_faces_processed) / s.base_faces : 0.0},
                        {"patches_shrunk", s.patches_shrunk},
                        {"patches_rigid", s.patches_rigid},
                        {"frozen_elements_seen", s.frozen_elements_seen},
                        {"threads_extended", s.threads_extended},
                        {"threads_trimmed", s.threads_trimmed},
                        {"thread_pieces", s.thread_pieces},
                        {"threads_filled", s.threads_filled},
                        {"threads_turned", s.threads_turned},
                        {"threads_mended", s.threads_mended},
                        {"gaps_closed", s.gaps_closed},
                        {"threads_torn", s.threads_torn},
                        {"threads_dented", s.threads_dented},
                        {"elements_torn", s.elements_torn},
                        {"threads_cut_at_patch", s.threads_cut_at_patch},
                        {"elements_folded", s.elements_folded},
                        {"elements_enlarged", s.elements_enlarged},
                        {"elements_nudged", s.elements_nudged},
                        {"elements_thinned", s.elements_thinned},
                        {"elements_mended", s.elements_mended},
                        {"ring_holes_filled", s.ring_holes_filled},
                        {"ring_holes_tilted", s.ring_holes_tilted},
                        {"ring_holes_enlarged", s.ring_holes_enlarged},
                        {"rings_swapped", s.rings_swapped},
                        {"rings_unlinked_removed", s.rings_unlinked_removed},
                        {"symmetry", s.symmetry},
                        {"scale", s.scale},
                        {"base_units_per_swatch_unit", s.base_scale},
                        {"region_density_min", s.region_density_min},
                        {"region_density_max", s.region_density_max},
                        {"region_density_mid_min", s.region_density_mid_min},
                        {"region_density_mid_max", s.region_density_mid_max},
                        {"region_density_min_at", {s.region_density_min_at.x(), s.region_density_min_at.y(), s.region_density_min_at.z()}},
                        {"region_count_density_min", s.region_count_density_min},
                        {"region_count_density_max", s.region_count_density_max},
                        {"region_count_density_mid_min", s.region_count_density_mid_min},
                        {"region_count_density_mid_max", s.region_count_density_mid_max},
                        {"region_count_density_min_at",
                         {s.region_count_density_min_at.x(), s.region_count_density_min_at.y(), s.region_count_density_min_at.z()}},
                        {"region_count_density_max_at",
                         {s.region_count_density_max_at.x(), s.region_count_density_max_at.y(), s.region_count_density_max_at.z()}},
                        {"regions", s.regions},
                        {"element_size_min", s.element_size_min},
                        {"element_size_max", s.element_size_max},
                        {"elements_sized", s.elements_sized},
                        {"elements_off_size", s.elements_off_size},
                        {"base_flipped_components", s.base_flipped_components},
                        {"base_fold_vertices_smoothed", s.base_fold_vertices_smoothed},
                        {"base_thin_faces_remeshed", s.base_thin_faces_remeshed},
                        {"base_holes_filled", s.base_holes_filled},
                        {"vertices_below_base", s.vertices_below_base},
                        {"elements_below_base", s.elements_below_base},
                        {"vertices_above_shell", s.vertices_above_shell},
                        {"embedding", s.embedding == Embedding::Shell ? "shell" : "normal"},
                        {"shell_height", s.shell_height}};
        if (s.embedding == Embedding::Shell) {
            const ShellStatistics& h = s.shell;
            j["stretch_l2_initial"] = h.stretch_l2_initial;
            j["stretch_l2_final"] = h.stretch_l2_final;
            nlohmann::json regions = nlohmann::json::array();
            for (const ShellLimitedRegion& g : h.limited_regions)
                regions.push_back({{"centre", {g.centre.x(), g.centre.y(), g.centre.z()}}, {"vertices", g.vertices}, {"min_height_ratio", g.min_ratio}});
            j["shell"] = {{"vertices", h.vertices},
                          {"prisms", h.prisms},
                          {"tetrahedra", h.tetrahedra},
                          {"charts", h.charts},
                          {"free_offset_vertices", h.free_offset_vertices},
                          {"optimisation_passes", h.optimisation_passes},
                          {"inverted_tetrahedra", h.inverted_world},
                          {"inverted_texture_tetrahedra", h.inverted_texture},
                          {"offset_intersections", h.offset_intersections},
                          {"height_limited_vertices", h.height_limited_vertices},
                          {"height_limited_area_fraction", h.limited_area_fraction},
                          {"min_height_ratio", h.min_height_ratio},
                          {"height_limited_regions", regions},
                          {"seconds_build", h.seconds_build},
                          {"seconds_optimise", h.seconds_optimise}};
        }
    return j.dump(2) + "\n";
}

std::string report_json(const PrintReport& report) { return print(report).dump(2) + "\n"; }

}  // namespace meshquilt
