// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt print DECORATED [--base BASE] -o OUT.3mf|OUT.stl --size-mm X [--mode fused|separate]
//                [--min-thickness MM] [--min-clearance MM] [--force] [--report REPORT.json]
// and the print options of the main job (--print OUT --size-mm X ...).

#include "cli.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/print.h"
#include "meshquilt/report.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <chrono>
#include <cmath>
#include <iostream>

namespace meshquilt::cli {

namespace {

}  // namespace

void check_print_args(const PrintArgs& a) {
    std::string ext = a.output.size() >= 4 ? a.output.substr(a.output.size() - 4) : "";
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".3mf" && ext != ".stl") throw InvalidInput(a.output + ": a print is written as .3mf or .stl");
    if (!(a.size_mm > 0.0) && !(a.unit_mm > 0.0))
        throw InvalidInput("the print needs its size: --size-mm (largest dimension) or --unit-mm (mm per model unit), positive");
}

void add_print_options(CLI::App* app, PrintArgs& a, bool with_output) {
    if (with_output) app->add_option("-o,--output", a.output, "Printable file: .3mf (millimetres; one object per body) or .stl (binary)")->required();
    auto* size = app->add_option("--size-mm", a.size_mm, "Largest dimension of the print in millimetres");
    app->add_option("--unit-mm", a.unit_mm, "Millimetres per model unit (instead of --size-mm)")->excludes(size);
    app->add_option("--mode", a.mode, "'fused': one watertight solid (OpenVDB union); 'separate': every element its own body (print-in-place)")
        ->check(CLI::IsMember({"fused", "separate"}))
        ->capture_default_str();
    app->add_option("--min-thickness", a.min_thickness, "Thinnest printable feature in mm")->capture_default_str();
    app->add_option("--min-clearance", a.min_clearance, "Smallest gap between separate bodies in mm")->capture_default_str();
    app->add_option("--voxel-mm", a.voxel_mm, "Fused mode: voxel size in mm (default: from the thinnest feature, at most 0.1)");
    app->add_option("--adaptivity", a.adaptivity, "Fused mode: mesh adaptivity in [0, 1] (0: every voxel)")->capture_default_str();
    app->add_option("--attach-mm", a.attach_mm, "Fused mode: grow the base by this much (mm) so elements resting on it join it")->capture_default_str();
    app->add_option("--base-thickness", a.base_thickness, "An open base becomes a sheet this thick (mm)")->capture_default_str();
    app->add_option("--max-voxels", a.max_voxels, "Fused mode: refuse larger voxel grids")->capture_default_str();
    app->add_flag("--force", a.force, "Write even when the clearance or thickness check fails");
}

void run_print(const PrintArgs& a, const Mesh& decoration, const Mesh* base, const std::string& name, const std::string& report_path) {
    check_print_args(a);
    const auto t0 = std::chrono::steady_clock::now();
    PrintOptions o;
    o.mode = a.mode == "separate" ? PrintMode::Separate : PrintMode::Fused;
    o.size_mm = a.size_mm;
    o.unit_mm = a.unit_mm;
    o.min_thickness_mm = a.min_thickness;
    o.min_clearance_mm = a.min_clearance;
    o.voxel_mm = a.voxel_mm;
    o.adaptivity = a.adaptivity;
    o.base_thickness_mm = a.base_thickness;
    o.attach_mm = a.attach_mm;
    o.max_voxels = a.max_voxels;
    o.force = a.force;
    o.reporter = make_cli_reporter();
    const auto write_report = [&](const PrintReport& r) {
        if (report_path.empty()) return;
        nlohmann::json j = nlohmann::json::parse(report_json(r));
        j["seconds"]["total"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        write_file_atomic(report_path, j.dump(2) + "\n");
    };
    PrintResult r;
    try {
        r = prepare_print(decoration, base, o, name);
    } catch (const PrintCheckFailed& e) {
        finish_progress();
        write_report(e.report);  // the violations, for the user to see; the print itself is not written
        throw;
    }
    finish_progress();
    for (const auto& w : r.warnings) std::cerr << "meshquilt: warning: " << w << '\n';
    WriteOptions wo;
    if (o.mode == PrintMode::Separate) {
        wo.element_of_face = r.model.element_of_face;
        wo.assembly_3mf = true;  // the bodies stay together in the slicer
        wo.group_names.resize(static_cast<std::size_t>(r.model.num_elements));
        for (int e = 0; e < r.model.num_elements; ++e) wo.group_names[static_cast<std::size_t>(e)] = "body_" + std::to_string(e);
    }
    wo.comment = "meshquilt print, millimetres";
    write_mesh(a.output, r.model.mesh, wo);
    write_report(r.report);
    if (!global_flags().quiet) {
        const PrintReport& p = r.report;
        std::cerr << "meshquilt: " << p.bodies << (p.bodies == 1 ? " body, " : " bodies, ") << p.triangles << " triangles, "
                  << p.size_mm.x() << " x " << p.size_mm.y() << " x " << p.size_mm.z() << " mm, volume " << p.volume_mm3 << " mm^3";
        if (p.mode == PrintMode::Separate && p.min_clearance_mm >= 0.0) std::cerr << ", min clearance " << p.min_clearance_mm << " mm";
        std::cerr << " -> " << a.output << '\n';
    }
}

void add_print_command(CLI::App& root, std::vector<Command>& commands) {
    auto a = std::make_shared<PrintArgs>();
    auto input = std::make_shared<std::string>();
    auto base = std::make_shared<std::string>();
    auto report = std::make_shared<std::string>();
    auto repair = std::make_shared<bool>(false);
    CLI::App* app = root.add_subcommand("print", "Make a decorated mesh printable: a watertight solid or separate bodies, in millimetres");
    app->add_option("decorated", *input, "Decorated mesh (e.g. meshquilt's output); each connected part must be closed")->required();
    app->add_option("--base", *base, "The base mesh, printed with the decoration (an open base is thickened)");
    add_print_options(app, *a, true);
    app->add_option("--report", *report, "Write a JSON report here (also when a check fails)");
    app->add_flag("--repair", *repair, "Repair safe input problems (degenerate faces, duplicate or non-manifold vertices, orientation) and report them");
    commands.push_back({app, [a, input, base, report, repair]() {
        check_print_args(*a);
        const Mesh deco = load_input(*input, *repair, false);
        Mesh b;
        if (!base->empty()) b = load_input(*base, *repair, false);
        run_print(*a, deco, base->empty() ? nullptr : &b, *input, *report);
        return 0;
    }});
}

}  // namespace meshquilt::cli
