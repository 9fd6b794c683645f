// labels: unit property
// Elements, closedness, genus, boundary loops, defect detection, and validate()'s errors, warnings
// and repairs, on small meshes whose answers are known.

#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "support/expect_error.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace meshquilt {
namespace {

namespace shapes = test::shapes;
constexpr double kPi = 3.14159265358979323846;

::testing::AssertionResult invalid_with(const std::function<void()>& f, const std::vector<std::string>& fragments) {
    return test::throws_with<InvalidInput>(f, fragments);
}

/// validate(mesh, "m.obj", options) must throw InvalidInput whose message contains the fragments.
::testing::AssertionResult rejects(const Mesh& mesh, const std::vector<std::string>& fragments, bool repair = false,
                                   bool thin = false) {
    ValidationOptions o;
    o.repair = repair;
    o.require_thin_axis = thin;
    return invalid_with([&] { validate(mesh, "m.obj", o); }, fragments);
}

bool contains(const std::vector<std::string>& lines, const std::string& fragment) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(fragment) != std::string::npos; });
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += "\n  " + l;
    return s.empty() ? " (none)" : s;
}

/// Two triangles sharing only vertex 0.
Mesh bowtie() {
    Mesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
    m.faces = {Tri(0, 1, 2), Tri(0, 3, 4)};
    return m;
}

/// A Moebius strip of `n` quads: one-sided, so no orientation of its faces is consistent.
Mesh moebius(int n = 12) {
    Mesh m;
    for (int i = 0; i < n; ++i) {
        const double u = 2 * kPi * i / n;
        const Vec3 c(2 * std::cos(u), 2 * std::sin(u), 0.0);
        const Vec3 d = std::cos(u / 2) * Vec3(std::cos(u), std::sin(u), 0.0) + std::sin(u / 2) * Vec3(0, 0, 1);
        m.vertices.push_back(c - 0.5 * d);  // 2 i: side -1
        m.vertices.push_back(c + 0.5 * d);  // 2 i + 1: side +1
    }
    for (int i = 0; i < n; ++i) {
        const int a = 2 * i, b = 2 * i + 1;
        // after a full turn the strip's sides swap
        const int c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
        m.faces.emplace_back(a, c, d);
        m.faces.emplace_back(a, d, b);
    }
    return m;
}

// ---------------------------------------------------------------- components

TEST(ConnectedComponents, NumberedByFirstFace) {
    const Mesh far = shapes::translated(shapes::cube(), Vec3(5, 0, 0));
    Mesh m = shapes::concat(far, shapes::cube());
    // Interleave the two cubes' faces: 0 from the far cube, 1 from the near one, ...
    std::vector<Tri> faces;
    for (std::size_t i = 0; i < 12; ++i) {
        faces.push_back(m.faces[12 + i]);
        faces.push_back(m.faces[i]);
    }
    m.faces = faces;
    int count = -1;
    const std::vector<int> c = connected_components(m, &count);
    EXPECT_EQ(count, 2);
    for (std::size_t f = 0; f < c.size(); ++f) EXPECT_EQ(c[f], static_cast<int>(f % 2)) << "face " << f;
}

TEST(ConnectedComponents, SharedVertexJoinsAndOutOfRangeThrows) {
    EXPECT_EQ(analyse(bowtie()).elements.size(), 1u);
    int count = 0;
    connected_components(shapes::voxels({{0, 0, 0}, {1, 1, 1}}), &count);
    EXPECT_EQ(count, 1);  // two cubes touching at a corner are one element
    Mesh bad = shapes::cube();
    bad.faces[2][0] = -1;
    EXPECT_TRUE(invalid_with([&] { connected_components(bad); }, {"face 2 uses vertex -1"}));
    EXPECT_TRUE(invalid_with([&] { analyse(bad); }, {"face 2 uses vertex -1, the mesh has 8 vertices"}));
    EXPECT_TRUE(connected_components(Mesh{}).empty());
}

// ---------------------------------------------------------------- closed surfaces

