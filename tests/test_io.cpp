// labels: unit
// Mesh readers and writers: fixtures in every supported format, exact round trips, one test per
// malformed-input message, atomic writes, and robustness against truncated and random input.

#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "support/expect_error.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <iostream>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace meshquilt {
namespace {

namespace fs = std::filesystem;
namespace shapes = test::shapes;

const std::string kData = std::string(MQ_TEST_DATA_DIR) + "/io/";

/// A fresh directory per test, removed afterwards.
class IoTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = "mq_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid());
        std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests have '/' in their names
        dir_ = fs::temp_directory_path() / name;
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write(const std::string& name, const std::string& bytes) const {
        const std::string p = path(name);
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }
    std::vector<std::string> listing() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    fs::path dir_;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

using test::throws_with;

::testing::AssertionResult read_fails(const std::string& path, const std::vector<std::string>& fragments) {
    return throws_with<InvalidInput>([&] { read_mesh(path); }, fragments);
}

/// Faces as position triples, each rotated to start at its smallest corner (orientation kept), sorted.
using Corner = std::array<double, 3>;
std::vector<std::array<Corner, 3>> canonical_faces(const Mesh& m) {
    std::vector<std::array<Corner, 3>> out;
    for (const Tri& t : m.faces) {
        std::array<Corner, 3> f;
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = m.vertices[static_cast<std::size_t>(t[k])];
            f[static_cast<std::size_t>(k)] = {p.x(), p.y(), p.z()};
        }
        std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
        out.push_back(f);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Fan triangulation of the cube fixture's quads, with the vertex order of shapes::cube().
Mesh fixture_cube() { return shapes::cube(); }

// ---------------------------------------------------------------- readers on fixtures

class FixtureTest : public ::testing::TestWithParam<const char*> {};

TEST_P(FixtureTest, ReadsTheUnitCube) {
    const Mesh m = read_mesh(kData + GetParam());
    EXPECT_EQ(m.num_vertices(), 8u);
    ASSERT_EQ(m.num_faces(), 12u);
    EXPECT_EQ(canonical_faces(m), canonical_faces(fixture_cube()));
    const MeshAnalysis a = analyse(m);
    ASSERT_EQ(a.elements.size(), 1u);
    EXPECT_TRUE(a.elements[0].closed);
    EXPECT_EQ(a.genus, 0);
    EXPECT_DOUBLE_EQ(a.elements[0].volume, 1.0);
    EXPECT_TRUE(a.problems.empty()) << a.problems.front();
}

INSTANTIATE_TEST_SUITE_P(AllFormats, FixtureTest,
                         ::testing::Values("cube_mixed.obj", "cube.off", "cube_ascii.ply", "cube_binary_le.ply",
                                           "cube_binary_be.ply", "cube_ascii.stl", "cube_binary_solid.stl"));

TEST(ReadObj, KeepsVertexOrderAndFanTriangulatesQuads) {
    const Mesh m = read_mesh(kData + "cube_mixed.obj");
    EXPECT_EQ(m.vertices, fixture_cube().vertices);
    // "f 1/1/1 3/4/1 4/3/1 2/2/1" -> (0 2 3) (0 3 1); "f -6 -2 -1 -5" -> (2 6 7) (2 7 3)
    EXPECT_EQ(m.faces[0], Tri(0, 2, 3));
    EXPECT_EQ(m.faces[1], Tri(0, 3, 1));
    EXPECT_EQ(m.faces[6], Tri(2, 6, 7));
    EXPECT_EQ(m.faces[7], Tri(2, 7, 3));
}

TEST_F(IoTest, ExtensionIsCaseInsensitive) {
    const std::string p = path("CUBE.Obj");
    fs::copy_file(kData + "cube_mixed.obj", p);
    EXPECT_EQ(read_mesh(p).num_faces(), 12u);
    const std::string q = path("cube.PLY");
    fs::copy_file(kData + "cube_binary_le.ply", q);
    EXPECT_EQ(read_mesh(q).num_faces(), 12u);
}

TEST_F(IoTest, ObjAllowsForwardReferencesAndKeepsUnreferencedVertices) {
    const Mesh m = read_mesh(write("fwd.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\n"));
    EXPECT_EQ(m.num_vertices(), 4u);
    EXPECT_EQ(m.faces.at(0), Tri(0, 1, 2));
}

TEST_F(IoTest, ObjReadsExtremeNumbers) {
    const Mesh m = read_mesh(write("num.obj", "v 1e-320 -0 1.7976931348623157e308\nv -1E+3 .5 5.\nv +2 1e-400 0\nf 1 2 3\n"));
    ASSERT_EQ(m.num_vertices(), 3u);
    EXPECT_EQ(m.vertices[0].x(), 1e-320);  // subnormal, kept exactly
    EXPECT_EQ(m.vertices[0].y(), 0.0);
    EXPECT_TRUE(std::signbit(m.vertices[0].y()));
    EXPECT_EQ(m.vertices[0].z(), std::numeric_limits<double>::max());
    EXPECT_EQ(m.vertices[1], Vec3(-1000.0, 0.5, 5.0));
    EXPECT_EQ(m.vertices[2], Vec3(2.0, 0.0, 0.0));  // underflow reads as zero, like strtod
    EXPECT_TRUE(read_fails(write("hex.obj", "v 0x1 0 0\n"), {"hex.obj:1: cannot read vertex coordinate '0x1'"}));
    EXPECT_TRUE(read_fails(write("sign.obj", "v +-1 0 0\n"), {"sign.obj:1: cannot read vertex coordinate '+-1'"}));
}

TEST_F(IoTest, PlyTriangleStripsAreDecoded) {
    // Two strips: 0 1 2 3 (two triangles) and 4 5 6 (one); -1 separates them.
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\n"
                            "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n"
                            "8 0 1 2 3 -1 4 5 6\n";
    const Mesh m = read_mesh(write("strips.ply", ply));
    ASSERT_EQ(m.num_faces(), 3u);
    EXPECT_EQ(m.faces[0], Tri(0, 1, 2));
    EXPECT_EQ(m.faces[1], Tri(2, 1, 3));  // odd window flipped: same winding as the first
    EXPECT_EQ(m.faces[2], Tri(4, 5, 6));
}

// ---------------------------------------------------------------- round trips

/// Coordinates that stress formatting: tiny, huge, subnormal, negative zero, non-terminating binary fractions.
Mesh awkward_mesh() {
    Mesh m = shapes::torus(2.0, 0.5, 9, 7);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double specials[] = {0.1, -0.0, 1e-300, 4.9e-324, 1.7976931348623157e308, -2.2250738585072014e-308,
                               3.141592653589793, 1.0 / 3.0, 123456789.123456789, -1e22};
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double r = unit(rng);
            m.vertices[i][k] = (i * 3 + static_cast<std::size_t>(k)) % 4 == 0 ? specials[(i + static_cast<std::size_t>(k)) % 10]
                                                                                : r * std::pow(10.0, static_cast<int>(i % 20) - 10);
        }
    m.vertices.emplace_back(9.0, 9.0, 9.0);  // unreferenced: OBJ and PLY keep it
    return m;
}

bool bitwise_equal(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

TEST_F(IoTest, ObjRoundTripIsBitExact) {
    const Mesh m = awkward_mesh();
    write_mesh(path("m.obj"), m);
    const Mesh r = read_mesh(path("m.obj"));
    EXPECT_TRUE(bitwise_equal(r.vertices, m.vertices));
    EXPECT_EQ(r.faces, m.faces);
    // Deterministic: writing again gives the same bytes.
    write_mesh(path("m2.obj"), r);
    EXPECT_EQ(slurp(path("m.obj")), slurp(path("m2.obj")));
}

TEST_F(IoTest, PlyRoundTripIsBitExact) {
    const Mesh m = awkward_mesh();
    write_mesh(path("m.ply"), m, {{}, "first line\nsecond line"});
    const Mesh r = read_mesh(path("m.ply"));
    EXPECT_TRUE(bitwise_equal(r.vertices, m.vertices));
    EXPECT_EQ(r.faces, m.faces);
    const std::string bytes = slurp(path("m.ply"));
    EXPECT_NE(bytes.find("format binary_little_endian 1.0\ncomment first line\ncomment second line\n"), std::string::npos);
    EXPECT_NE(bytes.find("property double x\n"), std::string::npos);
    EXPECT_NE(bytes.find("property list uchar int vertex_indices\nend_header\n"), std::string::npos);
}

TEST_F(IoTest, StlRoundTripIsFloatExactAndMergesCorners) {
    const Mesh m = shapes::torus(2.0, 0.5 + 1e-9, 12, 8);  // coordinates that float rounds
    write_mesh(path("m.stl"), m, {{}, "solid-looking comment"});
    const std::string bytes = slurp(path("m.stl"));
    ASSERT_EQ(bytes.size(), 84 + 50 * m.num_faces());
    EXPECT_NE(bytes.substr(0, 5), "solid");
    const Mesh r = read_mesh(path("m.stl"));
    EXPECT_EQ(r.num_vertices(), m.num_vertices());  // shared corners merged back
    ASSERT_EQ(r.num_faces(), m.num_faces());
    // Every facet comes back with its corners rounded to float, in its corner order. The writer
    // may move one facet to the front (so that ADMesh sees a binary file), so compare sorted lists.
    const auto corners = [](const Mesh& mesh, bool round) {
        std::vector<std::array<double, 9>> out;
        for (const Tri& t : mesh.faces) {
            std::array<double, 9> a{};
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) {
                    const double v = mesh.vertices[static_cast<std::size_t>(t[k])][c];
                    a[static_cast<std::size_t>(3 * k + c)] = round ? static_cast<double>(static_cast<float>(v)) : v;
                }
            out.push_back(a);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(corners(r, false), corners(m, true));
    const MeshAnalysis a = analyse(r);
    EXPECT_EQ(a.closed_elements(), 1);
    EXPECT_EQ(a.genus, 1);
}

TEST_F(IoTest, StlNormalsAreUnitAndOutward) {
    write_mesh(path("c.stl"), shapes::cube());
    const std::string bytes = slurp(path("c.stl"));
    float n[3];
    std::memcpy(n, bytes.data() + 84, sizeof n);  // first face: the z = 0 side
    EXPECT_EQ(n[0], 0.0f);
    EXPECT_EQ(n[1], 0.0f);
    EXPECT_EQ(n[2], -1.0f);
}

TEST_F(IoTest, ObjGroupsFacesByElement) {
    const Mesh m = shapes::concat(shapes::cube(), shapes::translated(shapes::cube(), Vec3(3, 0, 0)));
    std::vector<int> element(m.num_faces());
    for (std::size_t f = 0; f < element.size(); ++f) element[f] = static_cast<int>(f % 2 ? 0 : 7);  // interleaved
    WriteOptions options;
    options.element_of_face = element;
    options.comment = "two cubes\nfor the test";
    write_mesh(path("g.obj"), m, options);
    const std::string text = slurp(path("g.obj"));
    EXPECT_EQ(text.rfind("# two cubes\n# for the test\n", 0), 0u) << text.substr(0, 80);
    const std::size_t g0 = text.find("\no element_0\n"), g7 = text.find("\no element_7\n");
    ASSERT_NE(g0, std::string::npos);
    ASSERT_NE(g7, std::string::npos);
    EXPECT_LT(g0, g7);
    EXPECT_EQ(text.find("o element_0", g0 + 2), std::string::npos) << "element 0 written as more than one group";
    // Read back: the faces of element 0 in their order, then those of element 7.
    const Mesh r = read_mesh(path("g.obj"));
    ASSERT_EQ(r.num_faces(), m.num_faces());
    std::vector<Tri> expected;
    for (int want : {0, 7})
        for (std::size_t f = 0; f < m.faces.size(); ++f)
            if (element[f] == want) expected.push_back(m.faces[f]);
    EXPECT_EQ(r.faces, expected);
    EXPECT_TRUE(bitwise_equal(r.vertices, m.vertices));
}

TEST_F(IoTest, WritersRejectMeshesTheyCannotWriteFaithfully) {
    write_file_atomic(path("keep.obj"), "old");
    Mesh bad = shapes::cube();
    bad.faces[3][1] = 8;
    EXPECT_TRUE(throws_with<InvalidInput>([&] { write_mesh(path("keep.obj"), bad); },
                                          {"keep.obj", "face 3", "vertex index 8 out of range", "8 vertices"}));
    Mesh nan = shapes::cube();
    nan.vertices[5].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(throws_with<InvalidInput>([&] { write_mesh(path("keep.obj"), nan); }, {"vertex 5", "non-finite"}));
    WriteOptions options;
    options.element_of_face = {0, 1};
    EXPECT_TRUE(throws_with<InvalidInput>([&] { write_mesh(path("keep.obj"), shapes::cube(), options); },
                                          {"element_of_face has 2 entries for 12 faces"}));
    EXPECT_TRUE(throws_with<IoError>([&] { write_mesh(path("x.gltf"), shapes::cube()); }, {"x.gltf", "'.gltf'"}));
    EXPECT_EQ(slurp(path("keep.obj")), "old");
    EXPECT_EQ(listing(), std::vector<std::string>{"keep.obj"});
}

TEST_F(IoTest, LargeObjReadsInWellUnderASecond) {
    // The size of igea.obj: 270k faces, about 11 MB of text.
    const Mesh m = shapes::torus(2.0, 0.5, 600, 225);
    ASSERT_EQ(m.num_faces(), 270000u);
    write_mesh(path("big.obj"), m);
    EXPECT_GT(fs::file_size(path("big.obj")), 8u << 20);
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh r = read_mesh(path("big.obj"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(bitwise_equal(r.vertices, m.vertices));
    EXPECT_EQ(r.faces, m.faces);
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
    EXPECT_LT(seconds, 1.0) << "reading 270k faces took " << seconds << " s";  // about 0.1 s on one core
#else
    std::cout << "unoptimised build: read took " << seconds << " s (not checked)\n";
#endif
}

// ---------------------------------------------------------------- read errors

TEST_F(IoTest, MissingFileIsAnIoError) {
    const std::string p = path("nope.obj");
    EXPECT_TRUE(throws_with<IoError>([&] { read_mesh(p); }, {p + ": cannot open: No such file or directory"}));
}

TEST_F(IoTest, DirectoryIsAnIoError) {
    fs::create_directory(path("dir.obj"));
    EXPECT_TRUE(throws_with<IoError>([&] { read_mesh(path("dir.obj")); }, {"dir.obj: cannot open: Is a directory"}));
}

TEST_F(IoTest, UnknownExtensionIsAnIoError) {
    const std::string p = write("mesh.xyz", "v 0 0 0\n");
    EXPECT_TRUE(throws_with<IoError>([&] { read_mesh(p); }, {"mesh.xyz", "unknown mesh file extension '.xyz'", ".obj"}));
    const std::string q = write("mesh", "v 0 0 0\n");
    EXPECT_TRUE(throws_with<IoError>([&] { read_mesh(q); }, {"unknown mesh file extension (none)"}));
}

TEST_F(IoTest, ObjFaceIndexOutOfRangeNamesFileAndLine) {
    std::string text = "# header\n";
    for (int i = 0; i < 8; ++i) text += "v " + std::to_string(i) + " 0 " + std::to_string(i * i) + "\n";
    for (int i = 0; i < 7; ++i) text += "f 1 2 3\n";  // lines 10-16
    text += "f 1 2 9\n";                                 // line 17
    const std::string p = write("bad.obj", text);
    EXPECT_TRUE(read_fails(p, {p + ":17: face index 9 out of range (the file has 8 vertices)"}));
}

struct MalformedCase {
    const char* name;
    const char* content;
    std::vector<std::string> fragments;
};

class MalformedTest : public IoTest, public ::testing::WithParamInterface<MalformedCase> {};

TEST_P(MalformedTest, FailsWithMessage) {
    const MalformedCase& c = GetParam();
    const std::string p = write(c.name, c.content);
    std::vector<std::string> fragments;
    for (const std::string& f : c.fragments) fragments.push_back(f.rfind('@', 0) == 0 ? p + f.substr(1) : f);  // '@' = the path
    EXPECT_TRUE(read_fails(p, fragments));
}

/// Test names from the file name without its extension.
std::string case_name(const ::testing::TestParamInfo<MalformedCase>& param) {
    const std::string name = param.param.name;
    return name.substr(0, name.find('.'));
}

const std::string kPlyHead = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

INSTANTIATE_TEST_SUITE_P(
    Obj, MalformedTest,
    ::testing::Values(
        MalformedCase{"nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n", {"@:3: non-finite vertex coordinate 'nan'"}},
        MalformedCase{"inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", {"@:2: non-finite vertex coordinate '1e999'"}},
        MalformedCase{"short.obj", "v 0 0 0\nv 1 0\n", {"@:2: vertex needs 3 coordinates"}},
        MalformedCase{"word.obj", "v 0 0 0\nv 1 abc 0\n", {"@:2: cannot read vertex coordinate 'abc'"}},
        MalformedCase{"suffix.obj", "v 0 0 0\nv 1 2.5x 0\n", {"@:2: cannot read vertex coordinate '2.5x'"}},
        MalformedCase{"twocorners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", {"@:3: face with 2 corners (a face needs at least 3)"}},
        MalformedCase{"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", {"@:4: face index 0 is invalid"}},
        MalformedCase{"relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                      {"@:4: relative face index -4 points before the first vertex (3 vertices so far)"}},
        MalformedCase{"corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/a 2 3\n", {"@:4: cannot read face corner '1/a'"}},
        MalformedCase{"corner2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", {"@:4: cannot read face corner '1/1/1/1'"}},
        MalformedCase{"huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", {"@:4: face index 99999999999 out of range"}},
        MalformedCase{"empty.obj", "", {"@: no faces"}},
        MalformedCase{"points.obj", "v 0 0 0\nv 1 0 0\n# no faces here\n", {"@: no faces"}}),
    case_name);

INSTANTIATE_TEST_SUITE_P(
    Off, MalformedTest,
    ::testing::Values(
        MalformedCase{"magic.off", "OFX\n3 1 0\n", {"@:1: not an OFF file: it starts with 'OFX'"}},
        MalformedCase{"binary.off", "OFF BINARY\n", {"@:1: binary OFF is not supported"}},
        MalformedCase{"fourd.off", "4OFF\n3 1 0\n", {"@:1: unsupported OFF variant '4OFF'"}},
        MalformedCase{"counts.off", "OFF\n3 x 0\n", {"@:2: bad face count 'x'"}},
        MalformedCase{"nocounts.off", "OFF\n", {"@: truncated: the header has no vertex count"}},
        MalformedCase{"bigcount.off", "OFF\n2000000000 1 0\n0 0 0\n", {"@: header says 2000000000 vertices, more than a"}},
        MalformedCase{"truncv.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", {"@: truncated: header says 3 vertices, file holds 2"}},
        MalformedCase{"truncf.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                      {"@: truncated: header says 2 faces, file holds 1"}},
        MalformedCase{"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                      {"@:6: face index 3 out of range (the file has 3 vertices)"}},
        MalformedCase{"negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", {"@:6: face index -1 out of range"}},
        MalformedCase{"corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", {"@:6: face with 2 corners"}},
        MalformedCase{"missing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", {"@:6: face has 3 of the 4 indices it announces"}},
        MalformedCase{"nan.off", "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", {"@:4: non-finite vertex coordinate 'inf'"}},
        MalformedCase{"noface.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", {"@: no faces"}}),
    case_name);

INSTANTIATE_TEST_SUITE_P(
    Ply, MalformedTest,
    ::testing::Values(
        MalformedCase{"magic.ply", "plx\nformat ascii 1.0\nend_header\n", {"@: not a PLY file"}},
        MalformedCase{"noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", {"@: truncated header: no 'end_header' line"}},
        MalformedCase{"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", {"@:2: unknown PLY format 'binary_middle_endian'"}},
        MalformedCase{"noformat.ply", "ply\nelement vertex 0\nend_header\n", {"@:3: the header has no 'format' line"}},
        MalformedCase{"type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float128 x\nend_header\n",
                      {"@:4: unknown property type 'float128'"}},
        MalformedCase{"listcount.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n",
                      {"@:4: list count type must be an integer type"}},
        MalformedCase{"orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", {"@:3: property before any element"}},
        MalformedCase{"nox.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float y\nproperty float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n0 0\n0 0\n0 0\n3 0 1 2\n",
                      {"@:3: the vertex element has no scalar 'x' property"}},
        MalformedCase{"nolist.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int corners\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                      {"@:7: the face element has no 'vertex_indices' (or 'vertex_index') list"}},
        MalformedCase{"noface.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n",
                      {"@: no faces"}},
        MalformedCase{"huge.ply",
                      "ply\nformat ascii 1.0\nelement vertex 900000000000\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
                      {"@:3: header says 900000000000 vertex elements (the limit is 2^31 - 1)"}}),
    case_name);

// kPlyHead has 9 header lines: data starts on line 10.
TEST_F(IoTest, AsciiPlyDataErrorsNameTheLine) {
    EXPECT_TRUE(read_fails(write("range.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                           {"range.ply:13: face index 3 out of range (the file has 3 vertices)"}));
    EXPECT_TRUE(read_fails(write("word.ply", kPlyHead + "0 0 0\nabc 0 0\n0 1 0\n3 0 1 2\n"), {"word.ply:11: cannot read number 'abc'"}));
    EXPECT_TRUE(read_fails(write("nan.ply", kPlyHead + "0 nan 0\n1 0 0\n0 1 0\n3 0 1 2\n"), {"nan.ply:10: non-finite vertex coordinate"}));
    EXPECT_TRUE(read_fails(write("trunc.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
                           {"trunc.ply: truncated: header says 1 face elements, file ends in element 0"}));
    EXPECT_TRUE(read_fails(write("short.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n"),
                           {"short.ply: truncated: header says 1 face elements, which need at least 20 bytes, but only 18 bytes "
                            "follow the header"}));
    EXPECT_TRUE(read_fails(write("corners.ply", kPlyHead + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), {"corners.ply:13: face with 2 corners"}));
}

std::string binary_ply_header(const char* format, long long vertices, long long faces) {
    return "ply\nformat " + std::string(format) + " 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string le_floats(std::initializer_list<float> values) {
    std::string s;
    for (float v : values) s.append(reinterpret_cast<const char*>(&v), 4);
    return s;
}

std::string le_face(std::initializer_list<int> idx) {
    std::string s(1, static_cast<char>(idx.size()));
    for (int v : idx) s.append(reinterpret_cast<const char*>(&v), 4);
    return s;
}

TEST_F(IoTest, BinaryPlyErrorsNameTheRecord) {
    const std::string verts = le_floats({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const char* le = "binary_little_endian";
    EXPECT_TRUE(read_fails(write("range.ply", binary_ply_header(le, 3, 2) + verts + le_face({0, 1, 2}) + le_face({0, 1, 7})),
                           {"range.ply: face 1: face index 7 out of range (the file has 3 vertices)"}));
    EXPECT_TRUE(read_fails(write("nan.ply", binary_ply_header(le, 3, 1) +
                                                le_floats({0, 0, 0, 1, std::numeric_limits<float>::infinity(), 0, 0, 1, 0}) +
                                                le_face({0, 1, 2})),
                           {"nan.ply: vertex 1: non-finite vertex coordinate"}));
    EXPECT_TRUE(read_fails(write("trunc.ply", binary_ply_header(le, 3, 2) + verts + le_face({0, 1, 2}) + le_face({0, 1}).substr(0, 6)),
                           {"trunc.ply: face 1: face with 2 corners"}));
    EXPECT_TRUE(read_fails(write("cut.ply", binary_ply_header(le, 3, 2) + verts + le_face({0, 1, 2}) + le_face({0, 1, 2}).substr(0, 7)),
                           {"cut.ply: face 1: list of 3 indices runs past the end of the file"}));
    EXPECT_TRUE(read_fails(write("cutv.ply", binary_ply_header(le, 3, 1) + verts.substr(0, 30)),
                           {"cutv.ply: truncated: header says 3 vertex elements"}));
    // A header that claims more than the file can hold fails before anything is allocated.
    EXPECT_TRUE(read_fails(write("claim.ply", binary_ply_header(le, 2000000000, 1) + verts),
                           {"claim.ply: truncated: header says 2000000000 vertex elements, which need at least 24000000000 bytes, "
                            "but only 36 bytes follow the header"}));
    // A list length beyond the end of the file.
    std::string long_list = binary_ply_header(le, 3, 1);
    long_list.replace(long_list.find("list uchar int"), 14, "list uint int");
    const std::uint32_t n = 1000000000;
    EXPECT_TRUE(read_fails(write("list.ply", long_list + verts + std::string(reinterpret_cast<const char*>(&n), 4) + "abcd"),
                           {"list.ply: face 0: list of 1000000000 indices runs past the end of the file"}));
}

std::string binary_stl(std::uint32_t claimed, std::size_t triangles, float bad = 0.0f) {
    std::string s(80, ' ');
    s.append(reinterpret_cast<const char*>(&claimed), 4);
    for (std::size_t t = 0; t < triangles; ++t) {
        const float rec[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, bad};
        s.append(reinterpret_cast<const char*>(rec), sizeof rec);
        s.append(2, '\0');
    }
    return s;
}

TEST_F(IoTest, StlErrors) {
    EXPECT_TRUE(read_fails(write("x.stl", binary_stl(100, 42)), {"x.stl: truncated: header says 100 triangles, file holds 42"}));
    EXPECT_TRUE(read_fails(write("claim.stl", binary_stl(0xffffffffu, 1)),
                           {"claim.stl: truncated: header says 4294967295 triangles, file holds 1"}));
    EXPECT_TRUE(read_fails(write("short.stl", "not an stl"), {"short.stl: truncated: a binary STL needs an 84-byte header, the file has 10 bytes"}));
    EXPECT_TRUE(read_fails(write("nan.stl", binary_stl(3, 3, std::numeric_limits<float>::quiet_NaN())),
                           {"nan.stl: triangle 0: non-finite vertex coordinate"}));
    EXPECT_TRUE(read_fails(write("zero.stl", binary_stl(0, 0)), {"zero.stl: no faces"}));
    const std::string facet = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
    EXPECT_TRUE(read_fails(write("kw.stl", facet + "vertx 0 1 0\nendloop\nendfacet\nendsolid\n"),
                           {"kw.stl:6: expected 'vertex' or 'endloop', found 'vertx'"}));
    EXPECT_TRUE(read_fails(write("two.stl", facet + "endloop\nendfacet\nendsolid\n"), {"two.stl:6: facet with 2 vertices"}));
    EXPECT_TRUE(read_fails(write("nan2.stl", facet + "vertex 0 NaN 0\nendloop\nendfacet\nendsolid\n"),
                           {"nan2.stl:6: non-finite vertex coordinate 'NaN'"}));
    EXPECT_TRUE(read_fails(write("end.stl", facet + "vertex 0 1 0\nendloop\n"), {"end.stl:", "expected 'endfacet', found the end of the file"}));
    EXPECT_TRUE(read_fails(write("empty.stl", "solid nothing\nendsolid nothing\n"), {"empty.stl: no faces"}));
}

TEST_F(IoTest, StlAsciiWithSeveralSolidsAndPolygonFacets) {
    const std::string text =
        "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
        "endsolid a\nsolid b\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex -0 1 0\nvertex -1 0 0\nendloop\nendfacet\n"
        "endsolid b\n";
    const Mesh m = read_mesh(write("multi.stl", text));
    EXPECT_EQ(m.num_faces(), 3u);    // the quad fan-triangulated, plus one
    EXPECT_EQ(m.num_vertices(), 5u);  // (0,0,0) shared; -0 is 0
}

TEST_F(IoTest, BinaryStlWithTrailingBytesIsRead) {
    std::string s = binary_stl(2, 2) + "trailing junk";
    const Mesh m = read_mesh(write("pad.stl", s));
    EXPECT_EQ(m.num_faces(), 2u);
}

// ---------------------------------------------------------------- atomic writes

TEST_F(IoTest, WriteIntoMissingDirectoryFailsAndCreatesNothing) {
    const std::string p = path("no/such/dir/out.obj");
    EXPECT_TRUE(throws_with<IoError>([&] { write_mesh(p, shapes::cube()); }, {p, "cannot write", "No such file or directory"}));
    EXPECT_FALSE(fs::exists(path("no")));
    EXPECT_TRUE(listing().empty());
}

TEST_F(IoTest, WriteBelowARegularFileFailsAndLeavesItAlone) {
    write("file", "precious");
    const std::string p = path("file/out.ply");
    EXPECT_TRUE(throws_with<IoError>([&] { write_mesh(p, shapes::cube()); }, {p, "Not a directory"}));
    EXPECT_EQ(slurp(path("file")), "precious");
    EXPECT_EQ(listing(), std::vector<std::string>{"file"});
}

TEST_F(IoTest, WriteOverADirectoryFailsAndRemovesTheTemporaryFile) {
    fs::create_directory(path("out.stl"));
    EXPECT_TRUE(throws_with<IoError>([&] { write_mesh(path("out.stl"), shapes::cube()); }, {"out.stl: cannot write"}));
    EXPECT_TRUE(fs::is_directory(path("out.stl")));
    EXPECT_EQ(listing(), std::vector<std::string>{"out.stl"});
}

TEST_F(IoTest, SuccessfulWriteReplacesContentFullyAndLeavesNoTemporaryFiles) {
    write_file_atomic(path("r.json"), std::string(100000, 'x'));
    EXPECT_EQ(fs::file_size(path("r.json")), 100000u);
    write_file_atomic(path("r.json"), "{}\n");
    EXPECT_EQ(slurp(path("r.json")), "{}\n");
    write_mesh(path("m.obj"), shapes::torus());
    write_mesh(path("m.obj"), shapes::cube());
    EXPECT_EQ(read_mesh(path("m.obj")).num_faces(), 12u);
    EXPECT_EQ(listing(), (std::vector<std::string>{"m.obj", "r.json"}));
}

TEST_F(IoTest, ReplacingKeepsPermissions) {
    write_file_atomic(path("p.txt"), "a");
    ASSERT_EQ(::chmod(path("p.txt").c_str(), 0640), 0);
    write_file_atomic(path("p.txt"), "b");
    struct stat st {};
    ASSERT_EQ(::stat(path("p.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);
}

TEST_F(IoTest, WritingThroughASymlinkUpdatesItsTarget) {
    write("real.obj", "old");
    fs::create_symlink("real.obj", path("link.obj"));
    write_mesh(path("link.obj"), shapes::cube());
    EXPECT_TRUE(fs::is_symlink(path("link.obj")));
    EXPECT_EQ(read_mesh(path("real.obj")).num_faces(), 12u);
    EXPECT_EQ(listing(), (std::vector<std::string>{"link.obj", "real.obj"}));
}

TEST_F(IoTest, WritingToANamedPipeStreamsIntoItAndLeavesItAPipe) {
    // A device or a pipe (/dev/stdout, /dev/null, a FIFO) is written in place: renaming a temporary
    // file over it would replace the node with a regular file. The read end is opened first without
    // blocking, so that the write neither waits for a reader nor leaves the test hanging if it misses
    // the pipe; a cube's OBJ fits the pipe's buffer.
    const std::string fifo = path("out.obj");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    write_mesh(fifo, shapes::cube());
    std::string received;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) received.append(buffer, static_cast<std::size_t>(n));
    ::close(fd);
    EXPECT_TRUE(fs::is_fifo(fifo));
    ASSERT_FALSE(received.empty());
    EXPECT_EQ(parse_mesh("out.obj", received).num_faces(), 12u);
    EXPECT_EQ(listing(), std::vector<std::string>{"out.obj"});
}

TEST_F(IoTest, EmptyPathIsAnIoError) {
    EXPECT_TRUE(throws_with<IoError>([&] { write_file_atomic("", "x"); }, {"empty"}));
    EXPECT_TRUE(throws_with<IoError>([&] { write_file_atomic(path("") + "/", "x"); }, {"not a file name"}));
}

// ---------------------------------------------------------------- robustness

/// Parses `bytes` as a file called `name`: success must give a mesh with faces, indices in range
/// and finite coordinates; failure must be a meshquilt::Error. Anything else (another exception, a
/// crash, a sanitizer report) fails the test.
::testing::AssertionResult sane_or_error(const std::string& name, const std::string& bytes, bool* failed = nullptr) {
    try {
        const Mesh m = parse_mesh(name, bytes);
        if (m.faces.empty()) return ::testing::AssertionFailure() << "read a mesh without faces";
        for (const Tri& t : m.faces)
            for (int k = 0; k < 3; ++k)
                if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= m.vertices.size())
                    return ::testing::AssertionFailure() << "index out of range after a successful read";
        for (const Vec3& v : m.vertices)
            if (!v.allFinite()) return ::testing::AssertionFailure() << "non-finite vertex after a successful read";
    } catch (const Error&) {
        if (failed) *failed = true;
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "not a meshquilt::Error: " << e.what();
    }
    return ::testing::AssertionSuccess();
}

TEST(ParseMesh, MatchesReadMesh) {
    const std::string bytes = slurp(kData + "cube_binary_le.ply");
    const Mesh a = parse_mesh("memory.PLY", bytes);
    const Mesh b = read_mesh(kData + "cube_binary_le.ply");
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_TRUE(throws_with<InvalidInput>([&] { parse_mesh("upload.stl", "solid x\nendsolid\n"); }, {"upload.stl: no faces"}));
    EXPECT_TRUE(throws_with<IoError>([&] { parse_mesh("upload.dxf", "0\nSECTION\n"); }, {"upload.dxf", "'.dxf'"}));
}

class RobustnessTest : public ::testing::TestWithParam<const char*> {};

TEST_P(RobustnessTest, EveryTruncationIsAMeshOrAnError) {
    const std::string bytes = slurp(kData + GetParam());
    const std::string name = std::string("t") + fs::path(GetParam()).extension().string();
    int errors = 0;
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        bool failed = false;
        ASSERT_TRUE(sane_or_error(name, bytes.substr(0, n), &failed)) << "prefix of " << n << " bytes";
        errors += failed ? 1 : 0;
    }
    EXPECT_GT(errors, static_cast<int>(bytes.size() / 2)) << "most truncations must be detected";
}

TEST_P(RobustnessTest, RandomMutationsAreAMeshOrAnError) {
    const std::string bytes = slurp(kData + GetParam());
    const std::string name = std::string("m") + fs::path(GetParam()).extension().string();
    std::mt19937 rng(12345);
    const std::string alphabet = "0123456789-+.eE /\n\r\t#nafivxyzOFFplysolidfacet\xff";
    for (int round = 0; round < 5000; ++round) {
        std::string m = bytes;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const std::size_t at = rng() % m.size();
            switch (rng() % 4) {
            case 0: m[at] = static_cast<char>(rng()); break;
            case 1: m[at] = alphabet[rng() % alphabet.size()]; break;
            case 2: m.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
            default: m.erase(at, 1 + rng() % 8); break;
            }
            if (m.empty()) m = "x";
        }
        ASSERT_TRUE(sane_or_error(name, m)) << "round " << round;
    }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RobustnessTest,
                         ::testing::Values("cube_mixed.obj", "cube.off", "cube_ascii.ply", "cube_binary_le.ply",
                                           "cube_binary_be.ply", "cube_ascii.stl", "cube_binary_solid.stl"));

TEST(Robustness, RandomBytesAreAnError) {
    std::mt19937 rng(99);
    for (const std::string ext : {".obj", ".off", ".ply", ".stl"})
        for (int round = 0; round < 2000; ++round) {
            std::string bytes(rng() % 400, '\0');
            for (char& c : bytes) c = static_cast<char>(rng());
            if (round % 3 == 0 && ext == ".ply") bytes = "ply\nformat binary_little_endian 1.0\n" + bytes;
            if (round % 3 == 0 && ext == ".stl") bytes = "solid " + bytes;
            if (round % 3 == 0 && ext == ".off") bytes = "OFF\n" + bytes;
            ASSERT_TRUE(sane_or_error("r" + ext, bytes)) << ext << " round " << round;
        }
}

TEST(Robustness, HugeClaimsFailFast) {
    // Each of these would need gigabytes if the count were believed.
    std::string stl(80, ' ');
    stl += std::string("\xff\xff\xff\x7f", 4);
    EXPECT_TRUE(throws_with<InvalidInput>([&] { parse_mesh("a.stl", stl); }, {"header says 2147483647 triangles, file holds 0"}));
    EXPECT_TRUE(throws_with<InvalidInput>(
        [&] {
            parse_mesh("a.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 2147483647\nproperty double x\n"
                                "property double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n");
        },
        {"a.ply: truncated: header says 2147483647 vertex elements"}));
    EXPECT_TRUE(throws_with<InvalidInput>([&] { parse_mesh("a.off", "OFF\n2147483647 2147483647 0\n"); }, {"more than a"}));
    // An element we skip, with an absurd count but no properties, costs nothing.
    EXPECT_EQ(parse_mesh("b.ply", "ply\nformat ascii 1.0\nelement nothing 9000000000000000000\nelement vertex 3\n"
                                  "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                                  "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
                  .num_faces(),
              1u);
}

}  // namespace
}  // namespace meshquilt
