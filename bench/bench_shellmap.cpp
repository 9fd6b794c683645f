// SPDX-License-Identifier: AGPL-3.0-or-later
// Shell map construction and stretch optimisation (Zhou et al. 2006 Section 3.2, issue 4) on the
// shared meshes: the bunny (the paper's Figure 7: L2 stretch 1.14 before, 1.08 after), igea
// (268k faces) and armadillo, at shell heights of 1% and 2% of the bounding-box diagonal (the
// default surface run's shell is the swatch's thickness at 8% of the diagonal: about 1-2%).
// Meshes are read from MESHQUILT_MESHES (default ../shared/data/meshes beside the checkout); rows
// whose mesh is missing are skipped. Counters: faces, charts, stretch before and after, seconds
// to build and to optimise, share of the area with a lowered height, peak memory (MB).
// map_points: ShellMap::map (texture point to shell point) of 2^16 points spread over the bunny's
// shell at 1% height, heights from just below the base to just above the offset surface (the
// surface stage maps every vertex it embeds this way).
//
//   build/bench/bench_shellmap --benchmark_counters_tabular=true

#include "meshquilt/io.h"
#include "meshquilt/shellmap.h"
#include "meshquilt/surface.h"

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mq = meshquilt;
using meshquilt::bench::peak_rss_mb;
using meshquilt::bench::shared_mesh;

namespace {

void shell_row(benchmark::State& state, const char* name, double height_fraction) {
    const mq::Mesh* base = shared_mesh(name);
    if (!base) {
        state.SkipWithError((std::string(name) + ".obj not found (set MESHQUILT_MESHES)").c_str());
        return;
    }
    mq::ShellOptions o;
    o.height = height_fraction * mq::bounding_box(*base).size().norm();
    mq::ShellStatistics st;
    for (auto _ : state) {
        const mq::ShellMap shell(*base, o);
        st = shell.statistics();
        benchmark::DoNotOptimize(st);
    }
    state.counters["faces"] = st.prisms;
    state.counters["charts"] = st.charts;
    state.counters["stretch_before"] = st.stretch_l2_initial;
    state.counters["stretch_after"] = st.stretch_l2_final;
    state.counters["passes"] = st.optimisation_passes;
    state.counters["build_s"] = st.seconds_build;
    state.counters["optimise_s"] = st.seconds_optimise;
    state.counters["limited_area"] = st.limited_area_fraction;
    state.counters["peak_MB"] = peak_rss_mb();
}

void map_points(benchmark::State& state) {
    const mq::Mesh* base = shared_mesh("bunny");
    if (!base) {
        state.SkipWithError("bunny.obj not found (set MESHQUILT_MESHES)");
        return;
    }
    mq::ShellOptions o;
    o.height = 0.01 * mq::bounding_box(*base).size().norm();
    static const auto shell = std::make_unique<const mq::ShellMap>(*base, o);
    std::vector<mq::SurfacePoint> points(std::size_t{1} << 16);
    std::uint64_t x = 88172645463325252ULL;  // xorshift64: the same points every run
    auto next = [&x] {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        return static_cast<double>(x >> 11) * 0x1.0p-53;
    };
    for (std::size_t i = 0; i < points.size(); ++i) {
        mq::SurfacePoint& sp = points[i];
        sp.face = static_cast<int>((i * 7919) % base->faces.size());
        const double a = next(), b = next() * (1.0 - a);
        sp.bary = mq::Vec3(a, b, 1.0 - a - b);
        sp.height = (1.2 * next() - 0.1) * o.height;
    }
    for (auto _ : state)
        for (const mq::SurfacePoint& sp : points) benchmark::DoNotOptimize(shell->map(sp));
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * points.size()));
}

}  // namespace

BENCHMARK(map_points)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shell_row, bunny_h1, "bunny", 0.01)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, bunny_h2, "bunny", 0.02)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, armadillo_h1, "armadillo", 0.01)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, igea_h1, "igea", 0.01)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