TEST(Analyse, Cube) {
    const MeshAnalysis a = analyse(shapes::cube(2.0));
    EXPECT_EQ(a.faces, 12);
    EXPECT_EQ(a.vertices, 8);
    ASSERT_EQ(a.elements.size(), 1u);
    const ElementInfo& e = a.elements[0];
    EXPECT_TRUE(e.closed);
    EXPECT_TRUE(e.edge_manifold);
    EXPECT_EQ(e.genus, 0);
    EXPECT_EQ(e.boundary_loops, 0);
    EXPECT_DOUBLE_EQ(e.volume, 8.0);
    EXPECT_DOUBLE_EQ(e.area, 24.0);
    EXPECT_DOUBLE_EQ(a.area, 24.0);
    EXPECT_EQ(a.box.max, Vec3(2, 2, 2));
    EXPECT_EQ(a.closed_elements(), 1);
    EXPECT_FALSE(a.thin.is_thin);
    EXPECT_TRUE(a.problems.empty()) << joined(a.problems);
}

TEST(Analyse, TorusHasGenusOne) {
    for (int nu : {3, 8, 40}) {
        const MeshAnalysis a = analyse(shapes::torus(2.0, 0.5, nu, 5));
        ASSERT_EQ(a.elements.size(), 1u);
        EXPECT_TRUE(a.elements[0].closed) << nu;
        EXPECT_EQ(a.genus, 1) << nu;
        EXPECT_GT(a.elements[0].volume, 0.0);
    }
    // Fine enough, the volume approaches 2 pi^2 R r^2.
    const MeshAnalysis fine = analyse(shapes::torus(2.0, 0.5, 200, 100));
    const double exact = 2 * kPi * kPi * 2.0 * 0.25;
    EXPECT_NEAR(fine.elements[0].volume, exact, 2e-3 * exact);
}

TEST(Analyse, DoubleTorusHasGenusTwo) {
    const MeshAnalysis a = analyse(shapes::double_torus());
    ASSERT_EQ(a.elements.size(), 1u);
    EXPECT_TRUE(a.elements[0].closed);
    EXPECT_EQ(a.genus, 2);
    EXPECT_DOUBLE_EQ(a.elements[0].volume, 13.0);  // 15 voxels minus 2 holes
    EXPECT_TRUE(a.problems.empty()) << joined(a.problems);
    EXPECT_TRUE(a.thin.is_thin);
    EXPECT_EQ(a.thin.axis, 2);
}

TEST(Analyse, VoxelRingHasGenusOneAndGenusSums) {
    std::vector<std::array<int, 3>> ring;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            if (x != 1 || y != 1) ring.push_back({x, y, 0});
    const MeshAnalysis a = analyse(shapes::concat(shapes::voxels(ring), shapes::translated(shapes::double_torus(), Vec3(0, 0, 5))));
    ASSERT_EQ(a.elements.size(), 2u);
    EXPECT_EQ(a.elements[0].genus, 1);
    EXPECT_EQ(a.elements[1].genus, 2);
    EXPECT_EQ(a.genus, 3);
    EXPECT_EQ(a.closed_elements(), 2);
}

// ---------------------------------------------------------------- open surfaces

TEST(Analyse, OpenCylinderHasTwoBoundaryLoops) {
    const MeshAnalysis a = analyse(shapes::open_cylinder(1.0, 2.0, 16, 3));
    ASSERT_EQ(a.elements.size(), 1u);
    EXPECT_FALSE(a.elements[0].closed);
    EXPECT_EQ(a.elements[0].boundary_loops, 2);
    EXPECT_EQ(a.boundary_loops, 2);
    EXPECT_EQ(a.boundary_edges, 32);
    EXPECT_EQ(a.genus, 0);
    EXPECT_EQ(a.elements[0].volume, 0.0);  // not closed: no volume
    EXPECT_TRUE(a.problems.empty()) << joined(a.problems);
}

