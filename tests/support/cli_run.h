// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Running the meshquilt command line from tests.

#include <filesystem>
#include <string>

namespace meshquilt::test {

struct CliOutcome {
    int code = -1;    ///< exit code (-1 when the process did not exit normally)
    std::string err;  ///< everything written to stderr
};

/// Runs `meshquilt ARGS` (through the shell; stdout discarded) and captures stderr.
CliOutcome run_cli(const std::string& args);

/// The bytes of a file ("" when it cannot be read).
std::string slurp(const std::filesystem::path& path);

}  // namespace meshquilt::test
