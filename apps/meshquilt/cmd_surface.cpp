// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt [surface] BASE SWATCH -o OUT [--scale S | --swatch-size L] [--height H] [--field FIELD]
//           [--symmetry N] [--seed N] [--with-base] [--embed shell|normal] [--report REPORT.json]

#include "cli.h"
#include "meshquilt/decorate.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/report.h"
#include "meshquilt/surface.h"

#include <cstdio>
#include <iostream>

namespace meshquilt::cli {

namespace {
struct SurfaceArgs {
    std::string base, swatch, output, report, field, embed = "shell";
    double scale = kDefaultScale, swatch_size = 0.0, height = 0.0;
    int symmetry = 0;
    std::uint64_t seed = 1;
    bool with_base = false, repair = false, no_optimise = false;
    PrintArgs print;
    std::string print_report;
};

std::string num(double v, int digits = 10) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}
}  // namespace

void add_surface_command(CLI::App& root, std::vector<Command>& commands) {
    auto a = std::make_shared<SurfaceArgs>();
    CLI::App* app = root.add_subcommand(
        "surface", "Cover a base mesh with a geometric texture grown from a swatch (the default command: `meshquilt BASE SWATCH -o OUT`)");
    app->add_option("base", a->base, "Base mesh (OBJ, PLY, STL, OFF) to decorate; it is never changed")->required();
    app->add_option("swatch", a->swatch, "Swatch mesh: a slab of separate elements")->required();
    auto* out_opt = app->add_option("-o,--output", a->output, "Output mesh (.obj with one group per element, .ply, .stl)");
    auto* scale = app->add_option("--scale", a->scale,
                                  "Swatch footprint's longer side as a fraction of the base's bounding-box diagonal (default: " +
                                      num(kDefaultScale) + ", raised for a swatch so dense that the output would pass 4 million faces)");
    app->add_option("--swatch-size", a->swatch_size, "Swatch footprint's longer side in base units (instead of --scale)")->excludes(scale);
    app->add_option("--height", a->height, "Shell height in base units (default: the swatch's thickness at that scale)");
    app->add_option("--field", a->field, "Guidance field file (face/vertex vectors or strokes; see docs/surface.md)");
    app->add_option("--symmetry", a->symmetry, "Rotational symmetry of the swatch for the automatic field: 1, 2, 4, 6 (default: detect)");
    app->add_option("--seed", a->seed, "Random seed: same inputs and seed give identical output")->capture_default_str();
    app->add_flag("--with-base", a->with_base, "Also write the base, as the group 'base'");
    app->add_option("--embed", a->embed,
                    "Embedding of the texture: 'shell' (stretch-optimised tetrahedral shell map, no cuts into concave regions) or "
                    "'normal' (displacement along interpolated normals)")
        ->check(CLI::IsMember({"shell", "normal"}))
        ->capture_default_str();
    app->add_flag("--no-shell-optimisation", a->no_optimise, "Build the shell map without its stretch optimisation");
    app->add_option("--report", a->report, "Write a JSON quality report here");
    app->add_flag("--repair", a->repair, "Repair safe input problems (degenerate faces, duplicate or non-manifold vertices, orientation) and report them");
    auto* print_opt = app->add_option("--print", a->print.output,
                                      "Also write a printable .3mf/.stl in millimetres (fused: decoration and base as one solid; "
                                      "separate: the elements only); needs --size-mm or --unit-mm");
    add_print_options(app, a->print, false);
    app->add_option("--print-report", a->print_report, "Write the print's JSON report here");
    commands.push_back({app, [a, out_opt, print_opt, scale]() {
        if (out_opt->count() == 0 && print_opt->count() == 0) throw InvalidInput("give an output: -o OUT (mesh) and/or --print OUT.3mf|OUT.stl");
        if (print_opt->count() > 0) check_print_args(a->print);
        // decorate() validates (and with --repair repairs) the inputs, exactly as for the Python module.
        const Mesh base_in = read_mesh(a->base);
        const Mesh swatch = read_mesh(a->swatch);
        DecorateOptions d;
        d.base_name = a->base;
        d.swatch_name = a->swatch;
        d.repair = a->repair;
        SurfaceQuiltOptions& o = d.surface;
        if (scale->count() > 0) o.scale = a->scale;
        o.swatch_size = a->swatch_size;
        o.height = a->height;
        o.symmetry = a->symmetry;
        o.seed = a->seed;
        o.embedding = a->embed == "normal" ? Embedding::Normal : Embedding::Shell;
        o.optimise_shell = !a->no_optimise;
        if (!a->field.empty()) o.field = read_guidance_field(a->field);
        o.reporter = make_cli_reporter();
        const DecorateResult r = decorate(base_in, swatch, d);
        finish_progress();
        const Mesh& base = r.base;
        for (const auto& w : r.repairs) std::cerr << "meshquilt: repaired " << w << '\n';
        // (the warnings were printed by the reporter as they came)
        Mesh out = r.decoration.mesh;
        WriteOptions wo;
        wo.element_of_face = r.decoration.element_of_face;
        if (a->with_base) {
            const int id = r.report.elements;
            const int offset = static_cast<int>(out.vertices.size());
            out.vertices.insert(out.vertices.end(), base.vertices.begin(), base.vertices.end());
            for (const Tri& t : base.faces) {
                out.faces.push_back(t + Tri::Constant(offset));
                wo.element_of_face.push_back(id);
            }
            wo.group_names.assign(static_cast<std::size_t>(id) + 1, "");
            wo.group_names.back() = "base";
        }
        wo.comment = "meshquilt " + a->base + " " + a->swatch +
                     (a->swatch_size > 0 ? " --swatch-size " + num(a->swatch_size) : " --scale " + num(r.surface.scale)) +
                     (a->height > 0 ? " --height " + num(a->height) : "") + " --seed " + std::to_string(a->seed);
        if (!a->output.empty()) write_mesh(a->output, out, wo);
        if (!a->report.empty()) write_file_atomic(a->report, report_json(r));
        if (!a->print.output.empty()) {
            // Fused: the decoration and its base make one solid. Separate (print-in-place): the
            // elements alone; the base is the form they were grown on.
            const bool with_base_body = a->print.mode != "separate";
            run_print(a->print, r.decoration.mesh, with_base_body ? &base : nullptr, a->base + " + " + a->swatch, a->print_report);
        }
        if (!global_flags().quiet)
            std::cerr << "meshquilt: " << r.report.elements << " elements, " << r.report.faces << " faces"
                      << (r.surface.regions > 0 ? ", regions at " + num(r.surface.region_density_min, 3) + "-" + num(r.surface.region_density_max, 3) +
                                                      " of the swatch's density (" + num(r.surface.region_density_mid_min, 3) + "-" +
                                                      num(r.surface.region_density_mid_max, 3) + " on the shell's middle surface" +
                                                      (r.surface.region_count_density_max > 0
                                                           ? "; by count " + num(r.surface.region_count_density_min, 3) + "-" +
                                                                 num(r.surface.region_count_density_max, 3)
                                                           : std::string()) +
                                                      "; thinnest around " +
                                                      num(r.surface.region_density_min_at.x(), 4) +
                                                      ", " + num(r.surface.region_density_min_at.y(), 4) + ", " +
                                                      num(r.surface.region_density_min_at.z(), 4) + ")"
                                                : std::string())
                      << (a->output.empty() ? std::string() : " -> " + a->output) << '\n';
        return 0;
    }});
}

}  // namespace meshquilt::cli
