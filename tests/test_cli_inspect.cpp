// labels: e2e
// `meshquilt inspect` as a user runs it: JSON that parses and matches the mesh, a readable text
// report, problems reported without failing, and exit code 2 only for files it cannot read.

#include "meshquilt/io.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace meshquilt {
namespace {

namespace fs = std::filesystem;
namespace shapes = test::shapes;
using nlohmann::json;

struct Outcome {
    int code = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// Single-quoted for the shell.
std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

class CliInspect : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("mq_cli_inspect_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    /// Runs `meshquilt <args>` (already quoted), capturing stdout and stderr.
    Outcome run(const std::string& args) const {
        const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
        const std::string cmd = quote(MQ_CLI_PATH) + " " + args + " >" + quote(out.string()) + " 2>" + quote(err.string());
        const int status = std::system(cmd.c_str());
        Outcome o;
        o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        o.out = slurp(out);
        o.err = slurp(err);
        return o;
    }
    std::string mesh_file(const std::string& name, const Mesh& mesh) const {
        const std::string p = (dir_ / name).string();
        write_mesh(p, mesh);
        return p;
    }
    std::string file(const std::string& name, const std::string& bytes) const {
        const std::string p = (dir_ / name).string();
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }
    fs::path dir_;
};

TEST_F(CliInspect, JsonDescribesATorus) {
    const Mesh torus = shapes::torus(2.0, 0.5, 24, 12);
    const std::string p = mesh_file("my torus.obj", torus);  // a space in the name, too
    const Outcome o = run("inspect " + quote(p) + " --json");
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(o.err, "");
    const json j = json::parse(o.out);
    for (const char* key : {"file", "faces", "vertices", "unreferenced_vertices", "bbox", "thin_axis", "elements", "elements_closed",
                            "genus", "boundary_loops", "boundary_edges", "non_manifold_edges", "non_manifold_vertices",
                            "inconsistent_edges", "degenerate_faces", "duplicate_vertices", "problems"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["file"], p);
    EXPECT_EQ(j["faces"], torus.num_faces());
    EXPECT_EQ(j["vertices"], torus.num_vertices());
    EXPECT_EQ(j["unreferenced_vertices"], 0);
    EXPECT_NEAR(j["bbox"]["min"][0].get<double>(), -2.5, 1e-12);
    EXPECT_NEAR(j["bbox"]["max"][2].get<double>(), 0.5, 1e-12);
    EXPECT_EQ(j["thin_axis"]["axis"], "z");
    EXPECT_NEAR(j["thin_axis"]["thickness"].get<double>(), 1.0, 1e-12);
    EXPECT_EQ(j["thin_axis"]["is_thin"], true);
    ASSERT_EQ(j["elements"].size(), 1u);
    const json& e = j["elements"][0];
    EXPECT_EQ(e["faces"], torus.num_faces());
    EXPECT_EQ(e["vertices"], torus.num_vertices());
    EXPECT_EQ(e["closed"], true);
    EXPECT_EQ(e["genus"], 1);
    EXPECT_EQ(e["boundary_loops"], 0);
    EXPECT_GT(e["area"].get<double>(), 0.0);
    EXPECT_GT(e["volume"].get<double>(), 0.0);
    EXPECT_EQ(j["elements_closed"], 1);
    EXPECT_EQ(j["genus"], 1);
    EXPECT_EQ(j["boundary_edges"], 0);
    EXPECT_EQ(j["problems"], json::array());
}

TEST_F(CliInspect, BrokenMeshIsReportedNotFatal) {
    // Two voxels sharing an edge (non-manifold), plus a far triangle with a repeated corner, plus
    // an open square with one face flipped, plus an unreferenced vertex.
    Mesh m = shapes::concat(shapes::voxels({{0, 0, 0}, {1, 1, 0}}), shapes::translated(shapes::grid(2), Vec3(5, 0, 0)));
    std::swap(m.faces.back()[1], m.faces.back()[2]);
    m.faces.emplace_back(0, 0, 1);
    m.vertices.emplace_back(50.0, 50.0, 50.0);
    const std::string p = mesh_file("broken.obj", m);
    const Outcome o = run("inspect " + quote(p) + " --json");
    ASSERT_EQ(o.code, 0) << o.err;
    const json j = json::parse(o.out);
    EXPECT_EQ(j["non_manifold_edges"], 1);
    EXPECT_EQ(j["degenerate_faces"], 1);
    EXPECT_GT(j["inconsistent_edges"].get<int>(), 0);
    EXPECT_EQ(j["unreferenced_vertices"], 1);
    EXPECT_EQ(j["elements"].size(), 2u);
    EXPECT_EQ(j["elements"][1]["volume"], nullptr);  // open: no volume
    EXPECT_EQ(j["elements"][1]["boundary_loops"], 1);
    const std::string problems = j["problems"].dump();
    EXPECT_NE(problems.find("1 non-manifold edge (first between vertices"), std::string::npos) << problems;
    EXPECT_NE(problems.find("1 degenerate face"), std::string::npos) << problems;
    EXPECT_NE(problems.find("inconsistent orientation"), std::string::npos) << problems;

    const Outcome text = run("inspect " + quote(p));
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("problems (3):\n  - 1 degenerate face"), std::string::npos) << text.out;
}

TEST_F(CliInspect, TextReportOfACube) {
    const std::string p = mesh_file("cube.stl", shapes::cube(2.0));
    const Outcome o = run("inspect " + quote(p));
    ASSERT_EQ(o.code, 0) << o.err;
    for (const char* line : {"faces           12\n", "vertices        8 (0 unreferenced)\n",
                             "bounding box    [0, 0, 0] to [2, 2, 2], size 2 x 2 x 2\n",
                             "thin axis       z, thickness 2: not a swatch slab (more than half the middle extent, 2)\n",
                             "elements        1, 1 closed; faces per element: min 12, median 12, max 12\n", "genus           0\n",
                             "boundary        0 loops, 0 edges\n", "problems: none\n"})
        EXPECT_NE(o.out.find(line), std::string::npos) << "missing: " << line << "in:\n" << o.out;
}

TEST_F(CliInspect, TextListsTwentyElementsJsonListsAll) {
    Mesh m;
    for (int i = 0; i < 25; ++i) m = shapes::concat(m, shapes::cube(0.5, Vec3(i, 0, 0)));
    const std::string p = mesh_file("many.ply", m);
    const Outcome text = run("inspect " + quote(p));
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("elements (first 20 of 25; --json lists all)"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("\n      19 "), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("\n      20 "), std::string::npos) << text.out;
    const Outcome o = run("inspect " + quote(p) + " --json");
    ASSERT_EQ(o.code, 0) << o.err;
    const json j = json::parse(o.out);
    EXPECT_EQ(j["elements"].size(), 25u);
    EXPECT_EQ(j["elements_closed"], 25);
    EXPECT_NEAR(j["elements"][24]["volume"].get<double>(), 0.125, 1e-12);
}

TEST_F(CliInspect, UnparsableFileExitsWithTwoAndNamesIt) {
    const std::string p = file("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    const Outcome o = run("inspect " + quote(p) + " --json");
    EXPECT_EQ(o.code, 2);
    EXPECT_EQ(o.out, "");
    EXPECT_NE(o.err.find("meshquilt: error: " + p + ":3: face index 3 out of range (the file has 2 vertices)"), std::string::npos) << o.err;
}

TEST_F(CliInspect, MissingFileExitsWithTwo) {
    const std::string p = (dir_ / "nothing.obj").string();
    const Outcome o = run("inspect " + quote(p));
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find(p + ": cannot open: No such file or directory"), std::string::npos) << o.err;
}

TEST_F(CliInspect, UnknownExtensionAndMissingArgumentExitWithTwo) {
    const std::string p = file("mesh.txt", "hello");
    const Outcome o = run("inspect " + quote(p));
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("unknown mesh file extension '.txt'"), std::string::npos) << o.err;
    EXPECT_EQ(run("inspect").code, 2);
}

}  // namespace
}  // namespace meshquilt
