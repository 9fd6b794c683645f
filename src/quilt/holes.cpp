// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/holes.h"

#include "meshquilt/analysis.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <array>
#include <map>
#include <functional>
#include <set>
#include <unordered_map>
#include <vector>

namespace meshquilt::quilt {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
namespace PMP = CGAL::Polygon_mesh_processing;

std::uint64_t edge_key(int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); }
}  // namespace

HoleFilling fill_small_holes(Mesh& m, double max_extent, int max_vertices) {
    HoleFilling r;
    // Boundary half-edges (a -> b as a face runs, with no face running b -> a), by their start. A
    // vertex where two holes touch starts two.
    std::unordered_map<std::uint64_t, int> directed;
    directed.reserve(3 * m.faces.size());
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) ++directed[edge_key(t[k], t[(k + 1) % 3])];
    std::map<int, std::vector<int>> out;  // ordered: loops are found in a fixed order (deterministic)
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k)
            if (!directed.count(edge_key(t[(k + 1) % 3], t[k]))) out[t[k]].push_back(t[(k + 1) % 3]);
    for (auto& [a, bs] : out) std::sort(bs.begin(), bs.end(), std::greater<>());  // taken from the back
    // Walks along boundary half-edges until none is left at the vertex reached (on an oriented mesh
    // with manifold edges, as many leave each vertex as arrive: the walk ends where it began), cut
    // into simple loops where it comes back to a vertex: each is one hole, also where holes touch.
    std::vector<std::vector<int>> loops;
    for (auto& [start, unused] : out)
        while (!unused.empty()) {
            std::vector<int> stack;
            std::unordered_map<int, std::size_t> at;  // vertex -> its place in stack
            for (int v = start;;) {
                if (const auto it = at.find(v); it != at.end()) {
                    loops.emplace_back(stack.begin() + static_cast<std::ptrdiff_t>(it->second), stack.end());
                    for (std::size_t i = it->second + 1; i < stack.size(); ++i) at.erase(stack[i]);
                    stack.resize(it->second + 1);
                } else {
                    at[v] = stack.size();
                    stack.push_back(v);
                }
                auto& next = out[v];
                if (next.empty()) break;
                v = next.back();
                next.pop_back();
            }
        }
    const std::size_t old_faces = m.faces.size();
    for (std::vector<int>& loop : loops) {
        if (loop.size() < 3) continue;
        ++r.loops;
        if (static_cast<int>(loop.size()) > max_vertices) continue;
        Box3 box;
        std::set<std::array<double, 3>> positions;
        for (const int v : loop) {
            const Vec3& p = m.vertices[static_cast<std::size_t>(v)];
            box.extend(p);
            positions.insert({p.x(), p.y(), p.z()});
        }
        const double extent = box.size().norm();
        if (extent > max_extent || positions.size() != loop.size()) continue;
        // The fill runs against the faces around it: along the loop reversed.
        std::reverse(loop.begin(), loop.end());
        std::vector<K::Point_3> points;
        for (const int v : loop) {
            const Vec3& p = m.vertices[static_cast<std::size_t>(v)];
            points.emplace_back(p.x(), p.y(), p.z());
        }
        std::vector<CGAL::Triple<int, int, int>> patch;
        try {
            PMP::triangulate_hole_polyline(points, std::back_inserter(patch));
        } catch (const std::exception&) {
            continue;
        }
        if (patch.size() != loop.size() - 2) continue;  // CGAL could not fill it
        // CGAL's triangles are oriented alike; the one on the loop's edge 0 -> 1 tells which way.
        bool forward = true;
        for (const auto& t : patch) {
            const std::array<int, 3> c{t.first, t.second, t.third};
            for (int k = 0; k < 3; ++k)
                if (c[static_cast<std::size_t>(k)] == 0 && c[static_cast<std::size_t>((k + 1) % 3)] == 1) forward = true;
                else if (c[static_cast<std::size_t>(k)] == 1 && c[static_cast<std::size_t>((k + 1) % 3)] == 0) forward = false;
        }
        for (const auto& t : patch) {
            const int a = loop[static_cast<std::size_t>(t.first)], b = loop[static_cast<std::size_t>(t.second)],
                      c = loop[static_cast<std::size_t>(t.third)];
            m.faces.push_back(forward ? Tri(a, b, c) : Tri(a, c, b));
        }
        ++r.filled;
        r.largest = std::max(r.largest, extent);
    }
    r.faces = static_cast<int>(m.faces.size() - old_faces);
    return r;
}

}  // namespace meshquilt::quilt
