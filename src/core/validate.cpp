// SPDX-License-Identifier: AGPL-3.0-or-later
// validate(): the checks a user's mesh must pass, in a fixed order, each failing with a message
// that names the first offending element; with `repair`, the safe repairs instead (dropping
// degenerate faces and unreferenced vertices, merging duplicate vertices, making face orientation
// consistent, splitting non-manifold vertices, turning inside-out closed elements right side
// out), each reported in words.

#include "core/analysis_detail.h"
#include "meshquilt/errors.h"

#include <algorithm>
#include <queue>

namespace meshquilt {

namespace {

using namespace analysis_detail;

/// Keeps the faces whose `drop` flag is 0.
void drop_faces(Mesh& mesh, const std::vector<char>& drop) {
    std::size_t out = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        if (!drop[f]) mesh.faces[out++] = mesh.faces[f];
    mesh.faces.resize(out);
}

void flip(Tri& t) { std::swap(t[1], t[2]); }

/// Result of making neighbouring faces agree on their orientation.
struct Reorientation {
    int flipped = 0;
    int non_orientable_face = -1;  // a face where the propagation met itself flipped (Moebius strip, Klein bottle)
};

/// Breadth-first over manifold edges: a neighbour that runs along the shared edge in the same
/// direction gets the opposite flip state. Each edge-connected region keeps the orientation of the
/// majority of its faces, so the fewest faces change. Needs a mesh without non-manifold edges.
Reorientation reorient(Mesh& mesh) {
    Reorientation r;
    const std::size_t nf = mesh.faces.size();
    const std::vector<HalfEdge> he = sorted_half_edges(mesh);
    auto from_vertex = [&](int corner) { return mesh.faces[static_cast<std::size_t>(corner / 3)][corner % 3]; };
    // neighbour of each corner's edge, as (face, same direction) packed as 2 * face + same
    std::vector<int> start(nf + 1, 0);
    std::vector<std::pair<int, int>> pairs;
    for (std::size_t i = 0; i + 1 < he.size(); ++i)
        if (he[i].key == he[i + 1].key && (i + 2 >= he.size() || he[i + 2].key != he[i].key) &&
            (i == 0 || he[i - 1].key != he[i].key)) {
            const int f = he[i].corner / 3, g = he[i + 1].corner / 3;
            const int same = from_vertex(he[i].corner) == from_vertex(he[i + 1].corner) ? 1 : 0;
            pairs.emplace_back(f, 2 * g + same);
            pairs.emplace_back(g, 2 * f + same);
        }
    for (const auto& p : pairs) start[static_cast<std::size_t>(p.first) + 1]++;
    for (std::size_t f = 0; f < nf; ++f) start[f + 1] += start[f];
    std::vector<int> adjacent(pairs.size());
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (const auto& p : pairs) adjacent[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.first)]++)] = p.second;
    }
    std::vector<signed char> state(nf, -1);  // -1 unvisited, 0 keep, 1 flip
    std::vector<int> region;
    for (std::size_t seed = 0; seed < nf; ++seed) {
        if (state[seed] >= 0) continue;
        region.clear();
        state[seed] = 0;
        region.push_back(static_cast<int>(seed));
        for (std::size_t i = 0; i < region.size(); ++i) {
            const auto f = static_cast<std::size_t>(region[i]);
            for (int k = start[f]; k < start[f + 1]; ++k) {
                const int packed = adjacent[static_cast<std::size_t>(k)];
                const auto g = static_cast<std::size_t>(packed / 2);
                const auto want = static_cast<signed char>(state[f] ^ (packed & 1));
                if (state[g] < 0) {
                    state[g] = want;
                    region.push_back(static_cast<int>(g));
                } else if (state[g] != want && r.non_orientable_face < 0) {
                    r.non_orientable_face = static_cast<int>(g);
                }
            }
        }
        const auto flips = std::count_if(region.begin(), region.end(), [&](int f) { return state[static_cast<std::size_t>(f)] == 1; });
        const bool invert = 2 * static_cast<std::size_t>(flips) > region.size();
        for (const int f : region) {
            auto& s = state[static_cast<std::size_t>(f)];
            if (invert) s = static_cast<signed char>(1 - s);
            if (s == 1) {
                flip(mesh.faces[static_cast<std::size_t>(f)]);
                r.flipped++;
            }
        }
    }
    return r;
}

}  // namespace

