// SPDX-License-Identifier: AGPL-3.0-or-later
// The surface rows of Table 1 of Zhou et al. 2006:
//   Bunny + Weave: a ~5k-face bunny, 15,168-face weave -> ~700k output faces (86 min in the paper)
//   Bunny + Link : the bunny with chain mail          -> ~940k output faces (80 min in the paper)
// The base is the Stanford bunny decimated to 5,000 faces (CGAL edge collapse) when the shared
// data set is at hand (MESHQUILT_BUNNY, default ../shared/data/meshes/bunny.obj beside the
// checkout), else spot (5,856 faces, tests/data/surface). The swatch size is set so that the
// base holds target / swatch-faces footprints. Reports wall time per stage, output faces and
// peak memory (max RSS) as counters.
//
// Beside them, a part thinner than the footprint (ThinCapsule): trimesh's capsule of radius 0.06
// and length 1 (48 x 48, subdivided once, built by tests/support/shapes) with pebbles at swatch
// size 0.2, where slit patch discs once took 4,220 patches and 16 minutes (docs/surface.md, "Thin
// parts were slow"). Built when the tests are (it uses their shapes).
//
//   build/bench/bench_surface --benchmark_counters_tabular=true

#include "meshquilt/io.h"
#include "meshquilt/quilt.h"
#include "meshquilt/surface.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include "bench_util.h"
#ifdef MQ_TEST_SHAPES
#include "support/shapes.h"
#endif

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace mq = meshquilt;
using meshquilt::bench::peak_rss_mb;

namespace {

mq::Mesh decimate(const mq::Mesh& in, std::size_t faces) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using SM = CGAL::Surface_mesh<K::Point_3>;
    SM sm;
    std::vector<int> used(in.vertices.size(), -1);
    for (const auto& f : in.faces)
        for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(f[k])] = 1;
    std::vector<SM::Vertex_index> vi(in.vertices.size());
    for (std::size_t v = 0; v < in.vertices.size(); ++v)
        if (used[v] > 0) vi[v] = sm.add_vertex(K::Point_3(in.vertices[v].x(), in.vertices[v].y(), in.vertices[v].z()));
    for (const auto& f : in.faces) sm.add_face(vi[static_cast<std::size_t>(f[0])], vi[static_cast<std::size_t>(f[1])], vi[static_cast<std::size_t>(f[2])]);
    CGAL::Surface_mesh_simplification::Count_stop_predicate<SM> stop(faces * 3 / 2);  // counts edges: E = 1.5 F
    CGAL::Surface_mesh_simplification::edge_collapse(sm, stop);
    sm.collect_garbage();
    mq::Mesh out;
    for (auto v : sm.vertices()) out.vertices.emplace_back(sm.point(v).x(), sm.point(v).y(), sm.point(v).z());
    for (auto f : sm.faces()) {
        mq::Tri t;
        int k = 0;
        for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = static_cast<int>(v.idx());
        out.faces.push_back(t);
    }
    return out;
}

const mq::Mesh& base_mesh(std::string* name) {
    static std::string used;
    static const mq::Mesh base = [] {
        const char* env = std::getenv("MESHQUILT_BUNNY");
        const std::string bunny = env ? env : std::string(MQ_SOURCE_DIR) + "/../shared/data/meshes/bunny.obj";
        if (std::filesystem::exists(bunny)) {
            used = "bunny decimated to 5k faces";
            return decimate(mq::read_mesh(bunny), 5000);
        }
        used = "spot (bunny not found)";
        return mq::read_mesh(std::string(MQ_SOURCE_DIR) + "/tests/data/surface/spot.obj");
    }();
    *name = used;
    return base;
}

void counters(benchmark::State& state, const mq::Mesh& base, const mq::SurfaceQuiltResult& r) {
    state.counters["base_faces"] = static_cast<double>(base.faces.size());
    state.counters["out_faces"] = r.report.faces;
    state.counters["elements"] = r.report.elements;
    state.counters["removed"] = r.report.elements_removed;
    state.counters["patches"] = r.report.patches;
    state.counters["dens_min"] = r.surface.region_density_min;
    state.counters["dens_max"] = r.surface.region_density_max;
    state.counters["count_min"] = r.surface.region_count_density_min;  // 0 for threads (not counted)
    state.counters["count_max"] = r.surface.region_count_density_max;
    state.counters["peak_MB"] = peak_rss_mb();
    for (const auto& [stage, s] : r.report.seconds) state.counters["s_" + stage] = s;
}

void run_row(benchmark::State& state, const char* swatch_name, double target_faces) {
    std::string base_name;
    const mq::Mesh& base = base_mesh(&base_name);
    const mq::Mesh swatch = mq::read_mesh(std::string(MQ_SWATCH_DIR) + "/" + swatch_name + ".obj");
    const mq::Mesh sw = mq::normalize_swatch(swatch);
    const mq::Box3 box = mq::bounding_box(sw);
    double area = 0.0;
    for (const auto& f : base.faces)
        area += 0.5 * (base.vertices[static_cast<std::size_t>(f[1])] - base.vertices[static_cast<std::size_t>(f[0])])
                          .cross(base.vertices[static_cast<std::size_t>(f[2])] - base.vertices[static_cast<std::size_t>(f[0])])
                          .norm();
    // Footprint area so that the base holds target / swatch-faces footprints.
    const double footprint = area * static_cast<double>(sw.faces.size()) / target_faces;
    const double aspect = std::max(box.size().x(), box.size().y()) / std::sqrt(box.size().x() * box.size().y());
    mq::SurfaceQuiltResult r;
    for (auto _ : state) {
        mq::SurfaceQuiltOptions o;
        o.swatch_size = std::sqrt(footprint) * aspect;
        o.seed = 1;
        r = mq::quilt_surface(base, swatch, o);
        benchmark::DoNotOptimize(r.mesh.faces.data());
    }
    state.SetLabel(base_name);
    counters(state, base, r);
}

void BM_BunnyWeave(benchmark::State& state) { run_row(state, "weave", 700000); }
void BM_BunnyLink(benchmark::State& state) { run_row(state, "chainmail", 940000); }

#ifdef MQ_TEST_SHAPES
void BM_ThinCapsule(benchmark::State& state) {
    const mq::Mesh base = meshquilt::test::shapes::subdivided(meshquilt::test::shapes::capsule(0.06, 1.0, 48, 24, 1));
    const mq::Mesh swatch = mq::read_mesh(std::string(MQ_SWATCH_DIR) + "/pebbles.obj");
    mq::SurfaceQuiltResult r;
    for (auto _ : state) {
        mq::SurfaceQuiltOptions o;
        o.swatch_size = 0.2;
        o.seed = 1;
        r = mq::quilt_surface(base, swatch, o);
        benchmark::DoNotOptimize(r.mesh.faces.data());
    }
    state.SetLabel("capsule r 0.06, pebbles");
    counters(state, base, r);
}
#endif

}  // namespace

BENCHMARK(BM_BunnyWeave)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_BunnyLink)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
#ifdef MQ_TEST_SHAPES
BENCHMARK(BM_ThinCapsule)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
#endif
BENCHMARK_MAIN();
