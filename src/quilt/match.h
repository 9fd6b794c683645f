// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Geometry matching, Zhou et al. 2006 Section 2.4 (Eq. 1-3): the cost of placing the swatch at a
// translation t, E(t) = sum over output vertices v in P_out of min_f D(v, f + t).

#include "core/triangle_index.h"
#include "meshquilt/mesh.h"

#include <cstdint>
#include <random>
#include <vector>

namespace meshquilt::quilt {

/// An output point of the sub-patch with its unit normal.
struct Sample {
    Vec3 position;
    Vec3 normal;
};

struct MatchChoice {
    Vec2 translation = Vec2::Zero();  ///< where the swatch origin goes
    int index = -1;                   ///< index into the candidate list
    double cost = 0.0;                ///< E(t) / number of samples (>= 1; 1 is a perfect match)
    int candidates_within_tolerance = 0;
};

/// Evaluates E(t) for every candidate translation and picks one. Costs are first estimated on at
/// most `coarse_samples` of the samples, the best `refine_count` re-evaluated on all of them (up to
/// `fine_samples`); among those within `tolerance` of the best excess cost one is drawn from `rng`.
/// Deterministic for a given rng state; runs in parallel over translations.
MatchChoice choose_translation(const TriangleIndex& swatch, const MatchMetric& metric, const std::vector<Sample>& samples,
                               const std::vector<Vec2>& candidates, double tolerance, std::mt19937_64& rng,
                               int coarse_samples = 48, int fine_samples = 384, int refine_count = 8);

/// E(t) / |samples| for one translation (Eq. 3, normalised).
double matching_cost(const TriangleIndex& swatch, const MatchMetric& metric, const std::vector<Sample>& samples, const Vec2& t);

}  // namespace meshquilt::quilt
