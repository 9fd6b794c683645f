// SPDX-License-Identifier: AGPL-3.0-or-later
// Print checks on closed bodies: the thinnest feature (inward rays from face centroids through a
// CGAL AABB tree) and the smallest clearance between bodies (CGAL box_self_intersection_d broad
// phase, exact CGAL triangle-triangle squared distances).

#include "core/triangle_index.h"
#include "meshquilt/errors.h"
#include "print_detail.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

namespace meshquilt::print_detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using T3 = K::Triangle_3;
using TriIt = std::vector<T3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, TriIt>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

inline P3 pt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 vec(const P3& p) { return {p.x(), p.y(), p.z()}; }
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

std::vector<Mesh> split_elements(const ElementMesh& model) {
    const std::size_t n = static_cast<std::size_t>(std::max(model.num_elements, 0));
    if (model.element_of_face.size() != model.mesh.faces.size())
        throw InvalidInput("element_of_face has " + std::to_string(model.element_of_face.size()) + " entries for " +
                           std::to_string(model.mesh.faces.size()) + " faces");
    std::vector<std::vector<std::size_t>> faces_of(n);
    const auto nv = static_cast<long long>(model.mesh.vertices.size());
    for (std::size_t f = 0; f < model.mesh.faces.size(); ++f) {
        const int e = model.element_of_face[f];
        if (e < 0 || static_cast<std::size_t>(e) >= n)
            throw InvalidInput("face " + std::to_string(f) + " has element id " + std::to_string(e) + ", outside [0, " + std::to_string(n) + ")");
        for (int k = 0; k < 3; ++k)
            if (model.mesh.faces[f][k] < 0 || model.mesh.faces[f][k] >= nv)
                throw InvalidInput("face " + std::to_string(f) + " has vertex index " + std::to_string(model.mesh.faces[f][k]) + " out of range");
        faces_of[static_cast<std::size_t>(e)].push_back(f);
    }
    std::vector<Mesh> bodies(n);
    std::vector<int> index(model.mesh.vertices.size(), -1), stamp(model.mesh.vertices.size(), -1);
    for (std::size_t e = 0; e < n; ++e) {
        Mesh& body = bodies[e];
        for (std::size_t f : faces_of[e]) {
            Tri t;
            for (int k = 0; k < 3; ++k) {
                const auto v = static_cast<std::size_t>(model.mesh.faces[f][k]);
                if (stamp[v] != static_cast<int>(e)) {  // first use in this element (a vertex shared by two is copied)
                    stamp[v] = static_cast<int>(e);
                    index[v] = static_cast<int>(body.vertices.size());
                    body.vertices.push_back(model.mesh.vertices[v]);
                }
                t[k] = index[v];
            }
            body.faces.push_back(t);
        }
    }
    return bodies;
}

std::vector<double> face_thickness(const Mesh& body) {
    std::vector<double> out(body.faces.size(), kInf);
    if (body.faces.empty()) return out;
    std::vector<T3> tris;
    tris.reserve(body.faces.size());
    for (const Tri& t : body.faces) tris.emplace_back(pt(body.vertices[t[0]]), pt(body.vertices[t[1]]), pt(body.vertices[t[2]]));
    Tree tree(tris.cbegin(), tris.cend());
    tree.accelerate_distance_queries();
    for (std::size_t f = 0; f < body.faces.size(); ++f) {
        const Vec3 n = face_cross(body, f);
        const double len = n.norm();
        if (!(len > 0.0)) continue;
        const Vec3 c = face_centroid(body, f);
        const K::Ray_3 ray(pt(c), pt(c - n / len));
        const TriIt self = tris.cbegin() + static_cast<std::ptrdiff_t>(f);
        const auto hit = tree.first_intersection(ray, [self](const TriIt& id) { return id == self; });
        if (!hit) continue;
        if (const P3* p = boost::get<P3>(&hit->first)) out[f] = (vec(*p) - c).norm();
        else if (const K::Segment_3* s = boost::get<K::Segment_3>(&hit->first))
            out[f] = std::min((vec(s->source()) - c).norm(), (vec(s->target()) - c).norm());
    }
    return out;
}

