// labels: e2e
// The main job as a user runs it, `meshquilt BASE SWATCH -o OUT`: exit codes, messages, groups,
// report, atomic output, determinism.

#include "core/triangle_index.h"
#include "meshquilt/io.h"
#include "support/cli_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
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
using meshquilt::Vec3;

Outcome run(const std::string& args) { return meshquilt::test::run_cli(args); }

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t pos = 0; (pos = text.find(what, pos)) != std::string::npos; ++pos) ++n;
    return n;
}

class CliSurface : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("mq_cli_surface_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        base = std::string(MQ_TEST_DATA_DIR) + "/surface/eight.obj";
        swatch = std::string(MQ_SWATCH_DIR) + "/rivets.obj";
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
    std::string base, swatch;
};

TEST_F(CliSurface, MainJobWritesGroupsAndReportAndIsDeterministic) {
    const fs::path a = dir / "a.obj", b = dir / "b.obj", c = dir / "c.obj", report = dir / "r.json";
    const std::string common = base + " " + swatch + " --scale 0.3 --with-base";
    const auto first = run(common + " --seed 3 -o " + a.string() + " --report " + report.string());
    ASSERT_EQ(first.code, 0);
    ASSERT_EQ(run("surface " + common + " --seed 3 -o " + b.string()).code, 0);  // the explicit form
    ASSERT_EQ(run(common + " --seed 4 -o " + c.string()).code, 0);
    const std::string sa = slurp(a);
    EXPECT_EQ(sa, slurp(b));
    EXPECT_NE(sa, slurp(c));
    const auto j = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(count(sa, "\no element_"), j.at("elements").get<int>());
    EXPECT_EQ(count(sa, "\no base\n"), 1);
    // The base group holds the base's 634 faces.
    const std::size_t at = sa.find("\no base\n");
    EXPECT_EQ(count(sa.substr(at), "\nf "), 634);
    EXPECT_DOUBLE_EQ(j.at("surface").at("coverage").get<double>(), 1.0);
    for (const char* key : {"faces", "elements", "elements_closed", "elements_removed", "seconds"}) EXPECT_TRUE(j.contains(key)) << key;
    for (const char* key : {"region_density_min", "region_density_max", "region_density_mid_min", "region_density_mid_max", "region_count_density_min",
                            "region_count_density_max", "region_count_density_mid_min", "region_count_density_mid_max", "region_count_density_min_at",
                            "region_count_density_max_at",
                            "base_faces", "symmetry", "rings_swapped"})
        EXPECT_TRUE(j.at("surface").contains(key)) << key;
    // Rivets are counted (whole elements): the count is reported, its range in order.
    EXPECT_GT(j.at("surface").at("region_count_density_min").get<double>(), 0.0);
    EXPECT_LE(j.at("surface").at("region_count_density_min").get<double>(), j.at("surface").at("region_count_density_max").get<double>());
    // Every rivet measured against its swatch element, none off by more than 1.5 (the acceptance).
    EXPECT_EQ(j.at("surface").at("elements_sized").get<int>(), j.at("elements").get<int>());
    EXPECT_EQ(j.at("surface").at("elements_off_size").get<int>(), 0);
    EXPECT_GE(j.at("surface").at("element_size_min").get<double>(), 1.0 / 1.5);
    EXPECT_LE(j.at("surface").at("element_size_min").get<double>(), j.at("surface").at("element_size_max").get<double>());
    EXPECT_LE(j.at("surface").at("element_size_max").get<double>(), 1.5);
    // A point of the base in the thinnest region: on the eight's surface (its centre, or an unset
    // origin, is not).
    const auto& at_json = j.at("surface").at("region_density_min_at");
    ASSERT_EQ(at_json.size(), 3u);
    const meshquilt::Vec3 thinnest(at_json[0].get<double>(), at_json[1].get<double>(), at_json[2].get<double>());
    const meshquilt::Mesh eight = meshquilt::read_mesh(base);
    EXPECT_LT(meshquilt::TriangleIndex(eight).closest(thinnest).distance, 1e-9 * meshquilt::bounding_box(eight).size().norm()) << thinnest.transpose();
    EXPECT_GT(meshquilt::TriangleIndex(eight).closest(meshquilt::Vec3::Zero()).distance, 0.01);
    // The closing line gives the regions' densities (by area, on the middle surface, by count) and
    // the thinnest one's place, as the report has them.
    char summary[400];
    const auto& sj = j.at("surface");
    std::snprintf(summary, sizeof summary,
                  "regions at %.3g-%.3g of the swatch's density (%.3g-%.3g on the shell's middle surface; by count %.3g-%.3g; thinnest around %.4g, %.4g, %.4g) -> ",
                  sj.at("region_density_min").get<double>(), sj.at("region_density_max").get<double>(), sj.at("region_density_mid_min").get<double>(),
                  sj.at("region_density_mid_max").get<double>(), sj.at("region_count_density_min").get<double>(),
                  sj.at("region_count_density_max").get<double>(), sj.at("region_density_min_at")[0].get<double>(),
                  sj.at("region_density_min_at")[1].get<double>(), sj.at("region_density_min_at")[2].get<double>());
    EXPECT_NE(first.err.find(summary), std::string::npos) << first.err;
    // The scale given is the scale used, and the output file's header records it.
    EXPECT_DOUBLE_EQ(j.at("surface").at("scale").get<double>(), 0.3);
    EXPECT_NE(sa.find("--scale 0.3 --seed 3"), std::string::npos);
    EXPECT_EQ(j.at("elements_closed").get<int>(), j.at("elements").get<int>());
    // The shell map is the default embedding; its report (issue 4).
    EXPECT_EQ(j.at("surface").at("embedding").get<std::string>(), "shell");
    const double before = j.at("stretch_l2_initial").get<double>(), after = j.at("stretch_l2_final").get<double>();
    EXPECT_GE(before, 1.0);
    EXPECT_GE(after, 1.0);
    EXPECT_LE(after, before);
    for (const char* key : {"tetrahedra", "charts", "height_limited_vertices", "height_limited_regions", "inverted_tetrahedra", "min_height_ratio"})
        EXPECT_TRUE(j.at("shell").contains(key)) << key;
    EXPECT_EQ(j.at("shell").at("inverted_tetrahedra").get<int>(), 0);
}

