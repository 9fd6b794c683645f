// SPDX-License-Identifier: AGPL-3.0-or-later
// Wavefront OBJ: `v` and `f` records. Faces may use the v, v/vt, v//vn and v/vt/vn forms and
// negative (relative) indices; polygons are fan-triangulated; every other record is ignored.
// One pass over the buffer with a line scanner and std::from_chars: about 10x faster than iostreams.

#include "io/io_detail.h"

#include <string>
#include <utility>
#include <vector>

namespace meshquilt::io_detail {

namespace {

/// A face corner whose positive index pointed past the vertices read so far. OBJ files should not
/// do that, but many readers allow it, so the check waits until the whole file is read.
struct ForwardReference {
    long line;
    long long index;  // as written (1-based)
};

/// Reads the vertex index of one face corner token ("7", "7/3", "7//2", "-1/-1/-1").
bool corner_index(std::string_view token, long long& index) {
    const std::size_t slash = token.find('/');
    if (!parse_int(token.substr(0, slash), index)) return false;
    if (slash == std::string_view::npos) return true;
    // vt and vn parts: optional integers, at most two more parts.
    std::string_view rest = token.substr(slash + 1);
    const std::size_t slash2 = rest.find('/');
    long long ignored = 0;
    const std::string_view vt = rest.substr(0, slash2);
    if (!vt.empty() && !parse_int(vt, ignored)) return false;
    if (slash2 == std::string_view::npos) return true;
    const std::string_view vn = rest.substr(slash2 + 1);
    return vn.empty() || parse_int(vn, ignored);
}

}  // namespace

Mesh read_obj(const std::string& path, std::string_view data) {
    Mesh mesh;
    std::vector<ForwardReference> forward;
    std::vector<int> corners;
    const char* p = data.data();
    const char* const end = p + data.size();
    long line = 0;
    while (p < end) {
        ++line;
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
        if (!eol) eol = end;
        TextScanner scan(std::string_view(p, static_cast<std::size_t>(eol - p)), true, line);
        p = eol < end ? eol + 1 : end;

        const std::string_view keyword = scan.next_on_line();
        if (keyword == "v") {
            double xyz[3];
            for (double& c : xyz) {
                const std::string_view token = scan.next_on_line();
                if (token.empty()) fail_at(path, line, "vertex needs 3 coordinates");
                switch (parse_double(token, c)) {
                case NumberStatus::Ok: break;
                case NumberStatus::NonFinite: fail_at(path, line, "non-finite vertex coordinate " + quoted(token));
                case NumberStatus::Bad: fail_at(path, line, "cannot read vertex coordinate " + quoted(token));
                }
            }
            if (static_cast<long long>(mesh.vertices.size()) >= kMaxElements)
                fail_at(path, line, "too many vertices (the limit is 2^31 - 1)");
            mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
        } else if (keyword == "f") {
            corners.clear();
            const long long count = static_cast<long long>(mesh.vertices.size());
            for (std::string_view token = scan.next_on_line(); !token.empty(); token = scan.next_on_line()) {
                long long index = 0;
                if (!corner_index(token, index)) fail_at(path, line, "cannot read face corner " + quoted(token));
                long long resolved = 0;
                if (index > 0) {
                    if (index > kMaxElements)
                        fail_at(path, line,
                                "face index " + std::to_string(index) + " out of range (the file has " +
                                    std::to_string(count) + " vertices so far)");
                    if (index > count) forward.push_back({line, index});
                    resolved = index - 1;
                } else if (index < 0) {
                    resolved = count + index;
                    if (resolved < 0)
                        fail_at(path, line,
                                "relative face index " + std::to_string(index) + " points before the first vertex (" +
                                    std::to_string(count) + " vertices so far)");
                } else {
                    fail_at(path, line, "face index 0 is invalid (OBJ indices start at 1)");
                }
                corners.push_back(static_cast<int>(resolved));
            }
            if (corners.size() < 3)
                fail_at(path, line,
                        "face with " + std::to_string(corners.size()) + " corner" + (corners.size() == 1 ? "" : "s") +
                            " (a face needs at least 3)");
            if (static_cast<long long>(mesh.faces.size() + corners.size()) > kMaxElements)
                fail_at(path, line, "too many faces (the limit is 2^31 - 1)");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k)
                mesh.faces.emplace_back(corners[0], corners[k], corners[k + 1]);
        }
        // Every other record (vt, vn, g, o, s, usemtl, mtllib, l, p, comments...) is ignored.
    }
    for (const ForwardReference& ref : forward)
        if (ref.index > static_cast<long long>(mesh.vertices.size()))
            fail_at(path, ref.line,
                    "face index " + std::to_string(ref.index) + " out of range (the file has " +
                        std::to_string(mesh.vertices.size()) + " vertices)");
    return mesh;
}

}  // namespace meshquilt::io_detail
