// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Shared pieces of the command-line tool: subcommand registration, input loading, progress bar.

#include "meshquilt/analysis.h"
#include "meshquilt/mesh.h"
#include "meshquilt/reporter.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace meshquilt::cli {

/// A subcommand: its CLI11 parser and what runs when it was chosen. `run` returns the exit code.
struct Command {
    CLI::App* app = nullptr;
    std::function<int()> run;
};

void add_inspect_command(CLI::App& root, std::vector<Command>& commands);
void add_plane_command(CLI::App& root, std::vector<Command>& commands);
void add_surface_command(CLI::App& root, std::vector<Command>& commands);
void add_print_command(CLI::App& root, std::vector<Command>& commands);

/// The print options, shared by `meshquilt print` and the main job's --print.
struct PrintArgs {
    std::string output, mode = "fused";
    double size_mm = 0.0, unit_mm = 0.0, min_thickness = 0.8, min_clearance = 0.3, voxel_mm = 0.0, adaptivity = 0.2,
           base_thickness = 2.0, attach_mm = 0.2;
    std::uint64_t max_voxels = 200'000'000;
    bool force = false;
};
/// Registers --size-mm, --unit-mm, --mode, ... (and -o when `with_output`).
void add_print_options(CLI::App* app, PrintArgs& args, bool with_output);
/// Checks what can be checked before any work: the file type and the size. \throw InvalidInput
void check_print_args(const PrintArgs& args);
/// Prepares and writes the print of `decoration` (+ `base`); writes the JSON report to
/// `report_path` when not empty, also when a check fails.
void run_print(const PrintArgs& args, const Mesh& decoration, const Mesh* base, const std::string& name, const std::string& report_path);

/// Global flags, set by main() before any command runs.
struct GlobalFlags {
    bool quiet = false;    ///< no progress bar
    int verbosity = 0;     ///< -v: info logs, -vv: debug logs
};
GlobalFlags& global_flags();

/// A Reporter that draws a progress bar on stderr (when it is a terminal, or always with
/// MESHQUILT_PROGRESS=1) and prints warnings (and info with -v).
Reporter make_cli_reporter();
/// Ends the progress bar line, if one was drawn.
void finish_progress();

/// Reads and validates an input mesh; prints repairs and warnings to stderr.
Mesh load_input(const std::string& path, bool repair, bool require_thin_axis);

}  // namespace meshquilt::cli
