// SPDX-License-Identifier: AGPL-3.0-or-later
// Print export of a decorated bunny (issue 5): `fused` at 0.1 mm voxels (OpenVDB union and
// adaptive meshing) and `separate` (clearance and thickness checks), 100 mm tall. The decoration
// is made once, in process: the Stanford bunny (MESHQUILT_BUNNY, default
// ../shared/data/meshes/bunny.obj beside the checkout; else spot from tests/data) with the
// bundled rivets or chain mail at the default scale. Wall time per stage, output triangles and
// peak memory (max RSS) are counters.
//
//   build/bench/bench_print --benchmark_counters_tabular=true

#include "bench_util.h"
#include "meshquilt/io.h"
#include "meshquilt/print.h"
#include "meshquilt/surface.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>

namespace mq = meshquilt;
using meshquilt::bench::peak_rss_mb;

namespace {

const mq::Mesh& bunny() {
    static const mq::Mesh base = [] {
        const char* env = std::getenv("MESHQUILT_BUNNY");
        std::string path = env ? env : std::string(MQ_SOURCE_DIR) + "/../shared/data/meshes/bunny.obj";
        if (!std::filesystem::exists(path)) path = std::string(MQ_SOURCE_DIR) + "/tests/data/surface/spot.obj";
        return mq::read_mesh(path);
    }();
    return base;
}

const mq::SurfaceQuiltResult& decorated(const std::string& swatch) {
    static std::map<std::string, mq::SurfaceQuiltResult> cache;
    auto it = cache.find(swatch);
    if (it == cache.end()) {
        mq::SurfaceQuiltOptions o;
        o.seed = 1;
        it = cache.emplace(swatch, mq::quilt_surface(bunny(), mq::read_mesh(std::string(MQ_SWATCH_DIR) + "/" + swatch + ".obj"), o)).first;
    }
    return it->second;
}

void run(benchmark::State& state, const std::string& swatch, mq::PrintMode mode) {
    const mq::SurfaceQuiltResult& d = decorated(swatch);
    mq::PrintOptions o;
    o.mode = mode;
    o.size_mm = 100.0;
    o.voxel_mm = 0.1;
    o.force = true;  // measure, do not judge
    mq::PrintResult r;
    for (auto _ : state) r = mq::prepare_print(d.mesh, mode == mq::PrintMode::Fused ? &bunny() : nullptr, o, "bunny+" + swatch);
    const mq::PrintReport& p = r.report;
    state.counters["input_faces"] = static_cast<double>(d.mesh.faces.size());
    state.counters["out_tris"] = static_cast<double>(p.triangles);
    state.counters["bodies"] = p.bodies;
    state.counters["voxels_M"] = static_cast<double>(p.voxels_active) / 1e6;
    state.counters["volume_cm3"] = p.volume_mm3 / 1000.0;
    state.counters["voids"] = p.voids_filled;
    state.counters["scraps"] = p.scraps_dropped;
    state.counters["loose"] = p.loose_bodies;
    state.counters["s_prepare"] = p.seconds_prepare;
    state.counters["s_voxelise"] = p.seconds_voxelise;
    state.counters["s_mesh"] = p.seconds_mesh;
    state.counters["s_checks"] = p.seconds_checks;
    state.counters["peak_MB"] = peak_rss_mb();
}

}  // namespace

BENCHMARK_CAPTURE(run, fused_rivets, std::string("rivets"), mq::PrintMode::Fused)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(run, fused_chainmail, std::string("chainmail"), mq::PrintMode::Fused)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(run, separate_chainmail, std::string("chainmail"), mq::PrintMode::Separate)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
