// labels: e2e
// The `meshquilt plane` command as a user runs it: exit codes, messages, atomic output, determinism.

#include "support/cli_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

using Outcome = meshquilt::test::CliOutcome;
using meshquilt::test::slurp;

Outcome run(const std::string& args) { return meshquilt::test::run_cli(args); }

class CliPlane : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("mq_cli_plane_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        swatch = std::string(MQ_SWATCH_DIR) + "/pebbles.obj";
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
    std::string swatch;
};

TEST_F(CliPlane, SameSeedGivesByteIdenticalFiles) {
    const fs::path a = dir / "a.obj", b = dir / "b.obj", c = dir / "c.obj", report = dir / "r.json";
    ASSERT_EQ(run("plane " + swatch + " --size 30 30 --seed 4 -o " + a.string() + " --report " + report.string()).code, 0);
    ASSERT_EQ(run("plane " + swatch + " --size 30 30 --seed 4 -o " + b.string()).code, 0);
    ASSERT_EQ(run("plane " + swatch + " --size 30 30 --seed 5 -o " + c.string()).code, 0);
    const std::string sa = slurp(a);
    EXPECT_GT(sa.size(), 1000u);
    EXPECT_EQ(sa, slurp(b));
    EXPECT_NE(sa, slurp(c));
    // One `o` group per element, and the report agrees with the file.
    const auto j = nlohmann::json::parse(slurp(report));
    std::size_t groups = 0, pos = 0;
    while ((pos = sa.find("\no ", pos)) != std::string::npos) {
        ++groups;
        ++pos;
    }
    EXPECT_EQ(static_cast<int>(groups), j.at("elements").get<int>());
    for (const char* key : {"faces", "elements", "elements_closed", "elements_removed", "elements_crowded_out", "seconds"}) EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_TRUE(j.at("seconds").contains("matching"));
    EXPECT_TRUE(j.at("seconds").contains("merging"));
}

TEST_F(CliPlane, MissingSwatchExitsTwoAndNamesTheFile) {
    const Outcome o = run("plane " + (dir / "nope.obj").string() + " --size 10 10 -o " + (dir / "x.obj").string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("nope.obj"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

TEST_F(CliPlane, SwatchWithoutThinAxisIsRejected) {
    // A closed cube: as thick as it is wide.
    const fs::path cube = dir / "cube.obj";
    std::ofstream(cube) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                           "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
    const Outcome o = run("plane " + cube.string() + " --size 10 10 -o " + (dir / "x.obj").string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("cube.obj"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("thin axis"), std::string::npos) << o.err;
}

TEST_F(CliPlane, AbsurdOptionsAreUsageErrors) {
    const std::string out = (dir / "x.obj").string();
    for (const std::string& opts : {"--size 0 10", "--size -5 10", "--size nan 10", "--size 10", "--size 1e12 1e12", "--size 10 10 --cell 1e9"}) {
        const Outcome o = run("plane " + swatch + " " + opts + " -o " + out);
        EXPECT_EQ(o.code, 2) << opts << ": " << o.err;
        EXPECT_FALSE(o.err.empty()) << opts;
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliPlane, FailedRunLeavesExistingOutputUntouched) {
    const fs::path out = dir / "good.obj";
    std::ofstream(out) << "# a good file\n";
    const fs::path broken = dir / "broken.obj";
    std::ofstream(broken) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";  // index out of range
    const Outcome o = run("plane " + broken.string() + " --size 10 10 -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("broken.obj"), std::string::npos) << o.err;
    EXPECT_EQ(slurp(out), "# a good file\n");
    // No temporary files left behind.
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) (void)e, ++files;
    EXPECT_EQ(files, 2);
}

}  // namespace