TEST(Analyse, GridIsADiskAndAThinSlab) {
    const MeshAnalysis a = analyse(shapes::grid(5, 2.0));
    EXPECT_EQ(a.boundary_loops, 1);
    EXPECT_EQ(a.boundary_edges, 20);
    EXPECT_EQ(a.genus, 0);
    EXPECT_TRUE(a.thin.is_thin);
    EXPECT_EQ(a.thin.axis, 2);
    EXPECT_EQ(a.thin.thickness, 0.0);
}

TEST(Analyse, HolesTouchingAtAVertexAreCountedByFan) {
    // Two triangles sharing one vertex: one element, two boundary loops, one non-manifold vertex.
    const MeshAnalysis a = analyse(bowtie());
    EXPECT_EQ(a.boundary_loops, 2);
    EXPECT_EQ(a.non_manifold_vertices, 1);
    EXPECT_EQ(a.non_manifold_edges, 0);
    // A 4 x 4 grid without the quads (1,1) and (2,2), which share the corner (2,2): splitting that
    // vertex per fan joins the two holes into one loop, so outer boundary + 1.
    Mesh g = shapes::grid(4);
    std::vector<Tri> kept;
    for (std::size_t f = 0; f < g.faces.size(); ++f) {
        const std::size_t quad = f / 2;
        if (quad != 5 && quad != 10) kept.push_back(g.faces[f]);
    }
    g.faces = kept;
    const MeshAnalysis h = analyse(g);
    EXPECT_EQ(h.boundary_edges, 16 + 8);
    EXPECT_EQ(h.boundary_loops, 2);
    EXPECT_EQ(h.non_manifold_vertices, 1);
    EXPECT_TRUE(contains(h.problems, "1 non-manifold vertex (first: vertex 12, where 2 separate fans of faces meet)"))
        << joined(h.problems);
}

// ---------------------------------------------------------------- defects

TEST(Analyse, NonManifoldEdge) {
    Mesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
    m.faces = {Tri(0, 1, 2), Tri(1, 0, 3), Tri(0, 1, 4)};
    const MeshAnalysis a = analyse(m);
    EXPECT_EQ(a.non_manifold_edges, 1);
    EXPECT_EQ(a.non_manifold_vertices, 0);
    EXPECT_FALSE(a.elements[0].edge_manifold);
    EXPECT_FALSE(a.elements[0].closed);
    EXPECT_TRUE(contains(a.problems, "1 non-manifold edge (first between vertices 0 and 1, shared by 3 faces)")) << joined(a.problems);

    // Two voxels sharing only an edge: that edge has four faces; its ends are not pinched.
    const MeshAnalysis v = analyse(shapes::voxels({{0, 0, 0}, {1, 1, 0}}));
    EXPECT_EQ(v.non_manifold_edges, 1);
    EXPECT_EQ(v.non_manifold_vertices, 0);
}

TEST(Analyse, NonManifoldVertex) {
    const MeshAnalysis a = analyse(shapes::voxels({{0, 0, 0}, {1, 1, 1}}));
    EXPECT_EQ(a.non_manifold_vertices, 1);
    EXPECT_EQ(a.non_manifold_edges, 0);
    EXPECT_EQ(a.elements.size(), 1u);
}

TEST(Analyse, InconsistentOrientation) {
    Mesh m = shapes::cube();
    std::swap(m.faces[4][1], m.faces[4][2]);  // face 4 = (0 1 5)
    const MeshAnalysis a = analyse(m);
    EXPECT_EQ(a.inconsistent_edges, 3);
    EXPECT_FALSE(a.elements[0].closed);
    EXPECT_EQ(a.boundary_edges, 0);
    EXPECT_TRUE(contains(a.problems, "3 edges with inconsistent orientation (first between vertices 0 and 1"))
        << joined(a.problems);
    EXPECT_GT(analyse(moebius()).inconsistent_edges, 0);
}

