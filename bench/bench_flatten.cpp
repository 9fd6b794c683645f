// SPDX-License-Identifier: AGPL-3.0-or-later
// Flattening a patch of the base (surface quilting, step 4): LSCM and ARAP (CGAL's
// parameterizers; ARAP from LSCM's map, 10 iterations, as make_frame runs it for a swatch of free
// elements). Discs of a tenth of the bounding-box diagonal in radius around 16 seeds spread
// over the shared meshes' faces (the default run's patches on igea, 268k faces, hold a few
// thousand faces). Counters: discs the flattening failed on, faces per disc and area distortion
// (98th over 2nd percentile of the flat-to-3D area ratios, the quantity step 5 holds to 2) over
// the others, time per disc (all 16, failures included).
// Meshes are read from MESHQUILT_MESHES (default ../shared/data/meshes beside the checkout).
//
//   build/bench/bench_flatten --benchmark_counters_tabular=true

#include "quilt/field.h"
#include "quilt/patch.h"

#include "core/triangle_index.h"

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <string>

namespace mq = meshquilt;
using meshquilt::bench::shared_mesh;

namespace {

void flatten_row(benchmark::State& state, const char* name, bool rigid) {
    const mq::Mesh* base = shared_mesh(name);
    if (!base) {
        state.SkipWithError((std::string(name) + ".obj not found (set MESHQUILT_MESHES)").c_str());
        return;
    }
    const auto nb = mq::quilt::face_neighbours(*base);
    std::vector<mq::Vec3> centroid(base->faces.size());
    for (std::size_t f = 0; f < base->faces.size(); ++f) centroid[f] = mq::face_centroid(*base, f);
    const double radius = 0.1 * mq::bounding_box(*base).size().norm();
    std::vector<std::vector<int>> discs;
    for (int k = 0; k < 16; ++k)
        discs.push_back(mq::quilt::grow_disc(*base, nb, centroid, static_cast<int>(base->faces.size() * k / 16), radius));
    double faces = 0.0, distortion = 0.0, flattened = 0.0;
    for (auto _ : state) {
        faces = distortion = flattened = 0.0;
        for (const auto& disc : discs) {
            mq::quilt::FlatPatch flat;
            if (!(rigid ? mq::quilt::flatten_arap(*base, disc, &flat, 10) : mq::quilt::flatten_lscm(*base, disc, &flat))) continue;
            faces += static_cast<double>(disc.size());
            distortion += mq::quilt::area_distortion(*base, flat);
            flattened += 1.0;
        }
    }
    // Means over the discs flattened (CGAL's ARAP fails on some: make_frame keeps LSCM's map there).
    state.counters["failed"] = static_cast<double>(discs.size()) - flattened;
    state.counters["faces"] = flattened > 0 ? faces / flattened : 0.0;
    state.counters["distortion"] = flattened > 0 ? distortion / flattened : 0.0;
    state.counters["ms_per_disc"] =
        benchmark::Counter(static_cast<double>(discs.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(flatten_row, armadillo_lscm, "armadillo", false)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(flatten_row, armadillo_rigid, "armadillo", true)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(flatten_row, igea_lscm, "igea", false)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(flatten_row, igea_rigid, "igea", true)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_MAIN();