ValidationResult validate(const Mesh& input, const std::string& name, const ValidationOptions& options) {
    ValidationResult result;
    Mesh& mesh = result.mesh;
    mesh = input;
    const auto error = [&](const std::string& what) { throw InvalidInput(name + ": " + what); };
    const auto repaired = [&](const std::string& what) { result.repairs.push_back(name + ": " + what); };

    if (mesh.faces.empty()) error("no faces");

    // Non-finite coordinates are reported before bad indices, but need the indices to tell whether
    // a face uses the vertex.
    std::vector<char> used = referenced_vertices(mesh);
    const NonFiniteCheck finite = check_finite(mesh, used);
    if (finite.referenced > 0) error(finite.phrase());
    if (finite.unreferenced > 0 && !options.repair)
        error(finite.phrase() + "; no face uses them: pass --repair to drop unreferenced vertices");
    const RangeCheck range = check_indices(mesh);
    if (range.count > 0) error(range.phrase(mesh.vertices.size()));

    const DegenerateCheck degenerate = find_degenerate_faces(mesh);
    if (degenerate.count > 0) {
        if (!options.repair) error(degenerate.phrase() + "; pass --repair to drop degenerate faces");
        drop_faces(mesh, degenerate.is_degenerate);
        repaired("dropped " + degenerate.phrase());
        if (mesh.faces.empty()) error("no faces left after dropping " + count_of(degenerate.count, "degenerate face", "degenerate faces"));
    }

    const DuplicateCheck duplicates = find_duplicate_vertices(mesh);
    if (duplicates.count > 0) {
        if (options.repair) {
            for (Tri& t : mesh.faces)
                for (int k = 0; k < 3; ++k) t[k] = duplicates.representative[static_cast<std::size_t>(t[k])];
            repaired("merged " + duplicates.phrase());
            std::vector<char> collapsed(mesh.faces.size(), 0);
            int count = 0, first = -1;
            for (std::size_t f = 0; f < mesh.faces.size(); ++f)
                if (has_repeated_index(mesh.faces[f])) {
                    collapsed[f] = 1;
                    if (count++ == 0) first = static_cast<int>(f);
                }
            if (count > 0) {
                drop_faces(mesh, collapsed);
                repaired("dropped " + count_of(count, "face", "faces") + " that collapsed when duplicate vertices were merged (first: face " +
                         std::to_string(first) + " after the earlier repairs)");
                if (mesh.faces.empty()) error("no faces left after merging duplicate vertices");
            }
        } else {
            result.warnings.push_back(name + ": " + duplicates.phrase() +
                                      "; faces meeting there are not connected; pass --repair to merge them");
        }
    }

    Topology topo = compute_topology(mesh);
    if (topo.non_manifold_edges > 0)
        error(topo.non_manifold_edges_phrase() + "; repair the mesh so that every edge has at most two faces");
    if (topo.non_manifold_vertices > 0) {
        if (!options.repair) error(topo.non_manifold_vertices_phrase() + "; pass --repair to split each into one vertex per fan");
        const int added = split_non_manifold_vertices(mesh);
        repaired("split " + topo.non_manifold_vertices_phrase() + " into one vertex per fan (" + count_of(added, "vertex", "vertices") + " added)");
        topo = compute_topology(mesh);
    }
    if (topo.inconsistent_edges > 0) {
        if (!options.repair && !options.reorient) error(topo.inconsistent_phrase() + "; pass --repair to reorient the faces");
        const Reorientation r = reorient(mesh);
        if (r.non_orientable_face >= 0)
            error(topo.inconsistent_phrase() + "; the surface is not orientable (like a Moebius strip) near face " +
                  std::to_string(r.non_orientable_face) + ", so no orientation of its faces agrees");
        const std::string what = "reoriented " + count_of(r.flipped, "face", "faces") + " to fix " + topo.inconsistent_phrase();
        if (options.repair)
            repaired(what);
        else
            result.warnings.push_back(name + ": " + what + " (each connected piece keeps the side most of its faces face)");
        topo = compute_topology(mesh);
    }
    const std::vector<int> inside_out = topo.inside_out_elements();
    if (!inside_out.empty()) {
        if (options.repair) {
            for (std::size_t f = 0; f < mesh.faces.size(); ++f)
                if (std::binary_search(inside_out.begin(), inside_out.end(), topo.component_of_face[f])) flip(mesh.faces[f]);
            const ElementInfo& first = topo.elements[static_cast<std::size_t>(inside_out[0])];
            repaired("flipped " + count_of(static_cast<long long>(inside_out.size()), "inside-out closed element", "inside-out closed elements") +
                     " (first: element " + std::to_string(inside_out[0]) + ", " + std::to_string(first.faces) + " faces)");
        } else if (!options.reorient) {  // a base's inside-out pieces are flipped by the surface stage, which says so
            result.warnings.push_back(name + ": " + topo.inside_out_phrase() + "; pass --repair to flip them");
        }
    }

    if (options.require_thin_axis) {
        const Box3 box = bounding_box(mesh);
        const ThinAxis thin = thin_axis_of(box);
        if (!thin.is_thin) error(thin_axis_phrase(box));
        // A flat swatch (all in one plane) has a thin axis but no thickness: nothing to grow.
        if (!(thin.thickness > 1e-9 * box.size().maxCoeff()))
            error("flat: its thin axis (" + std::string(1, "xyz"[thin.axis]) +
                  ") has no thickness; a swatch's elements must be solids in a slab");
    }

    if (options.repair) {
        used = referenced_vertices(mesh);
        // Vertices merged into another were reported as merged; count only the others.
        int count = 0, first = -1;
        for (std::size_t v = 0; v < used.size(); ++v)
            if (!used[v] && (duplicates.count == 0 || duplicates.representative[v] == static_cast<int>(v)) && count++ == 0)
                first = static_cast<int>(v);
        if (std::count(used.begin(), used.end(), 0) > 0) {
            std::vector<int> new_index(mesh.vertices.size(), -1);
            std::size_t out = 0;
            for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
                if (used[v]) {
                    new_index[v] = static_cast<int>(out);
                    mesh.vertices[out++] = mesh.vertices[v];
                }
            mesh.vertices.resize(out);
            for (Tri& t : mesh.faces)
                for (int k = 0; k < 3; ++k) t[k] = new_index[static_cast<std::size_t>(t[k])];
            if (count > 0) repaired("dropped " + unreferenced_phrase(count, first));
        }
    }
    return result;
}

}  // namespace meshquilt