TEST(Analyse, InsideOutClosedElement) {
    const MeshAnalysis a = analyse(shapes::concat(shapes::cube(), shapes::flipped(shapes::translated(shapes::cube(), Vec3(3, 0, 0)))));
    ASSERT_EQ(a.elements.size(), 2u);
    EXPECT_TRUE(a.elements[1].closed);
    EXPECT_DOUBLE_EQ(a.elements[1].volume, -1.0);
    EXPECT_EQ(a.inconsistent_edges, 0);
    EXPECT_TRUE(contains(a.problems, "1 closed element is inside out (first: element 1, signed volume -1)")) << joined(a.problems);
}

TEST(Analyse, DegenerateAndDuplicateVertices) {
    Mesh m = shapes::cube(1.0);
    m.vertices.push_back(Vec3(0.5, 0.0, 0.0));              // 8: on the edge from vertex 0 to 1
    m.vertices.push_back(Vec3(1.0, 1.0, 1.0));              // 9: duplicates vertex 7
    m.vertices.push_back(Vec3(0.5, 1e-6, 0.0));             // 10: near the same edge, area 5e-7 >> 1e-14 * 3
    m.faces.push_back(Tri(0, 8, 1));                        // 12: zero area
    m.faces.push_back(Tri(3, 3, 7));                        // 13: repeated index
    m.faces.push_back(Tri(0, 1, 10));                       // 14: thin but not degenerate
    m.faces.push_back(Tri(9, 5, 4));                        // 15: uses the duplicate
    const MeshAnalysis a = analyse(m);
    EXPECT_EQ(a.degenerate_faces, 2);
    EXPECT_EQ(a.duplicate_vertices, 1);
    EXPECT_TRUE(contains(a.problems, "2 degenerate faces (first: face 12, which has zero area)")) << joined(a.problems);
    EXPECT_TRUE(contains(a.problems, "1 duplicate vertex (first: vertex 9 is at the position of vertex 7)")) << joined(a.problems);
}

TEST(Analyse, UnreferencedVerticesAndEmptyMesh) {
    Mesh m = shapes::cube();
    m.vertices.push_back(Vec3(100, 100, 100));  // not in the box either
    const MeshAnalysis a = analyse(m);
    EXPECT_EQ(a.unreferenced_vertices, 1);
    EXPECT_EQ(a.vertices, 8);
    EXPECT_EQ(a.box.max, Vec3(1, 1, 1));
    const MeshAnalysis empty = analyse(Mesh{});
    EXPECT_EQ(empty.faces, 0);
    EXPECT_EQ(empty.problems, std::vector<std::string>{"no faces"});
}

// ---------------------------------------------------------------- properties over a corpus

struct Known {
    const char* name;
    Mesh mesh;
    int genus, loops;
    bool closed;
};

std::vector<Known> corpus() {
    return {{"cube", shapes::cube(), 0, 0, true},
            {"torus", shapes::torus(3.0, 1.0, 17, 9), 1, 0, true},
            {"double torus", shapes::double_torus(), 2, 0, true},
            {"cylinder", shapes::open_cylinder(1.0, 3.0, 11, 5), 0, 2, false},
            {"grid", shapes::grid(6), 0, 1, false}};
}

/// A copy with faces and vertices shuffled and each face's corners rotated.
Mesh shuffled(const Mesh& m, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<int> perm(m.vertices.size());
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    Mesh out;
    out.vertices.resize(m.vertices.size());
    for (std::size_t v = 0; v < perm.size(); ++v) out.vertices[static_cast<std::size_t>(perm[v])] = m.vertices[v];
    for (const Tri& t : m.faces) {
        const int r = static_cast<int>(rng() % 3);
        out.faces.emplace_back(perm[static_cast<std::size_t>(t[r])], perm[static_cast<std::size_t>(t[(r + 1) % 3])],
                               perm[static_cast<std::size_t>(t[(r + 2) % 3])]);
    }
    std::shuffle(out.faces.begin(), out.faces.end(), rng);
    return out;
}

