// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt plane SWATCH --size W H -o OUT [--seed N] [--report REPORT.json]

#include "cli.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/quilt.h"
#include "meshquilt/report.h"

#include <chrono>
#include <cstdio>
#include <iostream>

namespace meshquilt::cli {

namespace {
struct PlaneArgs {
    std::string swatch;
    std::vector<double> size;
    std::string output;
    std::string report;
    std::uint64_t seed = 1;
    double cell = 0.0;
    int subpatch = 0;
    bool repair = false;
};
}  // namespace

void add_plane_command(CLI::App& root, std::vector<Command>& commands) {
    auto args = std::make_shared<PlaneArgs>();
    CLI::App* app = root.add_subcommand("plane", "Planar mesh quilting: grow a W x H texture from a swatch (Zhou et al. 2006, Section 2)");
    app->add_option("swatch", args->swatch, "Swatch mesh (OBJ, PLY, STL, OFF): a slab of separate elements")->required();
    app->add_option("--size", args->size, "Output footprint W H, in swatch units")->expected(2)->required();
    app->add_option("-o,--output", args->output, "Output mesh (.obj with one group per element, .ply, .stl)")->required();
    app->add_option("--seed", args->seed, "Random seed: same inputs and seed give identical output")->capture_default_str();
    app->add_option("--report", args->report, "Write a JSON quality report here");
    app->add_option("--cell", args->cell, "Grid cell size in swatch units (default: 1/24 of the swatch's longer side)");
    app->add_option("--subpatch", args->subpatch, "Output sub-patch side in cells (default: a third of the swatch's cells)");
    app->add_flag("--repair", args->repair, "Repair safe input problems (degenerate faces, duplicate or non-manifold vertices, orientation) and report them");
    commands.push_back({app, [args]() {
        const auto t0 = std::chrono::steady_clock::now();
        const Mesh swatch = load_input(args->swatch, args->repair, true);
        PlanarQuiltOptions o;
        o.width = args->size[0];
        o.height = args->size[1];
        o.seed = args->seed;
        o.cell_size = args->cell;
        o.subpatch_cells = args->subpatch;
        o.reporter = make_cli_reporter();
        QuiltResult r;
        try {
            r = quilt_plane(swatch, o);
        } catch (const InvalidInput& e) {
            throw InvalidInput(args->swatch + ": " + e.what());
        }
        finish_progress();
        for (const auto& w : r.warnings) std::cerr << "meshquilt: warning: " << w << '\n';
        WriteOptions wo;
        wo.element_of_face = r.element_of_face;
        auto num = [](double v) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.10g", v);
            return std::string(buf);
        };
        wo.comment = "meshquilt plane " + args->swatch + " --size " + num(o.width) + " " + num(o.height) + " --seed " + std::to_string(o.seed);
        write_mesh(args->output, r.mesh, wo);
        if (!args->report.empty()) {
            const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            write_file_atomic(args->report, report_json(r.report, total));
        }
        if (!global_flags().quiet)
            std::cerr << "meshquilt: " << r.report.elements << " elements, " << r.report.faces << " faces -> " << args->output << '\n';
        return 0;
    }});
}

}  // namespace meshquilt::cli
