// SPDX-License-Identifier: AGPL-3.0-or-later
// Print checks on closed bodies: the thinnest feature (inward rays from face centroids through a
// CGAL AABB tree) and the smallest clearance between bodies (CGAL box_self_intersection_d broad
// phase, exact CGAL triangle-triangle squared distances).

#include "core/triangle_index.h"
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
    const auto n = static_cast<std::size_t>(model.num_elements);
    out.min_of_element.assign(n, kInf);
    out.at_of_element.assign(n, Vec3::Zero());
    out.of_face.assign(model.mesh.faces.size(), kInf);
    std::vector<std::vector<int>> faces_of(n);
    for (std::size_t f = 0; f < model.mesh.faces.size(); ++f) faces_of[static_cast<std::size_t>(model.element_of_face[f])].push_back(static_cast<int>(f));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t e = r.begin(); e != r.end(); ++e) {
            Mesh body;
            std::map<int, int> index;
            for (int f : faces_of[e]) {
                Tri t;
                for (int k = 0; k < 3; ++k) {
                    const int v = model.mesh.faces[static_cast<std::size_t>(f)][k];
                    auto [it, fresh] = index.emplace(v, static_cast<int>(body.vertices.size()));
                    if (fresh) body.vertices.push_back(model.mesh.vertices[static_cast<std::size_t>(v)]);
                    t[k] = it->second;
                }
                body.faces.push_back(t);
            }
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
    double radius = threshold > 0.0 ? threshold : 1e-3 * diag;
    struct Candidate {
        int f, g;
        double d2;
    };
    for (;;) {
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
        if (found || radius > 2.0 * diag) break;
        radius *= 4.0;  // nothing this close: widen (violations, if any, were all in the first round)
    }
    std::stable_sort(out.below.begin(), out.below.end(), [](const PrintViolation& x, const PrintViolation& y) { return x.value_mm < y.value_mm; });
    return out;
}

}  // namespace meshquilt::print_detail