TEST(AnalyseProperty, TopologyIsIndependentOfNumberingAndFlipsNegateVolume) {
    for (const Known& k : corpus()) {
        SCOPED_TRACE(k.name);
        const MeshAnalysis a = analyse(k.mesh);
        ASSERT_EQ(a.elements.size(), 1u);
        EXPECT_EQ(a.genus, k.genus);
        EXPECT_EQ(a.boundary_loops, k.loops);
        EXPECT_EQ(a.elements[0].closed, k.closed);
        EXPECT_TRUE(a.problems.empty()) << joined(a.problems);
        // Euler: V - E + F = 2 - 2g - b, with E = (3F + boundary edges) / 2 on a manifold.
        const int edges = (3 * a.faces + a.boundary_edges) / 2;
        EXPECT_EQ(a.vertices - edges + a.faces, 2 - 2 * a.genus - a.boundary_loops);
        for (std::uint32_t seed : {1u, 2u, 3u}) {
            const MeshAnalysis s = analyse(shuffled(k.mesh, seed));
            EXPECT_EQ(s.genus, a.genus);
            EXPECT_EQ(s.boundary_loops, a.boundary_loops);
            EXPECT_EQ(s.boundary_edges, a.boundary_edges);
            EXPECT_EQ(s.elements[0].closed, a.elements[0].closed);
            EXPECT_NEAR(s.area, a.area, 1e-12 * a.area);
            EXPECT_NEAR(s.elements[0].volume, a.elements[0].volume, 1e-12 * (1 + std::abs(a.elements[0].volume)));
            EXPECT_TRUE(s.problems.empty()) << joined(s.problems);
        }
        const MeshAnalysis f = analyse(shapes::flipped(k.mesh));
        EXPECT_EQ(f.genus, a.genus);
        EXPECT_NEAR(f.elements[0].volume, -a.elements[0].volume, 1e-12 * (1 + std::abs(a.elements[0].volume)));
    }
}

TEST(AnalyseProperty, RepairedTriangleSoupIsTheOriginalSurface) {
    for (const Known& k : corpus()) {
        SCOPED_TRACE(k.name);
        const Mesh soup = shapes::soup(k.mesh);
        const MeshAnalysis raw = analyse(soup);
        EXPECT_EQ(static_cast<int>(raw.elements.size()), raw.faces);  // every triangle on its own
        EXPECT_GT(raw.duplicate_vertices, 0);
        ValidationOptions o;
        o.repair = true;
        const ValidationResult r = validate(soup, k.name, o);
        EXPECT_EQ(r.mesh.num_vertices(), k.mesh.num_vertices());
        const MeshAnalysis a = analyse(r.mesh);
        EXPECT_EQ(a.genus, k.genus);
        EXPECT_EQ(a.boundary_loops, k.loops);
        EXPECT_EQ(a.closed_elements(), k.closed ? 1 : 0);
        EXPECT_TRUE(contains(r.repairs, "merged")) << joined(r.repairs);
    }
}

// ---------------------------------------------------------------- validate: errors in order

TEST(Validate, GoodMeshPassesUnchanged) {
    const Mesh m = shapes::double_torus();
    ValidationOptions o;
    o.repair = true;
    o.require_thin_axis = true;
    const ValidationResult r = validate(m, "swatch.obj", o);
    EXPECT_EQ(r.mesh.vertices, m.vertices);
    EXPECT_EQ(r.mesh.faces, m.faces);
    EXPECT_TRUE(r.repairs.empty()) << joined(r.repairs);
    EXPECT_TRUE(r.warnings.empty()) << joined(r.warnings);
}

TEST(Validate, EmptyMesh) { EXPECT_TRUE(rejects(Mesh{}, {"m.obj: no faces"})); }

TEST(Validate, NonFiniteComesFirst) {
    Mesh m = shapes::cube();
    m.vertices[6].z() = std::numeric_limits<double>::infinity();
    m.vertices[2].x() = std::numeric_limits<double>::quiet_NaN();
    m.faces.push_back(Tri(0, 0, 99));  // also out of range and degenerate: reported later
    EXPECT_TRUE(rejects(m, {"m.obj: 2 vertices have non-finite coordinates (first: vertex 2)"}));
    EXPECT_TRUE(rejects(m, {"m.obj: 2 vertices have non-finite coordinates (first: vertex 2)"}, true));  // no repair for used ones
}

