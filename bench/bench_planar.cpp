// SPDX-License-Identifier: AGPL-3.0-or-later
// The planar rows of Table 1 of Zhou et al. 2006:
//   Plane + Wire : 15,168-face weave swatch -> 74,792 output faces (3 min in the paper)
//   Plane + Apple:  3,784-face apple swatch -> 321,046 output faces (3 min in the paper)
// with our bundled weave and pebbles swatches, output sized to reach about those face counts.
// Reports wall time per stage, output faces and peak memory (max RSS) as benchmark counters.
//
//   build/bench/bench_planar --benchmark_counters_tabular=true

#include "meshquilt/io.h"
#include "meshquilt/quilt.h"

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <cmath>

namespace mq = meshquilt;
using meshquilt::bench::peak_rss_mb;

namespace {

void run_row(benchmark::State& state, const char* swatch_name, double target_faces) {
    const mq::Mesh swatch = mq::normalize_swatch(mq::read_mesh(std::string(MQ_SWATCH_DIR) + "/" + swatch_name + ".obj"));
    const mq::Box3 box = mq::bounding_box(swatch);
    // Square output holding about target_faces / swatch_faces swatch footprints.
    const double footprints = target_faces / static_cast<double>(swatch.faces.size());
    const double side = std::sqrt(footprints * box.size().x() * box.size().y());
    mq::QuiltResult r;
    for (auto _ : state) {
        mq::PlanarQuiltOptions o;
        o.width = side;
        o.height = side;
        o.seed = 1;
        r = mq::quilt_plane(swatch, o);
        benchmark::DoNotOptimize(r.mesh.faces.data());
    }
    state.counters["swatch_faces"] = static_cast<double>(swatch.faces.size());
    state.counters["out_faces"] = r.report.faces;
    state.counters["elements"] = r.report.elements;
    state.counters["removed"] = r.report.elements_removed;
    state.counters["patches"] = r.report.patches;
    state.counters["peak_MB"] = peak_rss_mb();
    for (const auto& [stage, s] : r.report.seconds) state.counters["s_" + stage] = s;
}

void BM_PlaneWire(benchmark::State& state) { run_row(state, "weave", 74792); }
void BM_PlaneApple(benchmark::State& state) { run_row(state, "pebbles", 321046); }

}  // namespace

BENCHMARK(BM_PlaneWire)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_PlaneApple)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_MAIN();
