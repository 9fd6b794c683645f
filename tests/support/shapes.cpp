// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/shapes.h"

#include "meshquilt/analysis.h"
#include "meshquilt/quilt.h"
#include "quilt/swatch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>
#include <set>
#include <stdexcept>

namespace meshquilt::test::shapes {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Two triangles for the quad a b c d (counter-clockwise).
void add_quad(Mesh& m, int a, int b, int c, int d) {
    m.faces.emplace_back(a, b, c);
    m.faces.emplace_back(a, c, d);
}

}  // namespace

Mesh cube(double size, const Vec3& origin) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.push_back(origin + size * Vec3((i & 1) ? 1.0 : 0.0, (i & 2) ? 1.0 : 0.0, (i & 4) ? 1.0 : 0.0));
    // vertex i has x = bit 0, y = bit 1, z = bit 2
    add_quad(m, 0, 2, 3, 1);  // z = 0, normal -z
    add_quad(m, 4, 5, 7, 6);  // z = 1, normal +z
    add_quad(m, 0, 1, 5, 4);  // y = 0, normal -y
    add_quad(m, 2, 6, 7, 3);  // y = 1, normal +y
    add_quad(m, 0, 4, 6, 2);  // x = 0, normal -x
    add_quad(m, 1, 3, 7, 5);  // x = 1, normal +x
    return m;
}

Mesh fan_disc(double radius, int n) {
    if (n < 3) throw std::invalid_argument("fan_disc needs n >= 3");
    Mesh m;
    m.vertices.emplace_back(0.0, 0.0, 0.0);
    for (int i = 0; i < n; ++i) m.vertices.emplace_back(radius * std::cos(2 * kPi * i / n), radius * std::sin(2 * kPi * i / n), 0.0);
    for (int i = 0; i < n; ++i) m.faces.emplace_back(0, 1 + i, 1 + (i + 1) % n);
    return m;
}

Mesh fan_cube(double size, int n) {
    if (n < 1) throw std::invalid_argument("fan_cube needs n >= 1");
    Mesh m;
    // Vertices on the cube's edges are shared: keyed by their integer coordinates on a grid of n
    // steps per edge.
    std::map<std::tuple<int, int, int>, int> id;
    auto vertex = [&](int i, int j, int k) {
        auto [it, fresh] = id.emplace(std::make_tuple(i, j, k), static_cast<int>(m.vertices.size()));
        if (fresh) m.vertices.emplace_back(size * (static_cast<double>(i) / n - 0.5), size * (static_cast<double>(j) / n - 0.5),
                                           size * (static_cast<double>(k) / n - 0.5));
        return it->second;
    };
    // Each face: axis `a` fixed at side s (0 or n), u and v the other axes with u x v = +a.
    for (int a = 0; a < 3; ++a)
        for (int s = 0; s <= n; s += n) {
            const int u = (a + 1) % 3, v = (a + 2) % 3;
            auto at = [&](int iu, int iv) {
                std::array<int, 3> c{};
                c[static_cast<std::size_t>(a)] = s;
                c[static_cast<std::size_t>(u)] = iu;
                c[static_cast<std::size_t>(v)] = iv;
                return vertex(c[0], c[1], c[2]);
            };
            // The boundary loop, counter-clockwise seen from +a.
            std::vector<int> loop;
            for (int i = 0; i < n; ++i) loop.push_back(at(i, 0));
            for (int i = 0; i < n; ++i) loop.push_back(at(n, i));
            for (int i = n; i > 0; --i) loop.push_back(at(i, n));
            for (int i = n; i > 0; --i) loop.push_back(at(0, i));
            Vec3 centre = Vec3::Constant(0.0);
            centre[a] = size * (s == 0 ? -0.5 : 0.5);
            const int c = static_cast<int>(m.vertices.size());
            m.vertices.push_back(centre);
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const int p = loop[i], q = loop[(i + 1) % loop.size()];
                if (s == n) m.faces.emplace_back(c, p, q);
                else m.faces.emplace_back(c, q, p);  // the -a side faces the other way
            }
        }
    return m;
}

