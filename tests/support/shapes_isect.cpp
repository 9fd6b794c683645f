// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/shapes_isect.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace meshquilt::test::isect {

Eigen::Matrix3d rotation(const Vec3& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Mesh torus(double major, double minor, int nu, int nv, const Vec3& center, const Eigen::Matrix3d& rot) {
    if (nu < 3 || nv < 3) throw std::invalid_argument("torus: nu and nv must be >= 3");
    Mesh m;
    const double two_pi = 2.0 * M_PI;
    for (int i = 0; i < nu; ++i) {
        const double u = two_pi * i / nu;
        for (int j = 0; j < nv; ++j) {
            const double v = two_pi * j / nv;
            const Vec3 p((major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u),
                         minor * std::sin(v));
            m.vertices.push_back(rot * p + center);
        }
    }
    auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
    // (d/du x d/dv) points outwards, so (i,j) -> (i+1,j) -> (i+1,j+1) is counter-clockwise from outside.
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.faces.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.faces.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

Mesh icosphere(double radius, int subdivisions, const Vec3& center) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& v : V) v.normalize();
    std::vector<Tri> F = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                          {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4}, {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                          {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            V.push_back((V[static_cast<std::size_t>(a)] + V[static_cast<std::size_t>(b)]).normalized());
            const int id = static_cast<int>(V.size()) - 1;
            mid.emplace(key, id);
            return id;
        };
        std::vector<Tri> G;
        G.reserve(F.size() * 4);
        for (const Tri& f : F) {
            const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
            G.emplace_back(f[0], a, c);
            G.emplace_back(f[1], b, a);
            G.emplace_back(f[2], c, b);
            G.emplace_back(a, b, c);
        }
        F.swap(G);
    }
    Mesh m;
    m.vertices.reserve(V.size());
    for (const Vec3& v : V) m.vertices.push_back(radius * v + center);
    m.faces = std::move(F);
    return m;
}

Mesh cuboid(const Vec3& lo, const Vec3& hi) {
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
    // Two triangles per side, counter-clockwise from outside.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.faces.emplace_back(q[0], q[1], q[2]);
        m.faces.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

Mesh transformed(const Mesh& mesh, const Eigen::Matrix3d& rot, const Vec3& translation) {
    Mesh m = mesh;
    for (Vec3& v : m.vertices) v = rot * v + translation;
    return m;
}


}  // namespace meshquilt::test::isect
