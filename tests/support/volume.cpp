// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/volume.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace meshquilt::test {

double union_volume_by_rays(const std::vector<Mesh>& bodies, int n) {
    Box3 box;
    for (const Mesh& m : bodies) box.extend(bounding_box(m));
    if (box.empty() || n < 1) return 0.0;
    // Cell centres shifted by an irrational fraction so that no ray runs exactly through an edge
    // of a mesh built on round coordinates.
    const double dx = (box.max.x() - box.min.x()) / n, dy = (box.max.y() - box.min.y()) / n;
    const double fx = 0.5 + 0.0137 * std::sqrt(2.0), fy = 0.5 + 0.0091 * std::sqrt(3.0);
    struct Event {
        double z;
        int body;
        int step;  // +1 entering (facet facing down), -1 leaving
    };
    std::vector<std::vector<Event>> events(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const Mesh& m = bodies[b];
        for (const Tri& t : m.faces) {
            const Vec3 &p = m.vertices[t[0]], &q = m.vertices[t[1]], &r = m.vertices[t[2]];
            const double det = (q.x() - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (q.y() - p.y());
            if (det == 0.0) continue;  // vertical facet: no ray crosses it through its interior
            const int i0 = std::max(0, static_cast<int>(std::floor((std::min({p.x(), q.x(), r.x()}) - box.min.x()) / dx - fx)));
            const int i1 = std::min(n - 1, static_cast<int>(std::ceil((std::max({p.x(), q.x(), r.x()}) - box.min.x()) / dx - fx)));
            const int j0 = std::max(0, static_cast<int>(std::floor((std::min({p.y(), q.y(), r.y()}) - box.min.y()) / dy - fy)));
            const int j1 = std::min(n - 1, static_cast<int>(std::ceil((std::max({p.y(), q.y(), r.y()}) - box.min.y()) / dy - fy)));
            for (int i = i0; i <= i1; ++i)
                for (int j = j0; j <= j1; ++j) {
                    const double x = box.min.x() + (i + fx) * dx, y = box.min.y() + (j + fy) * dy;
                    const double u = ((q.x() - x) * (r.y() - y) - (r.x() - x) * (q.y() - y)) / det;
                    const double v = ((r.x() - x) * (p.y() - y) - (p.x() - x) * (r.y() - y)) / det;
                    const double w = 1.0 - u - v;
                    if (u < 0.0 || v < 0.0 || w < 0.0) continue;
                    const double z = u * p.z() + v * q.z() + w * r.z();
                    // det > 0: the facet faces up (counter-clockwise seen from above): the ray leaves.
                    events[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)].push_back(
                        {z, static_cast<int>(b), det > 0.0 ? -1 : +1});
                }
        }
    }
    double volume = 0.0;
    std::vector<int> winding(bodies.size(), 0);
    for (auto& ev : events) {
        if (ev.empty()) continue;
        std::sort(ev.begin(), ev.end(), [](const Event& a, const Event& b) { return a.z < b.z; });
        std::fill(winding.begin(), winding.end(), 0);
        int inside = 0;
        double from = 0.0, length = 0.0;
        for (const Event& e : ev) {
            const bool was = winding[static_cast<std::size_t>(e.body)] > 0;
            winding[static_cast<std::size_t>(e.body)] += e.step;
            const bool is = winding[static_cast<std::size_t>(e.body)] > 0;
            if (was == is) continue;
            if (is && inside++ == 0) from = e.z;
            if (!is && --inside == 0) length += e.z - from;
        }
        volume += length;
    }
    return volume * dx * dy;
}

}  // namespace meshquilt::test