ElementThickness element_thickness(const ElementMesh& model) {
    ElementThickness out;
    const auto n = static_cast<std::size_t>(std::max(model.num_elements, 0));
    out.min_of_element.assign(n, kInf);
    out.at_of_element.assign(n, Vec3::Zero());
    out.of_face.assign(model.mesh.faces.size(), kInf);
    const std::vector<Mesh> bodies = split_elements(model);  // validates the element ids first
    std::vector<std::vector<int>> faces_of(n);
    for (std::size_t f = 0; f < model.mesh.faces.size(); ++f) faces_of[static_cast<std::size_t>(model.element_of_face[f])].push_back(static_cast<int>(f));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t e = r.begin(); e != r.end(); ++e) {
            const Mesh& body = bodies[e];
            const std::vector<double> th = face_thickness(body);
            for (std::size_t i = 0; i < th.size(); ++i) {
                out.of_face[static_cast<std::size_t>(faces_of[e][i])] = th[i];
                if (th[i] < out.min_of_element[e]) {
                    out.min_of_element[e] = th[i];
                    out.at_of_element[e] = face_centroid(body, i);
                }
            }
        }
    });
    return out;
}

Clearances clearances(const ElementMesh& model, double threshold) {
    Clearances out;
    const Mesh& m = model.mesh;
    if (model.num_elements < 2) return out;
    const Box3 all = bounding_box(m);
    const double diag = all.size().norm();
    using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Tri*>;
    std::vector<CGAL::Bbox_3> tight(m.faces.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Tri& t = m.faces[f];
        tight[f] = pt(m.vertices[t[0]]).bbox() + pt(m.vertices[t[1]]).bbox() + pt(m.vertices[t[2]]).bbox();
    }
    const auto triangle = [&](std::size_t f) {
        const Tri& t = m.faces[f];
        return T3(pt(m.vertices[t[0]]), pt(m.vertices[t[1]]), pt(m.vertices[t[2]]));
    };
    struct Candidate {
        int f, g;
        double d2;
    };
    // One exact pass: every pair of faces of different elements closer than `radius` (their boxes
    // padded by radius / 2 overlap); true when one was found.
    const auto pass = [&](double radius) -> bool {
        const double pad = 0.5 * radius;
        std::vector<Box> boxes;
        boxes.reserve(m.faces.size());
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            const CGAL::Bbox_3& b = tight[f];
            boxes.emplace_back(CGAL::Bbox_3(b.xmin() - pad, b.ymin() - pad, b.zmin() - pad, b.xmax() + pad, b.ymax() + pad, b.zmax() + pad),
                               &m.faces[f]);
        }
        std::vector<Candidate> cand;
        const Tri* first = m.faces.data();
        CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
            const int f = static_cast<int>(a.handle() - first), g = static_cast<int>(b.handle() - first);
            if (model.element_of_face[static_cast<std::size_t>(f)] != model.element_of_face[static_cast<std::size_t>(g)])
                cand.push_back({std::min(f, g), std::max(f, g), 0.0});
        });
        // The broad phase's order depends on its internal sorting only, but sort anyway so every
        // tie below is broken the same way.
        std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) { return x.f != y.f ? x.f < y.f : x.g < y.g; });
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                cand[i].d2 = CGAL::to_double(CGAL::squared_distance(triangle(static_cast<std::size_t>(cand[i].f)), triangle(static_cast<std::size_t>(cand[i].g))));
        });
        // Per element pair: the closest candidate.
        std::map<std::pair<int, int>, const Candidate*> best;
        for (const Candidate& c : cand) {
            const int ea = model.element_of_face[static_cast<std::size_t>(c.f)], eb = model.element_of_face[static_cast<std::size_t>(c.g)];
            const auto key = std::minmax(ea, eb);
            auto it = best.find(key);
            if (it == best.end() || c.d2 < it->second->d2) best[key] = &c;
        }
        const double r2 = radius * radius;
        bool found = false;
        for (const auto& [key, c] : best) {
            if (c->d2 > r2) continue;
            found = true;
            const double d = std::sqrt(c->d2);
            const Vec3 at = 0.5 * (face_centroid(m, static_cast<std::size_t>(c->f)) + face_centroid(m, static_cast<std::size_t>(c->g)));
            if (out.min < 0.0 || d < out.min) {
                out.min = d;
                out.at = at;
                out.a = key.first;
                out.b = key.second;
            }
            if (d == 0.0) ++out.intersecting_pairs;
            if (d < threshold || d == 0.0)
                out.below.push_back({PrintViolation::Kind::Clearance, d, at, key.first, key.second});
        }
        return found;
    };
    const double first = threshold > 0.0 ? threshold : 1e-3 * diag;
    if (!pass(first)) {
        // Nothing within the threshold (so no violations). The smallest clearance still has to be
        // found, without a blind widening that would pair up every face of two big bodies: vertex
        // distances between the nearest bodies bound it from above, then one exact pass at that
        // radius finds it.
        const std::vector<Mesh> bodies = split_elements(model);
        std::vector<Box3> boxes(bodies.size());
        for (std::size_t e = 0; e < bodies.size(); ++e) boxes[e] = bounding_box(bodies[e]);
        std::vector<std::pair<int, int>> near;
        for (double reach = first; near.empty() && reach < 4.0 * diag; reach *= 4.0) {
            using BodyBox = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Box3*>;
            std::vector<BodyBox> bb;
            for (const Box3& b : boxes)
                if (!b.empty())
                    bb.emplace_back(CGAL::Bbox_3(b.min.x() - reach, b.min.y() - reach, b.min.z() - reach, b.max.x() + reach, b.max.y() + reach,
                                                 b.max.z() + reach),
                                    &b);
            CGAL::box_self_intersection_d(bb.begin(), bb.end(), [&](const BodyBox& a, const BodyBox& b) {
                const int i = static_cast<int>(a.handle() - boxes.data()), j = static_cast<int>(b.handle() - boxes.data());
                near.emplace_back(std::min(i, j), std::max(i, j));
            });
        }
        std::sort(near.begin(), near.end());
        std::vector<char> needed(bodies.size(), 0);
        for (const auto& [a, b] : near) needed[static_cast<std::size_t>(a)] = needed[static_cast<std::size_t>(b)] = 1;
        std::vector<std::unique_ptr<TriangleIndex>> index(bodies.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bodies.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t e = r.begin(); e != r.end(); ++e)
                if (needed[e]) index[e] = std::make_unique<TriangleIndex>(bodies[e]);
        });
        std::vector<double> bound(near.size(), kInf);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, near.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const auto [a, b] = near[i];
                for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}})
                    for (const Vec3& v : bodies[static_cast<std::size_t>(from)].vertices)
                        bound[i] = std::min(bound[i], index[static_cast<std::size_t>(to)]->closest(v).distance);
            }
        });
        const double upper = bound.empty() ? kInf : *std::min_element(bound.begin(), bound.end());
        // The bound is a true distance (a vertex to a face), so the exact pass at it finds a pair.
        double radius = std::isfinite(upper) ? upper * (1.0 + 1e-9) + 1e-12 * diag : 4.0 * first;
        while (!pass(radius) && radius < 4.0 * diag) radius *= 4.0;
    }
    std::stable_sort(out.below.begin(), out.below.end(), [](const PrintViolation& x, const PrintViolation& y) { return x.value_mm < y.value_mm; });
    return out;
}

}  // namespace meshquilt::print_detail
