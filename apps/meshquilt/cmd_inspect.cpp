// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt inspect FILE [--json]: what a mesh is made of and what is wrong with it. Problems are
// reported, not fatal: only a file that cannot be read or parsed fails (exit code 2).

#include "cli.h"
#include "meshquilt/analysis.h"
#include "meshquilt/io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace meshquilt::cli {

namespace {

struct InspectArgs {
    std::string file;
    bool json = false;
};

constexpr std::size_t kTextElements = 20;  // element rows in text mode; --json lists all

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

/// "1 edge", "2 edges".
std::string count(long long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

std::string vec(const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }

/// Keys in the order a reader wants them, not alphabetical.
nlohmann::ordered_json to_json(const std::string& file, const MeshAnalysis& a) {
    using json = nlohmann::ordered_json;
    json j;
    j["file"] = file;
    j["faces"] = a.faces;
    j["vertices"] = a.vertices;
    j["unreferenced_vertices"] = a.unreferenced_vertices;
    if (a.box.empty()) {
        j["bbox"] = nullptr;
    } else {
        j["bbox"] = {{"min", {a.box.min.x(), a.box.min.y(), a.box.min.z()}}, {"max", {a.box.max.x(), a.box.max.y(), a.box.max.z()}}};
    }
    j["thin_axis"] = {{"axis", axis_name(a.thin.axis)}, {"thickness", a.thin.thickness}, {"is_thin", a.thin.is_thin}};
    json elements = json::array();
    for (std::size_t i = 0; i < a.elements.size(); ++i) {
        const ElementInfo& e = a.elements[i];
        elements.push_back({{"index", i},
                            {"faces", e.faces},
                            {"vertices", e.vertices},
                            {"closed", e.closed},
                            {"edge_manifold", e.edge_manifold},
                            {"genus", e.genus},
                            {"boundary_loops", e.boundary_loops},
                            {"area", e.area},
                            {"volume", e.closed ? json(e.volume) : json(nullptr)}});
    }
    j["elements"] = std::move(elements);
    j["elements_closed"] = a.closed_elements();
    j["genus"] = a.genus;
    j["boundary_loops"] = a.boundary_loops;
    j["boundary_edges"] = a.boundary_edges;
    j["non_manifold_edges"] = a.non_manifold_edges;
    j["non_manifold_vertices"] = a.non_manifold_vertices;
    j["inconsistent_edges"] = a.inconsistent_edges;
    j["degenerate_faces"] = a.degenerate_faces;
    j["duplicate_vertices"] = a.duplicate_vertices;
    j["area"] = a.area;
    j["problems"] = a.problems;
    return j;
}

std::string to_text(const std::string& file, const MeshAnalysis& a) {
    std::ostringstream out;
    auto row = [&](const char* label, const std::string& value) {
        char buf[20];
        std::snprintf(buf, sizeof buf, "%-15s ", label);
        out << buf << value << '\n';
    };
    row("file", file);
    row("faces", std::to_string(a.faces));
    row("vertices", std::to_string(a.vertices) + " (" + std::to_string(a.unreferenced_vertices) + " unreferenced)");
    if (!a.box.empty()) {
        const Vec3 s = a.box.size();
        row("bounding box", vec(a.box.min) + " to " + vec(a.box.max) + ", size " + num(s.x()) + " x " + num(s.y()) + " x " + num(s.z()));
        Vec3 sorted = s;
        std::sort(sorted.data(), sorted.data() + 3);
        row("thin axis", std::string(axis_name(a.thin.axis)) + ", thickness " + num(a.thin.thickness) +
                             (a.thin.is_thin ? ": a valid swatch slab (at most half the middle extent, "
                                             : ": not a swatch slab (more than half the middle extent, ") +
                             num(sorted[1]) + ")");
    }
    std::vector<int> sizes;
    for (const ElementInfo& e : a.elements) sizes.push_back(e.faces);
    std::sort(sizes.begin(), sizes.end());
    std::string elements = std::to_string(a.elements.size()) + ", " + std::to_string(a.closed_elements()) + " closed";
    if (!sizes.empty())
        elements += "; faces per element: min " + std::to_string(sizes.front()) + ", median " +
                    std::to_string(sizes[sizes.size() / 2]) + ", max " + std::to_string(sizes.back());
    row("elements", elements);
    row("genus", std::to_string(a.genus) + (a.elements.size() > 1 ? " (summed over elements)" : ""));
    row("boundary", count(a.boundary_loops, "loop", "loops") + ", " + count(a.boundary_edges, "edge", "edges"));
    row("non-manifold", count(a.non_manifold_edges, "edge", "edges") + ", " + count(a.non_manifold_vertices, "vertex", "vertices"));
    row("orientation", count(a.inconsistent_edges, "inconsistent edge", "inconsistent edges"));
    row("degenerate", count(a.degenerate_faces, "face", "faces"));
    row("duplicates", count(a.duplicate_vertices, "vertex", "vertices"));
    row("area", num(a.area));

    if (!a.elements.empty()) {
        const std::size_t shown = std::min(a.elements.size(), kTextElements);
        out << '\n';
        if (shown < a.elements.size())
            out << "elements (first " << shown << " of " << a.elements.size() << "; --json lists all)\n";
        else
            out << "elements\n";
        char buf[160];
        std::snprintf(buf, sizeof buf, "  %6s %8s %7s %6s %6s %12s %12s\n", "index", "faces", "closed", "genus", "loops", "area",
                      "volume");
        out << buf;
        for (std::size_t i = 0; i < shown; ++i) {
            const ElementInfo& e = a.elements[i];
            std::snprintf(buf, sizeof buf, "  %6zu %8d %7s %6d %6d %12s %12s\n", i, e.faces, e.closed ? "yes" : "no", e.genus,
                          e.boundary_loops, num(e.area).c_str(), e.closed ? num(e.volume).c_str() : "-");
            out << buf;
        }
    }
    out << '\n';
    if (a.problems.empty()) {
        out << "problems: none\n";
    } else {
        out << "problems (" << a.problems.size() << "):\n";
        for (const std::string& p : a.problems) out << "  - " << p << '\n';
    }
    return out.str();
}

}  // namespace

void add_inspect_command(CLI::App& root, std::vector<Command>& commands) {
    auto args = std::make_shared<InspectArgs>();
    CLI::App* app = root.add_subcommand(
        "inspect", "Report a mesh's size, bounding box, thin axis, elements, genus, boundary and defects (problems do not fail)");
    app->add_option("file", args->file, "Mesh file (OBJ, PLY, STL, OFF)")->required();
    app->add_flag("--json", args->json, "Print one JSON object instead of text (lists every element)");
    commands.push_back({app, [args]() {
        const Mesh mesh = read_mesh(args->file);  // IoError / InvalidInput: main() exits with 2
        const MeshAnalysis a = analyse(mesh);
        if (args->json) std::cout << to_json(args->file, a).dump(2) << '\n';
        else std::cout << to_text(args->file, a);
        std::cout.flush();
        return std::cout.good() ? 0 : 1;
    }});
}

}  // namespace meshquilt::cli