TEST(Validate, UnreferencedNonFiniteVertexIsDroppedByRepair) {
    Mesh m = shapes::cube();
    m.vertices.push_back(Vec3(std::nan(""), 0, 0));
    EXPECT_TRUE(rejects(m, {"m.obj: 1 vertex has a non-finite coordinate (first: vertex 8)", "--repair"}));
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(m, "m.obj", o);
    EXPECT_EQ(r.mesh.num_vertices(), 8u);
    EXPECT_TRUE(contains(r.repairs, "m.obj: dropped 1 unreferenced vertex (first: vertex 8)")) << joined(r.repairs);
}

TEST(Validate, IndicesOutOfRange) {
    Mesh m = shapes::cube();
    m.faces[3][2] = 99;
    m.faces[7][0] = -4;
    EXPECT_TRUE(rejects(m, {"m.obj: 2 faces have vertex indices out of range (first: face 3 uses vertex 99, the mesh has 8 vertices)"}));
}

TEST(Validate, DegenerateFacesFailOrAreDropped) {
    Mesh m = shapes::cube();
    m.faces.push_back(Tri(1, 2, 1));
    m.faces.push_back(Tri(0, 0, 0));
    EXPECT_TRUE(rejects(m, {"m.obj: 2 degenerate faces (first: face 12, which repeats a vertex); pass --repair"}));
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(m, "m.obj", o);
    EXPECT_EQ(r.mesh.faces, shapes::cube().faces);
    EXPECT_EQ(r.repairs, std::vector<std::string>{"m.obj: dropped 2 degenerate faces (first: face 12, which repeats a vertex)"});
    Mesh all_bad;
    all_bad.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
    all_bad.faces = {Tri(0, 1, 2)};
    EXPECT_TRUE(rejects(all_bad, {"m.obj: 1 degenerate face (first: face 0, which has zero area)"}));
    EXPECT_TRUE(rejects(all_bad, {"m.obj: no faces left after dropping 1 degenerate face"}, true));
}

TEST(Validate, DuplicateVerticesWarnOrAreMerged) {
    const Mesh soup = shapes::soup(shapes::cube());
    const ValidationResult w = validate(soup, "m.stl");
    EXPECT_EQ(w.mesh.num_vertices(), 36u);
    EXPECT_TRUE(contains(w.warnings, "m.stl: 28 duplicate vertices (first: vertex 3 is at the position of vertex 0)")) << joined(w.warnings);
    EXPECT_TRUE(contains(w.warnings, "--repair"));
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(soup, "m.stl", o);
    EXPECT_EQ(r.mesh.num_vertices(), 8u);
    EXPECT_EQ(r.mesh.num_faces(), 12u);
    // merged vertices are reported once, as merged, not again as unreferenced
    EXPECT_EQ(r.repairs, std::vector<std::string>{"m.stl: merged 28 duplicate vertices (first: vertex 3 is at the position of vertex 0)"});
    EXPECT_EQ(analyse(r.mesh).closed_elements(), 1);
}

TEST(Validate, NonManifoldEdgesAreErrorsEvenWithRepair) {
    const Mesh edge = shapes::voxels({{0, 0, 0}, {1, 1, 0}});
    EXPECT_TRUE(rejects(edge, {"m.obj: 1 non-manifold edge (first between vertices", "shared by 4 faces"}, true));
    // Non-manifold edges are reported before non-manifold vertices, and the vertices' repair does
    // not hide them.
    const Mesh vertex = shapes::voxels({{0, 0, 0}, {1, 1, 1}});
    EXPECT_TRUE(rejects(shapes::concat(vertex, shapes::translated(edge, Vec3(9, 0, 0))), {"non-manifold edge"}));
    EXPECT_TRUE(rejects(shapes::concat(vertex, shapes::translated(edge, Vec3(9, 0, 0))), {"non-manifold edge"}, true));
}

