// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/cli_run.h"

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace meshquilt::test {

CliOutcome run_cli(const std::string& args) {
    static std::atomic<int> counter{0};
    const std::filesystem::path errfile = std::filesystem::temp_directory_path() /
                                          ("mq_cli_err_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".txt");
    const std::string cmd = std::string(MQ_CLI_PATH) + " " + args + " 2>" + errfile.string() + " >/dev/null";
    const int status = std::system(cmd.c_str());
    CliOutcome o;
    o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.err = slurp(errfile);
    std::filesystem::remove(errfile);
    return o;
}

std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace meshquilt::test
