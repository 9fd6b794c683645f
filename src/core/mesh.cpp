// SPDX-License-Identifier: AGPL-3.0-or-later
#include "meshquilt/mesh.h"

namespace meshquilt {

Box3 bounding_box(const Mesh& mesh) {
    Box3 box;
    for (const Tri& f : mesh.faces)
        for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[static_cast<std::size_t>(f[k])]);
    return box;
}

ElementMesh concatenate(const std::vector<const Mesh*>& parts) {
    ElementMesh out;
    std::size_t nv = 0, nf = 0;
    for (const Mesh* m : parts) {
        nv += m->vertices.size();
        nf += m->faces.size();
    }
    out.mesh.vertices.reserve(nv);
    out.mesh.faces.reserve(nf);
    out.element_of_face.reserve(nf);
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const int offset = static_cast<int>(out.mesh.vertices.size());
        out.mesh.vertices.insert(out.mesh.vertices.end(), parts[k]->vertices.begin(), parts[k]->vertices.end());
        for (const Tri& f : parts[k]->faces) {
            out.mesh.faces.push_back(f + Tri::Constant(offset));
            out.element_of_face.push_back(static_cast<int>(k));
        }
    }
    out.num_elements = static_cast<int>(parts.size());
    return out;
}

ElementMesh concatenate(const std::vector<Mesh>& parts) {
    std::vector<const Mesh*> ptrs;
    ptrs.reserve(parts.size());
    for (const Mesh& m : parts) ptrs.push_back(&m);
    return concatenate(ptrs);
}

}  // namespace meshquilt
