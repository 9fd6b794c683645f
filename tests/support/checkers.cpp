// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/checkers.h"

#include "core/intersect.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace meshquilt::test {
namespace {

/// One use of an undirected edge (lo, hi) by a face; `forward` if the face goes lo -> hi.
struct EdgeUse {
    int group;  ///< element id, or 0 for the whole mesh
    int lo, hi;
    int face;
    bool forward;
    bool operator<(const EdgeUse& o) const {
        return std::tie(group, lo, hi, face) < std::tie(o.group, o.lo, o.hi, o.face);
    }
};

std::vector<EdgeUse> edge_uses(const Mesh& mesh, const std::vector<int>* group) {
    std::vector<EdgeUse> uses;
    uses.reserve(3 * mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            uses.push_back({group ? (*group)[f] : 0, std::min(a, b), std::max(a, b), static_cast<int>(f), a < b});
        }
    }
    std::sort(uses.begin(), uses.end());
    return uses;
}

/// Edge problems of one group (a run of EdgeUse with the same group).
struct EdgeReport {
    int boundary = 0, non_manifold = 0, inconsistent = 0;
    std::string first_boundary, first_non_manifold, first_inconsistent;
    [[nodiscard]] bool ok() const { return boundary == 0 && non_manifold == 0 && inconsistent == 0; }
    [[nodiscard]] std::string text() const {
        std::ostringstream s;
        s << boundary << " boundary edges" << first_boundary << ", " << non_manifold << " non-manifold edges"
          << first_non_manifold << ", " << inconsistent << " inconsistently oriented edges" << first_inconsistent;
        return s.str();
    }
};

std::string edge_name(const EdgeUse& u) {
    std::ostringstream s;
    s << "edge between vertices " << u.lo << " and " << u.hi;
    return s.str();
}

/// Calls fn(first, last) for each run of uses of the same edge of the same group.
template <class Fn>
void for_each_edge(const std::vector<EdgeUse>& uses, Fn&& fn) {
    for (std::size_t k = 0; k < uses.size();) {
        std::size_t e = k + 1;
        while (e < uses.size() && uses[e].group == uses[k].group && uses[e].lo == uses[k].lo && uses[e].hi == uses[k].hi)
            ++e;
        fn(k, e);
        k = e;
    }
}

void classify_edge(const std::vector<EdgeUse>& uses, std::size_t k, std::size_t e, EdgeReport& r) {
    const std::size_t n = e - k;
    if (n == 1) {
        if (r.boundary++ == 0) r.first_boundary = " (first: " + edge_name(uses[k]) + ", face " + std::to_string(uses[k].face) + ")";
    } else if (n > 2) {
        if (r.non_manifold++ == 0) {
            std::ostringstream s;
            s << " (first: " << edge_name(uses[k]) << ", " << n << " faces:";
            for (std::size_t j = k; j < e; ++j) s << ' ' << uses[j].face;
            s << ")";
            r.first_non_manifold = s.str();
        }
    } else if (uses[k].forward == uses[k + 1].forward) {
        if (r.inconsistent++ == 0)
            r.first_inconsistent = " (first: " + edge_name(uses[k]) + ", faces " + std::to_string(uses[k].face) + " and " +
                                   std::to_string(uses[k + 1].face) + " both go the same way)";
    }
}

::testing::AssertionResult check_faces(const Mesh& mesh, bool require_area) {
    const auto n = static_cast<long long>(mesh.vertices.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || t[k] >= n)
                return ::testing::AssertionFailure() << "face " << f << " has vertex index " << t[k] << " out of range [0, "
                                                     << n << ")";
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            return ::testing::AssertionFailure() << "face " << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
                                                 << ") repeats a vertex index";
        if (require_area) {
            const auto& V = mesh.vertices;
            for (int k = 0; k < 3; ++k)
                if (!V[static_cast<std::size_t>(t[k])].allFinite())
                    return ::testing::AssertionFailure() << "face " << f << " uses vertex " << t[k]
                                                         << " with a non-finite coordinate";
            if (is_degenerate_triangle(V[static_cast<std::size_t>(t[0])], V[static_cast<std::size_t>(t[1])],
                                       V[static_cast<std::size_t>(t[2])]))
                return ::testing::AssertionFailure() << "face " << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
                                                     << ") is degenerate: its corners are collinear";
        }
    }
    return ::testing::AssertionSuccess();
}

int find_root(std::vector<int>& parent, int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
        parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        x = parent[static_cast<std::size_t>(x)];
    }
    return x;
}

}  // namespace

::testing::AssertionResult is_closed_manifold(const Mesh& mesh) {
    if (mesh.faces.empty()) return ::testing::AssertionFailure() << "mesh has no faces";
    if (auto r = check_faces(mesh, true); !r) return r;

    const std::vector<EdgeUse> uses = edge_uses(mesh, nullptr);
    EdgeReport report;
    for_each_edge(uses, [&](std::size_t k, std::size_t e) { classify_edge(uses, k, e, report); });
    if (!report.ok()) return ::testing::AssertionFailure() << "not closed: " << report.text();

    // Single fan per vertex: join the corners of the two faces of every edge at both of its ends,
    // then count the groups of corners at each vertex.
    auto corner = [&](int face, int vertex) {
        const Tri& t = mesh.faces[static_cast<std::size_t>(face)];
        return 3 * face + (t[0] == vertex ? 0 : t[1] == vertex ? 1 : 2);
    };
    std::vector<int> parent(3 * mesh.faces.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (std::size_t k = 0; k < uses.size(); k += 2)
        for (int v : {uses[k].lo, uses[k].hi}) {
            const int a = find_root(parent, corner(uses[k].face, v)), b = find_root(parent, corner(uses[k + 1].face, v));
            parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
        }
    std::map<int, std::vector<int>> fans;  // vertex -> roots of its corners
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) fans[mesh.faces[f][k]].push_back(find_root(parent, static_cast<int>(3 * f) + k));
    int bad = 0;
    int first = -1;
    std::size_t first_fans = 0;
    for (auto& [v, roots] : fans) {
        std::sort(roots.begin(), roots.end());
        const auto count = static_cast<std::size_t>(std::unique(roots.begin(), roots.end()) - roots.begin());
        if (count > 1 && bad++ == 0) first = v, first_fans = count;
    }
    if (bad > 0)
        return ::testing::AssertionFailure() << bad << " non-manifold vertices (first: vertex " << first << " has "
                                             << first_fans << " separate fans of faces)";
    return ::testing::AssertionSuccess() << "closed manifold: " << mesh.faces.size() << " faces";
}

