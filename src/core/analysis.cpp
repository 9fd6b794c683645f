// SPDX-License-Identifier: AGPL-3.0-or-later
// Elements (connected components), edge structure, closedness, genus, boundary loops and defect
// counts of an indexed triangle mesh. O(F log F): one sort of the half-edges, then union-finds.

#include "core/analysis_detail.h"
#include "meshquilt/errors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace meshquilt {

namespace analysis_detail {

namespace {

std::string number(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

std::string edge_text(int a, int b) { return "between vertices " + std::to_string(a) + " and " + std::to_string(b); }

}  // namespace

std::string count_of(long long n, const char* singular, const char* plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

std::vector<HalfEdge> sorted_half_edges(const Mesh& mesh) {
    std::vector<HalfEdge> he;
    he.reserve(mesh.faces.size() * 3);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        if (has_repeated_index(t)) continue;
        for (int k = 0; k < 3; ++k) he.push_back({edge_key(t[k], t[(k + 1) % 3]), static_cast<int>(3 * f) + k});
    }
    std::sort(he.begin(), he.end(),
              [](const HalfEdge& a, const HalfEdge& b) { return a.key < b.key || (a.key == b.key && a.corner < b.corner); });
    return he;
}

std::string RangeCheck::phrase(std::size_t num_vertices) const {
    return count_of(count, "face has a vertex index", "faces have vertex indices") + " out of range (first: face " +
           std::to_string(first_face) + " uses vertex " + std::to_string(first_index) + ", the mesh has " +
           std::to_string(num_vertices) + " vertices)";
}

RangeCheck check_indices(const Mesh& mesh) {
    RangeCheck r;
    const auto nv = static_cast<long long>(mesh.vertices.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || t[k] >= nv) {
                if (r.count++ == 0) {
                    r.first_face = static_cast<int>(f);
                    r.first_index = t[k];
                }
                break;
            }
    }
    return r;
}

std::vector<char> referenced_vertices(const Mesh& mesh) {
    std::vector<char> used(mesh.vertices.size(), 0);
    const auto nv = static_cast<long long>(mesh.vertices.size());
    for (const Tri& t : mesh.faces)
        for (int k = 0; k < 3; ++k)
            if (t[k] >= 0 && t[k] < nv) used[static_cast<std::size_t>(t[k])] = 1;
    return used;
}

std::string NonFiniteCheck::phrase() const {
    return count_of(count(), "vertex has a non-finite coordinate", "vertices have non-finite coordinates") +
           " (first: vertex " + std::to_string(first) + ")";
}

NonFiniteCheck check_finite(const Mesh& mesh, const std::vector<char>& referenced) {
    NonFiniteCheck r;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (mesh.vertices[v].allFinite()) continue;
        if (r.first < 0) r.first = static_cast<int>(v);
        (referenced[v] ? r.referenced : r.unreferenced)++;
    }
    return r;
}

std::string DegenerateCheck::phrase() const {
    return count_of(count, "degenerate face", "degenerate faces") + " (first: face " + std::to_string(first) +
           (first_repeated ? ", which repeats a vertex)" : ", which has zero area)");
}