Mesh torus(double major, double minor, int nu, int nv) {
    if (nu < 3 || nv < 3) throw std::invalid_argument("torus needs nu, nv >= 3");
    Mesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
            m.vertices.emplace_back((major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u),
                                    minor * std::sin(v));
        }
    auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) add_quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    return m;
}

Mesh open_cylinder(double radius, double height, int segments, int rings) {
    if (segments < 3 || rings < 1) throw std::invalid_argument("open_cylinder needs segments >= 3, rings >= 1");
    Mesh m;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * kPi * s / segments;
            m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), height * r / rings);
        }
    auto id = [&](int r, int s) { return r * segments + (s % segments); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) add_quad(m, id(r, s), id(r, s + 1), id(r + 1, s + 1), id(r + 1, s));
    return m;
}

Mesh capsule(double radius, double length, int segments, int cap_rings, int rings) {
    if (segments < 3 || cap_rings < 2 || rings < 1) throw std::invalid_argument("capsule needs segments >= 3, cap_rings >= 2, rings >= 1");
    Mesh m;
    // Rings of latitude from the south pole up: cap_rings - 1 on the lower hemisphere, rings + 1
    // along the tube (its two ends are the hemispheres' equators), cap_rings - 1 on the upper one.
    std::vector<std::pair<double, double>> lat;  // (ring radius, z)
    for (int i = 1; i < cap_rings; ++i) {
        const double t = -0.5 * kPi + 0.5 * kPi * i / cap_rings;
        lat.emplace_back(radius * std::cos(t), radius * std::sin(t));
    }
    for (int i = 0; i <= rings; ++i) lat.emplace_back(radius, length * i / rings);
    for (int i = cap_rings - 1; i >= 1; --i) {
        const double t = -0.5 * kPi + 0.5 * kPi * i / cap_rings;
        lat.emplace_back(radius * std::cos(t), length - radius * std::sin(t));
    }
    m.vertices.emplace_back(0.0, 0.0, -radius);
    for (const auto& [r, z] : lat)
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * kPi * s / segments;
            m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
        }
    const int top = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(0.0, 0.0, length + radius);
    auto id = [&](int r, int s) { return 1 + r * segments + (s % segments); };
    const int n = static_cast<int>(lat.size());
    for (int s = 0; s < segments; ++s) {
        m.faces.emplace_back(0, id(0, s + 1), id(0, s));
        m.faces.emplace_back(top, id(n - 1, s), id(n - 1, s + 1));
    }
    for (int r = 0; r + 1 < n; ++r)
        for (int s = 0; s < segments; ++s) add_quad(m, id(r, s), id(r, s + 1), id(r + 1, s + 1), id(r + 1, s));
    return m;
}

Mesh subdivided(const Mesh& mesh) {
    Mesh m;
    m.vertices = mesh.vertices;
    std::map<std::pair<int, int>, int> mid;
    auto at = [&](int a, int b) {
        const auto key = std::minmax(a, b);
        auto [it, fresh] = mid.try_emplace({key.first, key.second}, static_cast<int>(m.vertices.size()));
        if (fresh) m.vertices.push_back(0.5 * (mesh.vertices[static_cast<std::size_t>(a)] + mesh.vertices[static_cast<std::size_t>(b)]));
        return it->second;
    };
    for (const Tri& t : mesh.faces) {
        const int ab = at(t[0], t[1]), bc = at(t[1], t[2]), ca = at(t[2], t[0]);
        m.faces.emplace_back(t[0], ab, ca);
        m.faces.emplace_back(ab, t[1], bc);
        m.faces.emplace_back(ca, bc, t[2]);
        m.faces.emplace_back(ab, bc, ca);
    }
    return m;
}

Mesh grid(int n, double size) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.vertices.emplace_back(size * i / n, size * j / n, 0.0);
    auto id = [&](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) add_quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    return m;
}

