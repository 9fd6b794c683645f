// SPDX-License-Identifier: AGPL-3.0-or-later
// Performance of the exact intersection tests (core/intersect.h) on chain-mail-like workloads:
// a sheet of rings where every ring is linked with its neighbours along a row (boxes overlap
// heavily, surfaces stay apart) and a few rings are pushed into a neighbour (real intersections).
//
//   bench_intersect --benchmark_counters_tabular=true
//
// Counters: faces, elements, pairs (intersecting element pairs found), hits (colliding elements
// found per query).

#include "core/intersect.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace {

using meshquilt::ElementCollider;
using meshquilt::ElementMesh;
using meshquilt::concatenate;
using meshquilt::Mesh;
using meshquilt::Tri;
using meshquilt::Vec3;

Mesh torus(double R, double r, int nu, int nv, const Vec3& center, const Eigen::Matrix3d& rot) {
    Mesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2.0 * M_PI * i / nu, v = 2.0 * M_PI * j / nv;
            m.vertices.push_back(rot * Vec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)) +
                                 center);
        }
    auto id = [&](int i, int j) { return (i % nu) * nv + j % nv; };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.faces.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.faces.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

/// Rings on an n x n grid: rows of linked rings (alternately in the xy and xz planes, 1.3 apart),
/// rows 2.1 apart so that diagonal neighbours' boxes overlap without contact. Every ring with
/// i % 16 == 5 is pushed 0.35 towards its left neighbour, into it.
std::vector<Mesh> chain_mail(int n, int nu, int nv) {
    const Eigen::Matrix3d flat = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d up = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    std::vector<Mesh> rings;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double push = i % 16 == 5 ? 0.35 : 0.0;
            rings.push_back(torus(1.0, 0.2, nu, nv, Vec3(1.3 * i + push, 2.1 * j, 0.0), (i + j) % 2 ? up : flat));
        }
    return rings;
}


// 32 x 32 rings of 288 faces: 294,912 faces, 1024 elements. Arg: threads.
void BM_IntersectingElementPairs(benchmark::State& state) {
    static const ElementMesh sheet = concatenate(chain_mail(32, 24, 6));
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
    std::size_t pairs = 0;
    for (auto _ : state) {
        auto p = meshquilt::intersecting_element_pairs(sheet.mesh, sheet.element_of_face);
        pairs = p.size();
        benchmark::DoNotOptimize(p.data());
    }
    state.counters["faces"] = static_cast<double>(sheet.mesh.faces.size());
    state.counters["elements"] = 1024;
    state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_IntersectingElementPairs)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// ElementCollider holding n x n rings; each query re-tests a copy of a stored ring (ignoring
// itself) against its neighbours, as the synthesis loop does for a new candidate.
// Args: n, nu, nv (faces per ring = 2 nu nv).
void BM_ElementColliderQuery(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    const auto rings = chain_mail(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
    ElementCollider collider;
    for (const Mesh& r : rings) collider.add(r);
    std::size_t q = 0, hits = 0, queries = 0;
    for (auto _ : state) {
        const int id = static_cast<int>((q * 7919) % rings.size());
        ++q;
        const auto c = collider.colliding(rings[static_cast<std::size_t>(id)], {id});
        hits += c.size();
        ++queries;
        benchmark::DoNotOptimize(c.data());
    }
    state.counters["faces_per_element"] = static_cast<double>(rings[0].faces.size());
    state.counters["elements"] = static_cast<double>(rings.size());
    state.counters["hits"] = static_cast<double>(hits) / static_cast<double>(queries);
    state.SetItemsProcessed(static_cast<std::int64_t>(queries));
}
BENCHMARK(BM_ElementColliderQuery)->Args({32, 24, 6})->Args({16, 48, 24})->Args({12, 96, 24})->Unit(benchmark::kMicrosecond);

// The same query with an early-exit yes/no answer.
void BM_ElementColliderCollides(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    const auto rings = chain_mail(16, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
    ElementCollider collider;
    for (const Mesh& r : rings) collider.add(r);
    std::size_t q = 0;
    for (auto _ : state) {
        const int id = static_cast<int>((q++ * 7919) % rings.size());
        benchmark::DoNotOptimize(collider.collides(rings[static_cast<std::size_t>(id)], {id}));
    }
    state.counters["faces_per_element"] = static_cast<double>(rings[0].faces.size());
}
BENCHMARK(BM_ElementColliderCollides)->Args({48, 24})->Unit(benchmark::kMicrosecond);

// Cost of add() (prepare triangles, boxes, tree; insert in the grid). Args: nu, nv.
void BM_ElementColliderAdd(benchmark::State& state) {
    const auto rings = chain_mail(8, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
    std::size_t k = 0;
    ElementCollider collider;
    for (auto _ : state) {
        if (k == rings.size()) {
            state.PauseTiming();
            collider = ElementCollider();
            k = 0;
            state.ResumeTiming();
        }
        benchmark::DoNotOptimize(collider.add(rings[k++]));
    }
    state.counters["faces_per_element"] = static_cast<double>(rings[0].faces.size());
}
BENCHMARK(BM_ElementColliderAdd)->Args({24, 6})->Args({48, 24})->Unit(benchmark::kMicrosecond);

// Self-intersection count of one element (adjacent faces are the common case). Args: nu, nv.
void BM_CountSelfIntersections(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    const Mesh ring = torus(1.0, 0.2, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), Vec3::Zero(),
                            Eigen::Matrix3d::Identity());
    for (auto _ : state) benchmark::DoNotOptimize(meshquilt::count_self_intersections(ring));
    state.counters["faces"] = static_cast<double>(ring.faces.size());
}
BENCHMARK(BM_CountSelfIntersections)->Args({48, 24})->Args({512, 128})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