DegenerateCheck find_degenerate_faces(const Mesh& mesh) {
    DegenerateCheck r;
    r.is_degenerate.assign(mesh.faces.size(), 0);
    const double diagonal2 = bounding_box(mesh).size().squaredNorm();
    const double min_area = kDegenerateAreaFactor * diagonal2;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        const bool repeated = has_repeated_index(t);
        bool degenerate = repeated;
        if (!repeated) {
            const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
            const double area =
                0.5 * (mesh.vertices[static_cast<std::size_t>(t[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a).norm();
            degenerate = area <= min_area;  // false for NaN: non-finite vertices are reported on their own
        }
        if (!degenerate) continue;
        r.is_degenerate[f] = 1;
        if (r.count++ == 0) {
            r.first = static_cast<int>(f);
            r.first_repeated = repeated;
        }
    }
    return r;
}

std::string DuplicateCheck::phrase() const {
    return count_of(count, "duplicate vertex", "duplicate vertices") + " (first: vertex " + std::to_string(first) +
           " is at the position of vertex " + std::to_string(first_of) + ")";
}

DuplicateCheck find_duplicate_vertices(const Mesh& mesh) {
    DuplicateCheck r;
    const std::size_t nv = mesh.vertices.size();
    r.representative.resize(nv);
    std::iota(r.representative.begin(), r.representative.end(), 0);
    const std::vector<char> used = referenced_vertices(mesh);
    std::vector<int> order;
    order.reserve(nv);
    for (std::size_t v = 0; v < nv; ++v)
        if (used[v] && mesh.vertices[v].allFinite()) order.push_back(static_cast<int>(v));
    const auto less = [&](int a, int b) {
        const Vec3& p = mesh.vertices[static_cast<std::size_t>(a)];
        const Vec3& q = mesh.vertices[static_cast<std::size_t>(b)];
        if (p.x() != q.x()) return p.x() < q.x();
        if (p.y() != q.y()) return p.y() < q.y();
        if (p.z() != q.z()) return p.z() < q.z();
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 0; i < order.size();) {
        std::size_t j = i + 1;
        const Vec3& p = mesh.vertices[static_cast<std::size_t>(order[i])];
        while (j < order.size() && mesh.vertices[static_cast<std::size_t>(order[j])] == p) ++j;
        // order[i] is the lowest index of the run (ties sort by index)
        for (std::size_t k = i + 1; k < j; ++k) {
            const int v = order[k];
            r.representative[static_cast<std::size_t>(v)] = order[i];
            ++r.count;
            if (r.first < 0 || v < r.first) {
                r.first = v;
                r.first_of = order[i];
            }
        }
        i = j;
    }
    return r;
}

std::string Topology::non_manifold_edges_phrase() const {
    const EdgeName& e = first_non_manifold_edge;
    return count_of(non_manifold_edges, "non-manifold edge", "non-manifold edges") + " (first " + edge_text(std::min(e.from, e.to), std::max(e.from, e.to)) +
           ", shared by " + std::to_string(e.faces) + " faces)";
}

std::string Topology::non_manifold_vertices_phrase() const {
    return count_of(non_manifold_vertices, "non-manifold vertex", "non-manifold vertices") + " (first: vertex " +
           std::to_string(first_non_manifold_vertex) + ", where " + std::to_string(fans_at_first_non_manifold_vertex) +
           " separate fans of faces meet)";
}

std::string Topology::inconsistent_phrase() const {
    const EdgeName& e = first_inconsistent_edge;
    return count_of(inconsistent_edges, "edge with inconsistent orientation", "edges with inconsistent orientation") +
           " (first " + edge_text(std::min(e.from, e.to), std::max(e.from, e.to)) + ": both of its faces run from vertex " +
           std::to_string(e.from) + " to " + std::to_string(e.to) + ")";
}

std::vector<int> Topology::inside_out_elements() const {
    std::vector<int> out;
    for (std::size_t i = 0; i < elements.size(); ++i)
        if (elements[i].closed && elements[i].volume < 0.0) out.push_back(static_cast<int>(i));
    return out;
}

std::string Topology::inside_out_phrase() const {
    const std::vector<int> bad = inside_out_elements();
    if (bad.empty()) return {};
    return count_of(static_cast<long long>(bad.size()), "closed element is", "closed elements are") +
           " inside out (first: element " + std::to_string(bad[0]) + ", signed volume " +
           number(elements[static_cast<std::size_t>(bad[0])].volume) + ")";
}

Topology compute_topology(const Mesh& mesh) {
    Topology topo;
    const std::size_t nf = mesh.faces.size();
    const std::size_t nv = mesh.vertices.size();
    int num_components = 0;
    topo.component_of_face = connected_components(mesh, &num_components);
    const std::vector<int>& comp = topo.component_of_face;
    topo.elements.resize(static_cast<std::size_t>(num_components));
    auto element_of_face = [&](std::size_t f) -> ElementInfo& { return topo.elements[static_cast<std::size_t>(comp[f])]; };

    // Per-element face counts, areas, boxes, volumes; Euler counts V and F of faces in the edge structure.
    std::vector<int> vertex_component(nv, -1);
    std::vector<char> vertex_in_topology(nv, 0);
    std::vector<long long> euler_v(topo.elements.size(), 0), euler_e(topo.elements.size(), 0), euler_f(topo.elements.size(), 0);
    std::vector<char> has_topology(topo.elements.size(), 0);
    for (std::size_t f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        ElementInfo& el = element_of_face(f);
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        el.faces++;
        el.area += 0.5 * (b - a).cross(c - a).norm();
        el.volume += a.dot(b.cross(c)) / 6.0;  // divergence theorem; kept only for closed elements
        el.box.extend(a);
        el.box.extend(b);
        el.box.extend(c);
        const bool in_topology = !has_repeated_index(t);
        if (in_topology) {
            euler_f[static_cast<std::size_t>(comp[f])]++;
            has_topology[static_cast<std::size_t>(comp[f])] = 1;
        }
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<std::size_t>(t[k]);
            if (vertex_component[v] < 0) {
                vertex_component[v] = comp[f];
                el.vertices++;
            }
            if (in_topology && !vertex_in_topology[v]) {
                vertex_in_topology[v] = 1;
                euler_v[static_cast<std::size_t>(comp[f])]++;
            }
        }
    }
    for (std::size_t i = 0; i < topo.elements.size(); ++i) topo.elements[i].closed = has_topology[i] != 0;

    // Edges: runs of equal keys in the sorted half-edges.
    const std::vector<HalfEdge> he = sorted_half_edges(mesh);
    auto from_vertex = [&](int corner) { return mesh.faces[static_cast<std::size_t>(corner / 3)][corner % 3]; };
    auto to_vertex = [&](int corner) { return mesh.faces[static_cast<std::size_t>(corner / 3)][(corner % 3 + 1) % 3]; };
    auto next_corner = [](int corner) { return corner - corner % 3 + (corner % 3 + 1) % 3; };
    // Corners (face, vertex) are joined when their faces share an edge at that vertex: the corners
    // of one vertex then fall into one class per fan.
    UnionFind corners(3 * nf);
    std::vector<int> boundary;  // corners of boundary half-edges
    int first_non_manifold_corner = -1, first_inconsistent_corner = -1;
    for (std::size_t i = 0; i < he.size();) {
        std::size_t j = i + 1;
        while (j < he.size() && he[j].key == he[i].key) ++j;
        const std::size_t n = j - i;
        const int c0 = he[i].corner;  // the lowest corner: the first face that uses the edge
        ElementInfo& el = element_of_face(static_cast<std::size_t>(c0 / 3));
        euler_e[static_cast<std::size_t>(comp[static_cast<std::size_t>(c0 / 3)])]++;
        if (n == 1) {
            topo.boundary_edges++;
            el.closed = false;
            boundary.push_back(c0);
        } else if (n == 2) {
            if (from_vertex(c0) == from_vertex(he[i + 1].corner)) {
                topo.inconsistent_edges++;
                el.closed = false;
                if (first_inconsistent_corner < 0 || c0 < first_inconsistent_corner) {
                    first_inconsistent_corner = c0;
                    topo.first_inconsistent_edge = {from_vertex(c0), to_vertex(c0), 2};
                }
            }
        } else {
            topo.non_manifold_edges++;
            el.closed = false;
            el.edge_manifold = false;
            if (first_non_manifold_corner < 0 || c0 < first_non_manifold_corner) {
                first_non_manifold_corner = c0;
                topo.first_non_manifold_edge = {from_vertex(c0), to_vertex(c0), static_cast<int>(n)};
            }
        }
        if (n >= 2) {
            const int a = from_vertex(c0);
            for (std::size_t k = i + 1; k < j; ++k) {
                const int c = he[k].corner;
                // the corner of c's face at vertex a, and at the other end of the edge
                const int at_a = from_vertex(c) == a ? c : next_corner(c);
                const int at_b = from_vertex(c) == a ? next_corner(c) : c;
                corners.unite(at_a, c0);
                corners.unite(at_b, next_corner(c0));
            }
        }
        i = j;
    }

    // Fans around each vertex: distinct corner classes among the corners at the vertex.
    std::vector<int> start(nv + 1, 0);
    for (std::size_t f = 0; f < nf; ++f)
        if (!has_repeated_index(mesh.faces[f]))
            for (int k = 0; k < 3; ++k) start[static_cast<std::size_t>(mesh.faces[f][k]) + 1]++;
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<int> corner_at(static_cast<std::size_t>(start[nv]));
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (std::size_t f = 0; f < nf; ++f)
            if (!has_repeated_index(mesh.faces[f]))
                for (int k = 0; k < 3; ++k)
                    corner_at[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh.faces[f][k])]++)] = static_cast<int>(3 * f) + k;
    }
    topo.fan_of_corner.assign(3 * nf, -1);
    for (std::size_t f = 0; f < nf; ++f)
        if (!has_repeated_index(mesh.faces[f]))
            for (int k = 0; k < 3; ++k) topo.fan_of_corner[3 * f + static_cast<std::size_t>(k)] = corners.find(static_cast<int>(3 * f) + k);
    std::vector<int> roots;
    for (std::size_t v = 0; v < nv; ++v) {
        roots.clear();
        for (int i = start[v]; i < start[v + 1]; ++i) roots.push_back(corners.find(corner_at[static_cast<std::size_t>(i)]));
        std::sort(roots.begin(), roots.end());
        const auto fans = static_cast<int>(std::unique(roots.begin(), roots.end()) - roots.begin());
        if (fans > 1 && topo.non_manifold_vertices++ == 0) {
            topo.first_non_manifold_vertex = static_cast<int>(v);
            topo.fans_at_first_non_manifold_vertex = fans;
        }
    }

    // Boundary loops: boundary edges whose ends lie in the same fan of a vertex follow each other
    // along a loop. Linking by fan, not just by vertex, counts two holes that touch at a vertex as two.
    UnionFind loops(boundary.size());
    std::vector<int> boundary_at_fan(3 * nf, -1);
    for (std::size_t e = 0; e < boundary.size(); ++e)
        for (const int corner : {boundary[e], next_corner(boundary[e])}) {
            int& first = boundary_at_fan[static_cast<std::size_t>(corners.find(corner))];
            if (first < 0) first = static_cast<int>(e);
            else loops.unite(static_cast<int>(e), first);
        }
    for (std::size_t e = 0; e < boundary.size(); ++e)
        if (loops.find(static_cast<int>(e)) == static_cast<int>(e)) element_of_face(static_cast<std::size_t>(boundary[e] / 3)).boundary_loops++;

    for (std::size_t i = 0; i < topo.elements.size(); ++i) {
        ElementInfo& el = topo.elements[i];
        const long long chi = euler_v[i] - euler_e[i] + euler_f[i];  // = 2 - 2g - b
        const long long twice_genus = 2 - el.boundary_loops - chi;
        el.genus = twice_genus > 0 ? static_cast<int>(twice_genus / 2) : 0;
        if (!el.closed) el.volume = 0.0;
    }
    return topo;
}

