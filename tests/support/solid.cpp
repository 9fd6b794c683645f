// SPDX-License-Identifier: AGPL-3.0-or-later
#include "support/solid.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>

namespace meshquilt::test {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<SM>>>;
}  // namespace

struct Solid::Impl {
    SM sm;
    std::unique_ptr<Tree> tree;
    std::unique_ptr<CGAL::Side_of_triangle_mesh<SM, K>> side;
};

Solid::Solid(const Mesh& m) : impl_(std::make_unique<Impl>()) {
    for (const Vec3& v : m.vertices) impl_->sm.add_vertex(K::Point_3(v.x(), v.y(), v.z()));
    for (const Tri& t : m.faces)
        impl_->sm.add_face(SM::Vertex_index(static_cast<SM::size_type>(t[0])), SM::Vertex_index(static_cast<SM::size_type>(t[1])),
                           SM::Vertex_index(static_cast<SM::size_type>(t[2])));
    impl_->tree = std::make_unique<Tree>(faces(impl_->sm).first, faces(impl_->sm).second, impl_->sm);
    impl_->tree->accelerate_distance_queries();
    impl_->side = std::make_unique<CGAL::Side_of_triangle_mesh<SM, K>>(*impl_->tree);
}

Solid::~Solid() = default;

bool Solid::inside(const Vec3& p, double margin) const {
    const K::Point_3 q(p.x(), p.y(), p.z());
    if ((*impl_->side)(q) != CGAL::ON_BOUNDED_SIDE) return false;
    return margin <= 0.0 || std::sqrt(impl_->tree->squared_distance(q)) > margin;
}

double Solid::distance(const Vec3& p) const { return std::sqrt(impl_->tree->squared_distance(K::Point_3(p.x(), p.y(), p.z()))); }

}  // namespace meshquilt::test