::testing::AssertionResult elements_closed(const Mesh& mesh, const std::vector<int>& element_of_face) {
    if (element_of_face.size() != mesh.faces.size())
        return ::testing::AssertionFailure() << "element_of_face has " << element_of_face.size() << " entries for "
                                             << mesh.faces.size() << " faces";
    if (auto r = check_faces(mesh, false); !r) {
        // Name the element of the bad face too.
        for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
            const Tri& t = mesh.faces[f];
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                return ::testing::AssertionFailure() << "element " << element_of_face[f] << ": " << r.message();
        }
        return r;
    }
    const std::vector<EdgeUse> uses = edge_uses(mesh, &element_of_face);
    std::map<int, EdgeReport> reports;
    for_each_edge(uses, [&](std::size_t k, std::size_t e) { classify_edge(uses, k, e, reports[uses[k].group]); });
    int failing = 0;
    const EdgeReport* first = nullptr;
    int first_id = -1;
    for (const auto& [id, r] : reports)
        if (!r.ok() && failing++ == 0) first = &r, first_id = id;
    if (failing > 0)
        return ::testing::AssertionFailure() << failing << " of " << reports.size() << " elements not closed; first: element "
                                             << first_id << ": " << first->text();
    return ::testing::AssertionSuccess() << reports.size() << " closed elements";
}

::testing::AssertionResult no_element_intersections(const Mesh& mesh, const std::vector<int>& element_of_face,
                                                    const std::vector<std::pair<int, int>>& allowed) {
    std::vector<std::pair<int, int>> ok;
    for (const auto& [a, b] : allowed) ok.emplace_back(std::min(a, b), std::max(a, b));
    std::sort(ok.begin(), ok.end());
    std::vector<std::pair<int, int>> bad;
    try {
        for (const auto& p : intersecting_element_pairs(mesh, element_of_face))
            if (!std::binary_search(ok.begin(), ok.end(), p)) bad.push_back(p);
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "cannot test intersections: " << e.what();
    }
    if (bad.empty()) return ::testing::AssertionSuccess() << "no intersecting elements";
    auto r = ::testing::AssertionFailure();
    r << bad.size() << " intersecting element pairs:";
    for (std::size_t k = 0; k < std::min<std::size_t>(bad.size(), 10); ++k) r << " (" << bad[k].first << ", " << bad[k].second << ")";
    if (bad.size() > 10) r << " ...";
    return r;
}

::testing::AssertionResult no_self_intersections(const Mesh& mesh) {
    int n = 0;
    try {
        n = count_self_intersections(mesh);
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "cannot test self-intersections: " << e.what();
    }
    if (n == 0) return ::testing::AssertionSuccess() << "no self-intersections";
    return ::testing::AssertionFailure() << n << " pairs of faces intersect";
}

std::vector<Mesh> split_elements(const Mesh& mesh, const std::vector<int>& element_of_face) {
    if (element_of_face.size() != mesh.faces.size()) throw std::invalid_argument("split_elements: element_of_face size != faces");
    int max_id = -1;
    for (int e : element_of_face) {
        if (e < 0) throw std::invalid_argument("split_elements: negative element id");
        max_id = std::max(max_id, e);
    }
    std::vector<Mesh> out(static_cast<std::size_t>(max_id + 1));
    std::vector<std::map<int, int>> remap(out.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const auto e = static_cast<std::size_t>(element_of_face[f]);
        Tri t;
        for (int k = 0; k < 3; ++k) {
            const auto [it, inserted] = remap[e].emplace(mesh.faces[f][k], static_cast<int>(out[e].vertices.size()));
            if (inserted) out[e].vertices.push_back(mesh.vertices[static_cast<std::size_t>(mesh.faces[f][k])]);
            t[k] = it->second;
        }
        out[e].faces.push_back(t);
    }
    return out;
}

int rounded_linking(const Mesh& ring_a, const Mesh& ring_b) {
    return static_cast<int>(std::lround(linking_number(ring_centerline(ring_a), ring_centerline(ring_b))));
}

std::map<int, int> link_counts(const std::vector<Mesh>& rings, double reach) {
    std::vector<std::vector<Vec3>> lines;
    std::vector<Vec3> centres;
    for (const Mesh& r : rings) {
        lines.push_back(ring_centerline(r));
        Vec3 c = Vec3::Zero();
        for (const Vec3& v : r.vertices) c += v;
        centres.push_back(c / static_cast<double>(std::max<std::size_t>(1, r.vertices.size())));
    }
    std::map<int, int> count;
    for (std::size_t i = 0; i < rings.size(); ++i)
        for (std::size_t j = i + 1; j < rings.size(); ++j) {
            if ((centres[i] - centres[j]).norm() > reach) continue;
            if (links_once(lines[i], lines[j])) {
                ++count[static_cast<int>(i)];
                ++count[static_cast<int>(j)];
            }
        }
    return count;
}

}  // namespace meshquilt::test
