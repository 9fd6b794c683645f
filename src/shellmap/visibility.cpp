// SPDX-License-Identifier: AGPL-3.0-or-later
#include "shellmap/visibility.h"

#include "core/triangle_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshquilt::shell {

namespace {
double least_cos(const std::vector<Vec3>& normals, const Vec3& d) {
    double c = std::numeric_limits<double>::infinity();
    for (const Vec3& n : normals) c = std::min(c, d.dot(n));
    return c;
}
}  // namespace

double best_visibility(const std::vector<Vec3>& normals, const Vec3& start, Vec3* best) {
    *best = start;
    double best_cos = least_cos(normals, start);
    auto consider = [&](Vec3 d) {
        if (!(d.norm() > 1e-12) || !d.allFinite()) return;
        d.normalize();
        for (const Vec3& c : {d, Vec3(-d)}) {
            const double w = least_cos(normals, c);
            if (w > best_cos) {
                best_cos = w;
                *best = c;
            }
        }
    };
    const std::size_t n = std::min<std::size_t>(normals.size(), 16);
    for (std::size_t a = 0; a < n; ++a) {
        consider(normals[a]);
        for (std::size_t b = a + 1; b < n; ++b) {
            consider(normals[a] + normals[b]);
            for (std::size_t c = b + 1; c < n; ++c) consider((normals[a] - normals[b]).cross(normals[a] - normals[c]));
        }
    }
    return best_cos;
}

int smooth_folds(Mesh& mesh, double min_cos, int rounds) {
    const std::size_t V = mesh.vertices.size();
    std::vector<std::vector<int>> faces_of(V), ring(V);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            faces_of[static_cast<std::size_t>(mesh.faces[f][k])].push_back(static_cast<int>(f));
            ring[static_cast<std::size_t>(mesh.faces[f][k])].push_back(mesh.faces[f][(k + 1) % 3]);
            ring[static_cast<std::size_t>(mesh.faces[f][(k + 1) % 3])].push_back(mesh.faces[f][k]);
        }
    for (auto& r : ring) {
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
    }
    // Moving a fold vertex to its neighbours' mean can converge while the ring around it stays
    // folded; then the smoothed neighbourhood grows (up to `kMaxRings` rings around the folds).
    constexpr int kMaxRings = 4;
    std::vector<char> moved(V, 0);
    int rings = 0, stalled = 0;
    std::size_t fewest = std::numeric_limits<std::size_t>::max();
    for (int round = 0; round < rounds; ++round) {
        const std::vector<Vec3> fn = face_normals(mesh);
        std::vector<int> folds;
        for (std::size_t v = 0; v < V; ++v) {
            if (faces_of[v].empty()) continue;
            std::vector<Vec3> normals;
            Vec3 sum = Vec3::Zero();
            for (int f : faces_of[v]) {
                normals.push_back(fn[static_cast<std::size_t>(f)]);
                sum += fn[static_cast<std::size_t>(f)];
            }
            Vec3 d;
            if (best_visibility(normals, sum.norm() > 0 ? Vec3(sum.normalized()) : normals.front(), &d) < min_cos) folds.push_back(static_cast<int>(v));
        }
        if (folds.empty()) break;
        if (folds.size() < fewest) {
            fewest = folds.size();
            stalled = 0;
        } else if (++stalled >= 3 && rings < kMaxRings) {
            ++rings;
            stalled = 0;
        }
        std::vector<char> in(V, 0);
        std::vector<int> region = folds;
        for (int v : folds) in[static_cast<std::size_t>(v)] = 1;
        for (int r = 0, begin = 0; r < rings; ++r) {
            const int end = static_cast<int>(region.size());
            for (int i = begin; i < end; ++i)
                for (int w : ring[static_cast<std::size_t>(region[static_cast<std::size_t>(i)])])
                    if (!in[static_cast<std::size_t>(w)]) {
                        in[static_cast<std::size_t>(w)] = 1;
                        region.push_back(w);
                    }
            begin = end;
        }
        std::vector<Vec3> target(region.size());
        for (std::size_t i = 0; i < region.size(); ++i) {
            Vec3 c = Vec3::Zero();
            for (int w : ring[static_cast<std::size_t>(region[i])]) c += mesh.vertices[static_cast<std::size_t>(w)];
            target[i] = c / static_cast<double>(ring[static_cast<std::size_t>(region[i])].size());
        }
        for (std::size_t i = 0; i < region.size(); ++i) {
            mesh.vertices[static_cast<std::size_t>(region[i])] = target[i];
            moved[static_cast<std::size_t>(region[i])] = 1;
        }
    }
    return static_cast<int>(std::count(moved.begin(), moved.end(), 1));
}

}  // namespace meshquilt::shell
