// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/match.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

namespace meshquilt::quilt {

namespace {
/// Every k-th sample so that at most `count` remain (deterministic, spread over the input order).
std::vector<Sample> stride_subset(const std::vector<Sample>& s, int count) {
    if (static_cast<int>(s.size()) <= count) return s;
    std::vector<Sample> out;
    out.reserve(static_cast<std::size_t>(count));
    const double step = static_cast<double>(s.size()) / count;
    for (int i = 0; i < count; ++i) out.push_back(s[static_cast<std::size_t>(i * step)]);
    return out;
}
}  // namespace

double matching_cost(const TriangleIndex& swatch, const MatchMetric& metric, const std::vector<Sample>& samples, const Vec2& t) {
    if (samples.empty()) return 1.0;
    const Vec3 shift(t.x(), t.y(), 0.0);
    double sum = 0.0;
    for (const Sample& s : samples) {
        double score = 0.0;
        (void)swatch.best_match(s.position - shift, s.normal, metric, &score);  // Eq. 2
        sum += score;                                                           // Eq. 3
    }
    return sum / static_cast<double>(samples.size());
}

MatchChoice choose_translation(const TriangleIndex& swatch, const MatchMetric& metric, const std::vector<Sample>& samples,
                               const std::vector<Vec2>& candidates, double tolerance, std::mt19937_64& rng,
                               int coarse_samples, int fine_samples, int refine_count) {
    MatchChoice choice;
    if (candidates.empty()) return choice;
    if (samples.empty()) {
        std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
        choice.index = static_cast<int>(pick(rng));
        choice.translation = candidates[static_cast<std::size_t>(choice.index)];
        choice.cost = 1.0;
        choice.candidates_within_tolerance = static_cast<int>(candidates.size());
        return choice;
    }
    const std::vector<Sample> coarse = stride_subset(samples, coarse_samples);
    std::vector<double> cost(candidates.size());
    tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
        cost[i] = matching_cost(swatch, metric, coarse, candidates[i]);
    });
    std::vector<std::size_t> order(candidates.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
    order.resize(std::min(order.size(), static_cast<std::size_t>(refine_count)));

    const std::vector<Sample> fine = stride_subset(samples, fine_samples);
    std::vector<double> fine_cost(order.size());
    tbb::parallel_for(std::size_t(0), order.size(), [&](std::size_t k) {
        fine_cost[k] = matching_cost(swatch, metric, fine, candidates[order[k]]);
    });
    const double best = *std::min_element(fine_cost.begin(), fine_cost.end());
    // D >= 1, so E/N - 1 is the mismatch; keep those within tolerance of the best mismatch
    // (plus a small absolute slack so that several perfect matches all count).
    const double limit = 1.0 + (best - 1.0) * (1.0 + tolerance) + 0.01;
    std::vector<std::size_t> good;
    for (std::size_t k = 0; k < order.size(); ++k)
        if (fine_cost[k] <= limit) good.push_back(k);
    std::uniform_int_distribution<std::size_t> pick(0, good.size() - 1);
    const std::size_t k = good[pick(rng)];
    choice.index = static_cast<int>(order[k]);
    choice.translation = candidates[order[k]];
    choice.cost = fine_cost[k];
    choice.candidates_within_tolerance = static_cast<int>(good.size());
    return choice;
}

}  // namespace meshquilt::quilt
