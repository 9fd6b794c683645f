// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/solid_grid.h"

#include <algorithm>
#include <cmath>

namespace meshquilt::quilt {

SolidGrid::SolidGrid(const Mesh& m, int cells) {
    if (m.vertices.empty() || m.faces.empty() || cells < 1) return;
    Vec3 lo = m.vertices.front(), hi = lo;
    for (const Vec3& v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Vec3 size = hi - lo;
    const double longest = size.maxCoeff();
    if (!(longest > 0.0) || !std::isfinite(longest)) return;
    h_ = longest / cells;
    lo_ = lo;
    nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / h_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / h_)));
    nz_ = std::max(1, static_cast<int>(std::ceil(size.z() / h_)));
    std::vector<std::vector<double>> column(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    // Column centres are offset by a tiny irrational share of a cell, so no centre lies on a
    // vertex or an edge of a mesh whose coordinates sit on the grid (a crossing counted twice or
    // not at all would flip the column's parity).
    const double ox = 0.5 + 1.4142135623730951e-7, oy = 0.5 + 1.7320508075688772e-7;
    for (const Tri& t : m.faces) {
        const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
        const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        if (det == 0.0) continue;  // vertical: no column crosses it
        const int i0 = std::max(0, static_cast<int>(std::floor((std::min({a.x(), b.x(), c.x()}) - lo_.x()) / h_ - ox)));
        const int i1 = std::min(nx_ - 1, static_cast<int>(std::ceil((std::max({a.x(), b.x(), c.x()}) - lo_.x()) / h_ - ox)));
        const int j0 = std::max(0, static_cast<int>(std::floor((std::min({a.y(), b.y(), c.y()}) - lo_.y()) / h_ - oy)));
        const int j1 = std::min(ny_ - 1, static_cast<int>(std::ceil((std::max({a.y(), b.y(), c.y()}) - lo_.y()) / h_ - oy)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double x = lo_.x() + (i + ox) * h_, y = lo_.y() + (j + oy) * h_;
                const double u = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) / det;
                const double v = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) / det;
                const double w = 1.0 - u - v;
                if (u < 0.0 || v < 0.0 || w < 0.0) continue;
                column[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i)].push_back(u * a.z() + v * b.z() + w * c.z());
            }
    }
    in_.assign(column.size() * static_cast<std::size_t>(nz_), 0);
    for (std::size_t col = 0; col < column.size(); ++col) {
        std::vector<double>& z = column[col];
        if (z.size() % 2 != 0) continue;
        std::sort(z.begin(), z.end());
        for (std::size_t s = 0; s + 1 < z.size(); s += 2)
            for (int k = std::max(0, static_cast<int>(std::ceil((z[s] - lo_.z()) / h_ - 0.5))); k < nz_; ++k) {
                if (lo_.z() + (k + 0.5) * h_ > z[s + 1]) break;
                in_[col * static_cast<std::size_t>(nz_) + static_cast<std::size_t>(k)] = 1;
            }
    }
}

}  // namespace meshquilt::quilt
