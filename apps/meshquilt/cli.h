// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Shared pieces of the command-line tool: subcommand registration, input loading, progress bar.

#include "meshquilt/analysis.h"
#include "meshquilt/mesh.h"
#include "meshquilt/reporter.h"

#include <CLI/CLI.hpp>

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
