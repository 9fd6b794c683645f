// SPDX-License-Identifier: AGPL-3.0-or-later
// meshquilt: geometric texture synthesis from a swatch mesh (Zhou et al. 2006, "Mesh Quilting").

#include "cli.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/version.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <mutex>
#include <new>
#include <unistd.h>

namespace meshquilt::cli {

GlobalFlags& global_flags() {
    static GlobalFlags flags;
    return flags;
}

namespace {
struct ProgressState {
    std::mutex mutex;
    std::string stage;
    int last_percent = -1;
    bool drawn = false;
};
ProgressState& progress_state() {
    static ProgressState s;
    return s;
}
bool progress_enabled() {
    if (global_flags().quiet) return false;
    const char* env = std::getenv("MESHQUILT_PROGRESS");
    if (env) return std::string(env) == "1";
    return isatty(fileno(stderr)) != 0;
}
}  // namespace

void finish_progress() {
    auto& s = progress_state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (s.drawn) std::fputc('\n', stderr);
    s.drawn = false;
    s.last_percent = -1;
    s.stage.clear();
}

Reporter make_cli_reporter() {
    Reporter r;
    if (progress_enabled()) {
        r.progress = [](const std::string& stage, double fraction) {
            auto& s = progress_state();
            std::lock_guard<std::mutex> lock(s.mutex);
            const int percent = static_cast<int>(fraction * 100.0 + 0.5);
            if (stage == s.stage && percent == s.last_percent) return true;
            s.stage = stage;
            s.last_percent = percent;
            const int width = 30;
            const int filled = percent * width / 100;
            std::fprintf(stderr, "\r%-12s [%s%s] %3d%%", stage.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                         std::string(static_cast<std::size_t>(width - filled), '.').c_str(), percent);
            std::fflush(stderr);
            s.drawn = true;
            return true;
        };
    }
    r.log = [](LogLevel level, const std::string& text) {
        const int v = global_flags().verbosity;
        if (level == LogLevel::Debug && v < 2) return;
        if (level == LogLevel::Info && v < 1) return;
        finish_progress();
        std::cerr << (level == LogLevel::Warning ? "meshquilt: warning: " : "meshquilt: ") << text << '\n';
    };
    return r;
}

Mesh load_input(const std::string& path, bool repair, bool require_thin_axis) {
    Mesh raw = read_mesh(path);
    ValidationOptions vo;
    vo.repair = repair;
    vo.require_thin_axis = require_thin_axis;
    ValidationResult res = validate(raw, path, vo);
    for (const auto& r : res.repairs) std::cerr << "meshquilt: repaired " << r << '\n';
    for (const auto& w : res.warnings) std::cerr << "meshquilt: warning: " << w << '\n';
    return std::move(res.mesh);
}

}  // namespace meshquilt::cli

int main(int argc, char** argv) {
    using namespace meshquilt;
    using namespace meshquilt::cli;
    CLI::App root{"meshquilt: cover meshes with geometric textures grown from a swatch (mesh quilting)", "meshquilt"};
    root.footer("The main job: meshquilt BASE SWATCH -o OUT [options], the same as `meshquilt surface BASE SWATCH ...`.");
    root.require_subcommand(1);
    root.add_flag("-q,--quiet", global_flags().quiet, "No progress bar");
    root.add_flag("-v,--verbose", global_flags().verbosity, "More log output (repeat for debug)");
    root.set_version_flag("--version", std::string("meshquilt ") + version());
    std::vector<Command> commands;
    add_plane_command(root, commands);
    add_inspect_command(root, commands);
    add_surface_command(root, commands);
    add_print_command(root, commands);
    // Global flags (-q, -v) may also follow a command's own arguments.
    for (auto& c : commands) c.app->fallthrough();
    // `meshquilt BASE SWATCH ...` is `meshquilt surface BASE SWATCH ...`: the first argument that is
    // not a flag, if it names no command, starts the main job.
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (!args[i].empty() && args[i][0] == '-') continue;
        bool known = false;
        for (const auto& c : commands) known = known || c.app->check_name(args[i]);
        if (!known && args[i] != "help") args.insert(args.begin() + static_cast<std::ptrdiff_t>(i), "surface");
        break;
    }
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments reversed
    try {
        root.parse(args);
    } catch (const CLI::ParseError& e) {
        const int code = root.exit(e);
        return code == 0 ? 0 : 2;  // usage errors exit with 2
    }
    try {
        for (auto& c : commands)
            if (c.app->parsed()) {
                const int code = c.run();
                finish_progress();
                return code;
            }
        return 2;
    } catch (const Error& e) {
        finish_progress();
        std::cerr << "meshquilt: error: " << e.what() << '\n';
        return exit_code_for(e.code());
    } catch (const std::bad_alloc&) {
        finish_progress();
        std::cerr << "meshquilt: error: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        finish_progress();
        std::cerr << "meshquilt: internal error: " << e.what() << '\n';
        return 1;
    }
}