// Two cubes touching at a corner: an error naming the vertex, or with repair one vertex per fan, the
// faces and positions unchanged, and two closed cubes.
TEST(Validate, NonManifoldVerticesFailOrAreSplit) {
    const Mesh vertex = shapes::voxels({{0, 0, 0}, {1, 1, 1}});
    EXPECT_TRUE(rejects(vertex, {"m.obj: 1 non-manifold vertex (first: vertex", "where 2 separate fans of faces meet",
                                 "pass --repair to split"}));
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(vertex, "m.obj", o);
    ASSERT_EQ(r.repairs.size(), 1U) << joined(r.repairs);
    EXPECT_TRUE(contains(r.repairs, "m.obj: split 1 non-manifold vertex (first: vertex")) << joined(r.repairs);
    EXPECT_TRUE(contains(r.repairs, "into one vertex per fan (1 vertex added)")) << joined(r.repairs);
    ASSERT_EQ(r.mesh.num_faces(), vertex.num_faces());
    EXPECT_EQ(r.mesh.num_vertices(), vertex.num_vertices() + 1);
    for (std::size_t f = 0; f < vertex.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(r.mesh.vertices[r.mesh.faces[f][k]], vertex.vertices[vertex.faces[f][k]]);
    const MeshAnalysis a = analyse(r.mesh);
    EXPECT_EQ(a.non_manifold_vertices, 0);
    EXPECT_EQ(a.closed_elements(), 2);
    // The copy sits where the vertex was: the one problem left is that duplicate, which a second
    // validation only warns about.
    EXPECT_EQ(a.problems, std::vector<std::string>{"1 duplicate vertex (first: vertex 15 is at the position of vertex 6)"});
    EXPECT_TRUE(validate(r.mesh, "m.obj").repairs.empty());
    Mesh again = r.mesh;
    EXPECT_EQ(split_non_manifold_vertices(again), 0);  // nothing left to split
    EXPECT_EQ(again.vertices, r.mesh.vertices);

    // A bow tie of three fans at one vertex (three triangles sharing only their apex): two copies.
    Mesh fans;
    fans.vertices = {Vec3(0, 0, 0)};
    for (int i = 0; i < 3; ++i) {
        const double a0 = 2.1 * i, a1 = a0 + 0.5;
        fans.vertices.emplace_back(std::cos(a0), std::sin(a0), 0.0);
        fans.vertices.emplace_back(std::cos(a1), std::sin(a1), 0.0);
        fans.faces.emplace_back(0, 2 * i + 1, 2 * i + 2);
    }
    const ValidationResult b = validate(fans, "fans.obj", o);
    EXPECT_TRUE(contains(b.repairs, "fans.obj: split 1 non-manifold vertex (first: vertex 0, where 3 separate fans of faces meet) into one vertex per fan (2 vertices added)"))
        << joined(b.repairs);
    EXPECT_EQ(analyse(b.mesh).non_manifold_vertices, 0);
    EXPECT_EQ(b.mesh.num_vertices(), 9u);
}

TEST(Validate, InconsistentOrientationFailsOrIsRepaired) {
    Mesh m = shapes::cube();
    std::swap(m.faces[4][1], m.faces[4][2]);
    EXPECT_TRUE(rejects(m, {"m.obj: 3 edges with inconsistent orientation (first between vertices 0 and 1",
                            "pass --repair to reorient"}));
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(m, "m.obj", o);
    EXPECT_EQ(r.mesh.faces, shapes::cube().faces);  // the one odd face turned back; the majority kept
    EXPECT_TRUE(contains(r.repairs, "m.obj: reoriented 1 face to fix 3 edges with inconsistent orientation")) << joined(r.repairs);
    EXPECT_TRUE(rejects(moebius(), {"m.obj: 1 edge with inconsistent orientation", "not orientable"}, true));
    // `reorient` alone (a base): the same faces, said as a warning, and nothing else repaired.
    ValidationOptions base;
    base.reorient = true;
    Mesh with_duplicate = m;
    with_duplicate.vertices.push_back(with_duplicate.vertices[0]);
    const ValidationResult b = validate(with_duplicate, "m.obj", base);
    EXPECT_EQ(b.mesh.faces, shapes::cube().faces);
    EXPECT_TRUE(b.repairs.empty()) << joined(b.repairs);
    EXPECT_TRUE(contains(b.warnings, "m.obj: reoriented 1 face to fix 3 edges with inconsistent orientation")) << joined(b.warnings);
    EXPECT_EQ(b.mesh.vertices.size(), with_duplicate.vertices.size());  // no other repair: the duplicate stays
    EXPECT_THROW(validate(moebius(), "m.obj", base), InvalidInput);
    // An inside-out closed piece of a base is left to the surface stage (it flips it and says so).
    const ValidationResult inside_out = validate(shapes::flipped(shapes::cube()), "m.obj", base);
    EXPECT_TRUE(inside_out.warnings.empty()) << joined(inside_out.warnings);
    EXPECT_EQ(inside_out.mesh.faces, shapes::flipped(shapes::cube()).faces);
}

TEST(Validate, InsideOutElementWarnsOrIsFlipped) {
    const Mesh m = shapes::concat(shapes::cube(), shapes::flipped(shapes::translated(shapes::cube(), Vec3(3, 0, 0))));
    const ValidationResult w = validate(m, "m.obj");
    EXPECT_TRUE(w.repairs.empty());
    EXPECT_TRUE(contains(w.warnings, "m.obj: 1 closed element is inside out (first: element 1, signed volume -1); pass --repair"))
        << joined(w.warnings);
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(m, "m.obj", o);
    EXPECT_TRUE(contains(r.repairs, "m.obj: flipped 1 inside-out closed element (first: element 1, 12 faces)")) << joined(r.repairs);
    const MeshAnalysis a = analyse(r.mesh);
    EXPECT_DOUBLE_EQ(a.elements[0].volume, 1.0);
    EXPECT_DOUBLE_EQ(a.elements[1].volume, 1.0);
}

TEST(Validate, ThinAxisRequired) {
    EXPECT_TRUE(rejects(shapes::cube(), {"m.obj: no thin axis: the smallest extent (1) is more than half the middle one (1); a swatch must be a slab"},
                        false, true));
    EXPECT_NO_THROW(validate(shapes::cube(), "m.obj"));  // only swatches need one
    Mesh slab = shapes::cube();
    for (Vec3& v : slab.vertices) v = v.cwiseProduct(Vec3(2.0, 4.0, 1.0));  // 2 x 4 x 1: 1 <= 0.5 * 2
    ValidationOptions o;
    o.require_thin_axis = true;
    EXPECT_NO_THROW(validate(slab, "m.obj", o));
    // A flat swatch (a square in the plane y = 0) has a thin axis but nothing to grow.
    Mesh flat;
    flat.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(0, 0, 1)};
    flat.faces = {Tri(0, 1, 2), Tri(0, 2, 3)};
    EXPECT_TRUE(rejects(flat, {"m.obj: flat: its thin axis (y) has no thickness"}, false, true));
    EXPECT_NO_THROW(validate(flat, "m.obj"));  // a flat base is fine
}

TEST(Validate, UnreferencedVerticesAreKeptOrDropped) {
    Mesh m = shapes::cube();
    m.vertices.insert(m.vertices.begin(), Vec3(7, 7, 7));
    m.vertices.push_back(Vec3(8, 8, 8));
    for (Tri& t : m.faces) t += Tri::Ones();
    EXPECT_EQ(validate(m, "m.obj").mesh.num_vertices(), 10u);
    ValidationOptions o;
    o.repair = true;
    const ValidationResult r = validate(m, "m.obj", o);
    EXPECT_EQ(r.mesh.vertices, shapes::cube().vertices);
    EXPECT_EQ(r.mesh.faces, shapes::cube().faces);
    EXPECT_EQ(r.repairs, std::vector<std::string>{"m.obj: dropped 2 unreferenced vertices (first: vertex 0)"});
}

}  // namespace
}  // namespace meshquilt
