// SPDX-License-Identifier: AGPL-3.0-or-later
// The direction field of surface quilting (docs/surface.md, "Direction field") on the shared
// meshes at full resolution: the smoothest 4-direction field (the bundled weave's symmetry), and
// the same through a user's stroke (a soft constraint). On a large base it is most of the stage
// "prepare base" (igea, 268,686 faces: 18 s of 20.6 in session 43).
// Meshes are read from MESHQUILT_MESHES (default ../shared/data/meshes beside the checkout); rows
// whose mesh is missing are skipped. Counters: faces, seconds, peak memory (MB).
//
//   build/bench/bench_field --benchmark_counters_tabular=true

#include "meshquilt/io.h"
#include "meshquilt/surface.h"
#include "quilt/field.h"

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <string>

namespace mq = meshquilt;
using meshquilt::bench::peak_rss_mb;
using meshquilt::bench::shared_mesh;

namespace {

void field_row(benchmark::State& state, const char* name, bool stroke) {
    const mq::Mesh* base = shared_mesh(name);
    if (!base) {
        state.SkipWithError((std::string(name) + ".obj not found (set MESHQUILT_MESHES)").c_str());
        return;
    }
    const auto nb = mq::quilt::face_neighbours(*base);
    mq::GuidanceField user;
    if (stroke) {
        // One stroke across the bounding box's longest horizontal extent, through its middle.
        const mq::Box3 box = mq::bounding_box(*base);
        const mq::Vec3 mid = 0.5 * (box.min + box.max);
        user.strokes.push_back({mid - 0.4 * box.size().x() * mq::Vec3::UnitX(), mid, mid + 0.4 * box.size().x() * mq::Vec3::UnitX()});
    }
    for (auto _ : state) {
        const mq::quilt::DirectionField f = mq::quilt::compute_field(*base, nb, 4, user, name);
        benchmark::DoNotOptimize(f.direction.data());
    }
    state.counters["faces"] = static_cast<double>(base->faces.size());
    state.counters["peak_MB"] = peak_rss_mb();
}

}  // namespace

BENCHMARK_CAPTURE(field_row, bunny, "bunny", false)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_CAPTURE(field_row, armadillo, "armadillo", false)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_CAPTURE(field_row, igea, "igea", false)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_CAPTURE(field_row, igea_stroke, "igea", true)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_MAIN();