Mesh voxels(const std::vector<std::array<int, 3>>& cells) {
    const std::set<std::array<int, 3>> filled(cells.begin(), cells.end());
    Mesh m;
    std::map<std::array<int, 3>, int> index;
    auto vertex = [&](std::array<int, 3> p) {
        auto [it, inserted] = index.try_emplace(p, static_cast<int>(m.vertices.size()));
        if (inserted) m.vertices.emplace_back(p[0], p[1], p[2]);
        return it->second;
    };
    for (const auto& c : filled)
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                std::array<int, 3> n = c;
                n[static_cast<std::size_t>(axis)] += side ? 1 : -1;
                if (filled.count(n)) continue;
                // The face of the voxel on plane axis = c[axis] + side, with the other two axes u, v
                // chosen so (u, v, axis) is right-handed; counter-clockwise seen from outside.
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                std::array<int, 3> p[4];
                for (int k = 0; k < 4; ++k) {
                    p[k] = c;
                    p[k][static_cast<std::size_t>(axis)] += side;
                }
                p[1][static_cast<std::size_t>(u)] += 1;
                p[2][static_cast<std::size_t>(u)] += 1;
                p[2][static_cast<std::size_t>(v)] += 1;
                p[3][static_cast<std::size_t>(v)] += 1;
                const int a = vertex(p[0]), b = vertex(p[1]), cc = vertex(p[2]), d = vertex(p[3]);
                if (side) add_quad(m, a, b, cc, d);
                else add_quad(m, a, d, cc, b);
            }
    return m;
}

Mesh double_torus() {
    std::vector<std::array<int, 3>> cells;
    for (int x = 0; x < 5; ++x)
        for (int y = 0; y < 3; ++y)
            if (!(y == 1 && (x == 1 || x == 3))) cells.push_back({x, y, 0});
    return voxels(cells);
}

Mesh grid_net(int n, double pitch, double bar, double h, double cell) {
    const int N = static_cast<int>(std::lround((n * pitch + bar) / cell));
    auto filled = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= N || j >= N) return false;
        const double x = (i + 0.5) * cell, y = (j + 0.5) * cell;
        return std::fmod(x, pitch) < bar || std::fmod(y, pitch) < bar;
    };
    Mesh m;
    std::map<std::tuple<int, int, int>, int> index;
    auto v = [&](int i, int j, int k) {
        auto [it, fresh] = index.emplace(std::make_tuple(i, j, k), static_cast<int>(m.vertices.size()));
        if (fresh) m.vertices.emplace_back(i * cell, j * cell, k * h);
        return it->second;
    };
    auto quad = [&](int a, int b, int c, int d) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
    };
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            if (!filled(i, j)) continue;
            quad(v(i, j, 1), v(i + 1, j, 1), v(i + 1, j + 1, 1), v(i, j + 1, 1));
            quad(v(i, j, 0), v(i, j + 1, 0), v(i + 1, j + 1, 0), v(i + 1, j, 0));
            if (!filled(i - 1, j)) quad(v(i, j, 0), v(i, j, 1), v(i, j + 1, 1), v(i, j + 1, 0));
            if (!filled(i + 1, j)) quad(v(i + 1, j, 0), v(i + 1, j + 1, 0), v(i + 1, j + 1, 1), v(i + 1, j, 1));
            if (!filled(i, j - 1)) quad(v(i, j, 0), v(i + 1, j, 0), v(i + 1, j, 1), v(i, j, 1));
            if (!filled(i, j + 1)) quad(v(i, j + 1, 0), v(i, j + 1, 1), v(i + 1, j + 1, 1), v(i + 1, j + 1, 0));
        }
    return m;
}

namespace {

/// Calls fn(along, across, z) for each of the 2n threads of a plain weave, `pitch` apart:
/// `along` 0 for the warps (along x), 1 for the wefts (along y); `across` the thread's centre
/// line across; z(t) its height at t along it, rising and falling by `amplitude` (a cosine) over
/// and under the threads it crosses (warp i over weft j at t = (j + 0.5) pitch where i + j is even).
template <class Fn>
void for_each_weave_thread(int n, double pitch, double amplitude, Fn fn) {
    for (int along = 0; along < 2; ++along)
        for (int i = 0; i < n; ++i) {
            const double sign = along == 0 ? 1.0 : -1.0;
            fn(along, (i + 0.5) * pitch, [=](double t) { return sign * amplitude * std::cos(M_PI * (t / pitch - 0.5) + M_PI * i); });
        }
}

}  // namespace