std::string unreferenced_phrase(int count, int first) {
    return count_of(count, "unreferenced vertex", "unreferenced vertices") + " (first: vertex " + std::to_string(first) + ")";
}

std::string thin_axis_phrase(const Box3& box) {
    const Vec3 s = box.size();
    double e[3] = {s.x(), s.y(), s.z()};
    std::sort(e, e + 3);
    return "no thin axis: the smallest extent (" + number(e[0]) + ") is more than half the middle one (" + number(e[1]) +
           "); a swatch must be a slab";
}

}  // namespace analysis_detail

std::vector<int> connected_components(const Mesh& mesh, int* count) {
    using namespace analysis_detail;
    const RangeCheck range = check_indices(mesh);
    if (range.count > 0) throw InvalidInput("connected_components: " + range.phrase(mesh.vertices.size()));
    UnionFind uf(mesh.vertices.size());
    for (const Tri& t : mesh.faces) {
        uf.unite(t[0], t[1]);
        uf.unite(t[1], t[2]);
    }
    std::vector<int> id_of_root(mesh.vertices.size(), -1);
    std::vector<int> component(mesh.faces.size());
    int n = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        int& id = id_of_root[static_cast<std::size_t>(uf.find(mesh.faces[f][0]))];
        if (id < 0) id = n++;
        component[f] = id;
    }
    if (count) *count = n;
    return component;
}