TEST_F(CliSurface, NormalEmbeddingOnRequestDiffersAndHasNoShellReport) {
    const fs::path a = dir / "a.obj", b = dir / "b.obj", report = dir / "r.json";
    const std::string common = base + " " + swatch + " --scale 0.3 --seed 2";
    ASSERT_EQ(run(common + " -o " + a.string()).code, 0);
    // (Global flags may come after the command's arguments.)
    ASSERT_EQ(run(common + " --embed normal -o " + b.string() + " --report " + report.string() + " -q").code, 0);
    EXPECT_NE(slurp(a), slurp(b));
    const auto j = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(j.at("surface").at("embedding").get<std::string>(), "normal");
    EXPECT_FALSE(j.contains("stretch_l2_final"));
    EXPECT_FALSE(j.contains("shell"));
}

TEST_F(CliSurface, BadInputsExitTwoNameTheFileAndWriteNothing) {
    const fs::path out = dir / "out.obj";
    // Missing base.
    Outcome o = run((dir / "nope.obj").string() + " " + swatch + " -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("nope.obj"), std::string::npos) << o.err;
    // A non-manifold base: three triangles on one edge.
    const fs::path fin = dir / "fin.obj";
    std::ofstream(fin) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    o = run(fin.string() + " " + swatch + " -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("fin.obj"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("non-manifold"), std::string::npos) << o.err;
    // A bow tie (two triangles sharing only a vertex): --repair would split the vertex.
    const fs::path bow = dir / "bowtie.obj";
    std::ofstream(bow) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n";
    o = run(bow.string() + " " + swatch + " -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("bowtie.obj: 1 non-manifold vertex (first: vertex 0"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("pass --repair to split"), std::string::npos) << o.err;
    // Empty base file.
    const fs::path empty = dir / "empty.obj";
    std::ofstream(empty) << "# nothing\n";
    o = run(empty.string() + " " + swatch + " -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("empty.obj"), std::string::npos) << o.err;
    // Absurd scales and options.
    for (const std::string& opts : {"--scale 0", "--scale -1", "--scale nan", "--scale 1e-6", "--swatch-size -2", "--height -1",
                                    "--symmetry 5", "--embed bogus", "--scale 0.1 --swatch-size 1"}) {
        o = run(base + " " + swatch + " " + opts + " -o " + out.string());
        EXPECT_EQ(o.code, 2) << opts << ": " << o.err;
        EXPECT_FALSE(o.err.empty()) << opts;
    }
    // A malformed field file: file and line named.
    const fs::path field = dir / "field.txt";
    std::ofstream(field) << "face 0 1 0 0\nface 1 1 0\n";
    o = run(base + " " + swatch + " --field " + field.string() + " -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_NE(o.err.find("field.txt:2"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliSurface, FailedRunLeavesExistingOutputUntouched) {
    const fs::path out = dir / "good.obj";
    std::ofstream(out) << "# a good file\n";
    const Outcome o = run(base + " " + swatch + " --scale 1e-6 -o " + out.string());
    EXPECT_EQ(o.code, 2);
    EXPECT_EQ(slurp(out), "# a good file\n");
}

/// Copies the OBJ `from` to `to` with every `every`-th face (the first, then every `every`-th after
/// it) reversed.
void write_with_faces_reversed(const std::string& from, const fs::path& to, int every) {
    std::ifstream in(from);
    std::ofstream out(to);
    std::string line;
    int f = 0;
    while (std::getline(in, line)) {
        if (line.rfind("f ", 0) == 0 && f++ % every == 0) {
            std::istringstream ss(line.substr(2));
            std::string a, b, c;
            ss >> a >> b >> c;
            out << "f " << a << " " << c << " " << b << "\n";
        } else {
            out << line << "\n";
        }
    }
}

TEST_F(CliSurface, InsideOutBaseIsDecoratedWithAWarning) {
    // The eight with every face reversed.
    write_with_faces_reversed(base, dir / "flipped.obj", 1);
    const Outcome o = run((dir / "flipped.obj").string() + " " + swatch + " --scale 0.3 -o " + (dir / "o.obj").string());
    EXPECT_EQ(o.code, 0) << o.err;
    EXPECT_NE(o.err.find("facing inwards"), std::string::npos) << o.err;
    // Said once, by the stage that flips it: no advice to pass --repair for what is already done.
    EXPECT_EQ(o.err.find("inside out"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("--repair"), std::string::npos) << o.err;
}

TEST_F(CliSurface, InconsistentlyOrientedBaseIsReorientedWithAWarning) {
    // The eight with every third face reversed: its faces disagree about their sides.
    const fs::path partly = dir / "partly.obj";
    write_with_faces_reversed(base, partly, 3);
    const fs::path o_path = dir / "o.obj", ref_path = dir / "ref.obj";
    Outcome o = run(partly.string() + " " + swatch + " --scale 0.3 --seed 1 -o " + o_path.string());
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(count(o.err, "reoriented"), 1) << o.err;
    EXPECT_NE(o.err.find("meshquilt: warning: " + partly.string() + ": reoriented 212 faces to fix "), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("inconsistent orientation"), std::string::npos) << o.err;
    // Each piece keeps the side most of its faces face: the eight itself again (a reversed face
    // a c b flips back to a b c), so the decoration is the eight's, byte for byte after the
    // header's command line (which names the base file). Compared as a whole: gtest's line diff
    // of two files this large does not fit in memory.
    o = run(base + " " + swatch + " --scale 0.3 --seed 1 -o " + ref_path.string());
    ASSERT_EQ(o.code, 0) << o.err;
    const auto body = [](const fs::path& p) {
        const std::string text = slurp(p);
        return text.substr(std::min(text.size(), text.find('\n')));
    };
    const std::string reference = body(ref_path);
    EXPECT_GT(reference.size(), 1000u);
    EXPECT_TRUE(body(o_path) == reference);
    // With --repair the same reorientation is listed as a repair, once, naming the file once.
    fs::remove(o_path);
    o = run(partly.string() + " " + swatch + " --scale 0.3 --seed 1 --repair -o " + o_path.string());
    EXPECT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(count(o.err, "reoriented"), 1) << o.err;
    EXPECT_NE(o.err.find("meshquilt: repaired " + partly.string() + ": reoriented "), std::string::npos) << o.err;
    EXPECT_TRUE(body(o_path) == reference);
}

TEST_F(CliSurface, NonOrientableBaseIsRefused) {
    // A Moebius strip (12 quads, half a twist): no orientation of its faces agrees.
    const fs::path strip = dir / "moebius.obj";
    {
        std::ofstream out(strip);
        const int n = 12;
        for (int i = 0; i < n; ++i) {
            const double u = 2.0 * M_PI * i / n;
            const Vec3 c(2.0 * std::cos(u), 2.0 * std::sin(u), 0.0);
            const Vec3 d = std::cos(u / 2) * Vec3(std::cos(u), std::sin(u), 0.0) + std::sin(u / 2) * Vec3::UnitZ();
            for (const Vec3& v : {Vec3(c - 0.5 * d), Vec3(c + 0.5 * d)}) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
        }
        for (int i = 0; i < n; ++i) {
            const int a = 2 * i + 1, b = 2 * i + 2;  // 1-based
            const int c = i + 1 < n ? 2 * (i + 1) + 1 : 2, e = i + 1 < n ? 2 * (i + 1) + 2 : 1;
            out << "f " << a << " " << c << " " << e << "\nf " << a << " " << e << " " << b << "\n";
        }
    }
    const fs::path o_path = dir / "o.obj";
    const Outcome o = run(strip.string() + " " + swatch + " --scale 0.3 -o " + o_path.string());
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_NE(o.err.find(strip.string() + ": "), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("not orientable"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(o_path));
}

}  // namespace