Mesh ribbon_weave(int n, double pitch, double width, double amplitude, int segments) {
    Mesh m;
    const double length = n * pitch;
    for_each_weave_thread(n, pitch, amplitude, [&](int along, double across, auto z_at) {
        const int first = static_cast<int>(m.vertices.size());
        for (int k = 0; k <= segments; ++k) {
            const double t = length * k / segments, z = z_at(t);
            for (int s = 0; s < 3; ++s) {
                const double c = across + (s - 1) * 0.5 * width;
                m.vertices.push_back(along == 0 ? Vec3(t, c, z) : Vec3(c, t, z));
            }
        }
        for (int k = 0; k < segments; ++k)
            for (int s = 0; s < 2; ++s) {
                const int a = first + 3 * k + s, b = a + 1, c = a + 3, d = a + 4;
                // Faces up: (t, across) is right-handed for warps, left-handed for wefts.
                if (along == 0) {
                    m.faces.push_back({a, c, d});
                    m.faces.push_back({a, d, b});
                } else {
                    m.faces.push_back({a, b, d});
                    m.faces.push_back({a, d, c});
                }
            }
    });
    return m;
}

Mesh round_weave(int n, double pitch, double half_width, double half_height, double amplitude, int sides, int segments) {
    Mesh m;
    const double length = n * pitch;
    for_each_weave_thread(n, pitch, amplitude, [&](int along, double across, auto z_at) {
        const int first = static_cast<int>(m.vertices.size());
        auto point = [&](double t, double c, double z) { return along == 0 ? Vec3(t, c, z) : Vec3(c, t, z); };
        for (int k = 0; k <= segments; ++k) {
            const double t = length * k / segments, z = z_at(t);
            for (int s = 0; s < sides; ++s) {
                const double a = 2.0 * M_PI * (s + 0.5) / sides;
                m.vertices.push_back(point(t, across + half_width * std::cos(a), z + half_height * std::sin(a)));
            }
        }
        const int caps = static_cast<int>(m.vertices.size());
        m.vertices.push_back(point(0.0, across, z_at(0.0)));
        m.vertices.push_back(point(length, across, z_at(length)));
        // Round (t, across, z) a thread is right-handed for warps and left-handed for wefts: the
        // faces below are inward for warps (flipped) and outward for wefts.
        std::vector<Tri> faces;
        for (int k = 0; k < segments; ++k)
            for (int s = 0; s < sides; ++s) {
                const int a = first + k * sides + s, b = first + k * sides + (s + 1) % sides, c = a + sides, d = b + sides;
                faces.push_back({a, c, d});
                faces.push_back({a, d, b});
            }
        for (int s = 0; s < sides; ++s) {
            const int s1 = (s + 1) % sides;
            faces.push_back({caps, first + s, first + s1});
            faces.push_back({caps + 1, first + segments * sides + s1, first + segments * sides + s});
        }
        for (Tri f : faces) {
            if (along == 0) std::swap(f[1], f[2]);
            m.faces.push_back(f);
        }
    });
    return m;
}

Mesh concat(const Mesh& a, const Mesh& b) {
    Mesh m = a;
    const int offset = static_cast<int>(a.vertices.size());
    m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (const Tri& t : b.faces) m.faces.push_back(t + Tri::Constant(offset));
    return m;
}

Mesh translated(Mesh mesh, const Vec3& offset) {
    for (Vec3& v : mesh.vertices) v += offset;
    return mesh;
}

Mesh flipped(Mesh mesh) {
    for (Tri& t : mesh.faces) std::swap(t[1], t[2]);
    return mesh;
}

Mesh soup(const Mesh& mesh) {
    Mesh m;
    for (const Tri& t : mesh.faces) {
        const int base = static_cast<int>(m.vertices.size());
        for (int k = 0; k < 3; ++k) m.vertices.push_back(mesh.vertices[static_cast<std::size_t>(t[k])]);
        m.faces.emplace_back(base, base + 1, base + 2);
    }
    return m;
}

Mesh thickened(const Mesh& swatch, double by) {
    Mesh m = normalize_swatch(swatch);
    int n = 0;
    const std::vector<int> comp = connected_components(m, &n);
    quilt::thicken_elements(&m, comp, std::vector<double>(static_cast<std::size_t>(n), by));
    return normalize_swatch(m);
}

}  // namespace meshquilt::test::shapes