int MeshAnalysis::closed_elements() const {
    return static_cast<int>(std::count_if(elements.begin(), elements.end(), [](const ElementInfo& e) { return e.closed; }));
}

MeshAnalysis analyse(const Mesh& mesh) {
    using namespace analysis_detail;
    MeshAnalysis a;
    const RangeCheck range = check_indices(mesh);
    if (range.count > 0) throw InvalidInput("analyse: " + range.phrase(mesh.vertices.size()));
    a.faces = static_cast<int>(mesh.faces.size());
    const std::vector<char> used = referenced_vertices(mesh);
    for (const char u : used) (u ? a.vertices : a.unreferenced_vertices)++;
    a.box = bounding_box(mesh);
    a.thin = thin_axis_of(a.box);
    if (mesh.faces.empty()) {
        a.problems.push_back("no faces");
        return a;
    }
    const NonFiniteCheck finite = check_finite(mesh, used);
    const DegenerateCheck degenerate = find_degenerate_faces(mesh);
    const DuplicateCheck duplicates = find_duplicate_vertices(mesh);
    Topology topo = compute_topology(mesh);

    // Same order and words as validate().
    if (finite.count() > 0) a.problems.push_back(finite.phrase());
    if (degenerate.count > 0) a.problems.push_back(degenerate.phrase());
    if (duplicates.count > 0) a.problems.push_back(duplicates.phrase());
    if (topo.non_manifold_edges > 0) a.problems.push_back(topo.non_manifold_edges_phrase());
    if (topo.non_manifold_vertices > 0) a.problems.push_back(topo.non_manifold_vertices_phrase());
    if (topo.inconsistent_edges > 0) a.problems.push_back(topo.inconsistent_phrase());
    if (!topo.inside_out_elements().empty()) a.problems.push_back(topo.inside_out_phrase());

    a.elements = std::move(topo.elements);
    for (const ElementInfo& e : a.elements) {
        a.genus += e.genus;
        a.boundary_loops += e.boundary_loops;
        a.area += e.area;
    }
    a.boundary_edges = topo.boundary_edges;
    a.non_manifold_edges = topo.non_manifold_edges;
    a.non_manifold_vertices = topo.non_manifold_vertices;
    a.inconsistent_edges = topo.inconsistent_edges;
    a.degenerate_faces = degenerate.count;
    a.duplicate_vertices = duplicates.count;
    return a;
}


int split_non_manifold_vertices(Mesh& mesh) {
    const analysis_detail::Topology topo = analysis_detail::compute_topology(mesh);
    if (topo.non_manifold_vertices == 0) return 0;
    const std::size_t nv = mesh.vertices.size();
    std::vector<int> first_fan(nv, -1);
    std::map<std::pair<int, int>, int> copy;  // (vertex, fan) -> the vertex's copy for that fan
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int fan = topo.fan_of_corner[3 * f + static_cast<std::size_t>(k)];
            if (fan < 0) continue;
            const auto v = static_cast<std::size_t>(mesh.faces[f][k]);
            if (first_fan[v] < 0) first_fan[v] = fan;
            if (first_fan[v] == fan) continue;
            const auto [it, fresh] = copy.try_emplace({static_cast<int>(v), fan}, static_cast<int>(mesh.vertices.size()));
            if (fresh) mesh.vertices.push_back(mesh.vertices[v]);
            const int to = it->second;
            mesh.faces[f][k] = to;
        }
    return static_cast<int>(mesh.vertices.size() - nv);
}

}  // namespace meshquilt
