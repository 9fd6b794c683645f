// SPDX-License-Identifier: AGPL-3.0-or-later
#include "meshquilt/mesh.h"

namespace meshquilt {

Box3 bounding_box(const Mesh& mesh) {
    Box3 box;
    for (const Tri& f : mesh.faces)
        for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[static_cast<std::size_t>(f[k])]);
    return box;
}

}  // namespace meshquilt
