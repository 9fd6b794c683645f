// SPDX-License-Identifier: AGPL-3.0-or-later
// Shell map construction and stretch optimisation (Zhou et al. 2006 Section 3.2, issue 4) on the
// shared meshes: the bunny (the paper's Figure 7: L2 stretch 1.14 before, 1.08 after), igea
// (268k faces) and armadillo, at shell heights of 1% and 2% of the bounding-box diagonal (the
// default surface run's shell is the swatch's thickness at 8% of the diagonal: about 1-2%).
// Meshes are read from MESHQUILT_MESHES (default ../shared/data/meshes beside the checkout); rows
// whose mesh is missing are skipped. Counters: faces, charts, stretch before and after, seconds
// to build and to optimise, share of the area with a lowered height, peak memory (MB).
//
//   build/bench/bench_shellmap --benchmark_counters_tabular=true

#include "meshquilt/io.h"
#include "meshquilt/shellmap.h"

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <string>

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

}  // namespace

BENCHMARK_CAPTURE(shell_row, bunny_h1, "bunny", 0.01)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, bunny_h2, "bunny", 0.02)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, armadillo_h1, "armadillo", 0.01)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(shell_row, igea_h1, "igea", 0.01)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
