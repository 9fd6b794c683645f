// SPDX-License-Identifier: AGPL-3.0-or-later
// write_mesh(): OBJ (shortest round-trip decimal coordinates, one `o element_<id>` group per
// element), binary little-endian PLY (double coordinates, int32 indices) and binary STL (float32).
// The whole file is formatted in memory, then written atomically.

#include "io/io_detail.h"
#include "meshquilt/io.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace meshquilt {

namespace {

/// Comment text split into lines, carriage returns dropped.
std::vector<std::string> comment_lines(const std::string& comment) {
    std::vector<std::string> lines;
    std::string current;
    for (char c : comment) {
        if (c == '\n') {
            lines.push_back(current);
            current.clear();
        } else if (c != '\r') {
            current += c;
        }
    }
    if (!current.empty()) lines.push_back(current);
    return lines;
}

void append_double(std::string& out, double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest string that reads back exactly
    out.append(buf, r.ptr);
}

void append_int(std::string& out, long long v) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

std::string format_obj(const Mesh& mesh, const WriteOptions& options) {
    std::string out;
    out.reserve(mesh.vertices.size() * 64 + mesh.faces.size() * 32 + 256);
    for (const std::string& line : comment_lines(options.comment)) out += "# " + line + "\n";
    out += "# meshquilt: " + std::to_string(mesh.vertices.size()) + " vertices, " + std::to_string(mesh.faces.size()) +
           " faces\n";
    for (const Vec3& v : mesh.vertices) {
        out += "v ";
        append_double(out, v.x());
        out += ' ';
        append_double(out, v.y());
        out += ' ';
        append_double(out, v.z());
        out += '\n';
    }
    std::vector<std::size_t> order(mesh.faces.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    const std::vector<int>& element = options.element_of_face;
    if (!element.empty())
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return element[a] < element[b]; });
    for (std::size_t i = 0; i < order.size(); ++i) {
        const std::size_t f = order[i];
        if (!element.empty() && (i == 0 || element[f] != element[order[i - 1]])) {
            const auto id = static_cast<std::size_t>(element[f]);
            if (id < options.group_names.size() && !options.group_names[id].empty()) {
                out += "o ";
                out += options.group_names[id];
            } else {
                out += "o element_";
                append_int(out, element[f]);
            }
            out += '\n';
        }
        const Tri& t = mesh.faces[f];
        out += "f ";
        append_int(out, t[0] + 1LL);
        out += ' ';
        append_int(out, t[1] + 1LL);
        out += ' ';
        append_int(out, t[2] + 1LL);
        out += '\n';
    }
    return out;
}

bool host_is_little_endian() {
    const std::uint16_t probe = 1;
    unsigned char first = 0;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

/// Appends the little-endian bytes of a trivially copyable value.
template <class T>
void append_le(std::string& out, T value) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (!host_is_little_endian()) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
}

std::string format_ply(const Mesh& mesh, const WriteOptions& options) {
    std::string out = "ply\nformat binary_little_endian 1.0\n";
    for (const std::string& line : comment_lines(options.comment)) out += "comment " + line + "\n";
    out += "comment written by meshquilt\n";
    out += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
    out += "property double x\nproperty double y\nproperty double z\n";
    out += "element face " + std::to_string(mesh.faces.size()) + "\n";
    out += "property list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + mesh.vertices.size() * 24 + mesh.faces.size() * 13);
    for (const Vec3& v : mesh.vertices) {
        append_le(out, v.x());
        append_le(out, v.y());
        append_le(out, v.z());
    }
    for (const Tri& t : mesh.faces) {
        out += static_cast<char>(3);
        append_le(out, static_cast<std::int32_t>(t[0]));
        append_le(out, static_cast<std::int32_t>(t[1]));
        append_le(out, static_cast<std::int32_t>(t[2]));
    }
    return out;
}

std::string format_stl(const Mesh& mesh, const WriteOptions& options) {
    // The 80-byte header must not start with "solid", or some readers take the file for ASCII.
    std::string header = "binary STL written by meshquilt";
    for (const std::string& line : comment_lines(options.comment)) header += "; " + line;
    header.resize(80, ' ');
    std::string out = header;
    out.reserve(84 + mesh.faces.size() * 50);
    append_le(out, static_cast<std::uint32_t>(mesh.faces.size()));
    // ADMesh (and PrusaSlicer, which embeds it) takes a file for ASCII when none of the 128 bytes
    // after the header exceeds 127, as for a box at integer coordinates. A facet whose normal has
    // a negative component has such a byte (the float's sign), so one goes first when needed.
    std::vector<std::size_t> order(mesh.faces.size());
    for (std::size_t f = 0; f < order.size(); ++f) order[f] = f;
    const auto negative_normal = [&](std::size_t f) {
        const Tri& t = mesh.faces[f];
        const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
        return (n.array() < 0.0).any();
    };
    if (!order.empty() && !negative_normal(0))
        for (std::size_t f = 1; f < order.size(); ++f)
            if (negative_normal(f)) {
                std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(f), order.begin() + static_cast<std::ptrdiff_t>(f) + 1);
                break;
            }
    for (std::size_t f : order) {
        const Tri& t = mesh.faces[f];
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        Vec3 n = (b - a).cross(c - a);
        const double len = n.norm();
        n = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
        for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(n[k]));
        for (const Vec3* p : {&a, &b, &c})
            for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>((*p)[k]));
        append_le(out, std::uint16_t{0});
    }
    return out;
}

/// The writers index vertices by the faces' numbers and the readers reject non-finite numbers, so
/// a mesh that breaks either is refused before anything is written.
void check_writable(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
    const auto fail = [&](const std::string& what) { throw InvalidInput(path + ": cannot write: " + what); };
    if (!options.element_of_face.empty() && options.element_of_face.size() != mesh.faces.size())
        fail("element_of_face has " + std::to_string(options.element_of_face.size()) + " entries for " +
             std::to_string(mesh.faces.size()) + " faces");
    const auto nv = static_cast<long long>(mesh.vertices.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= nv)
                fail("face " + std::to_string(f) + " has vertex index " + std::to_string(mesh.faces[f][k]) +
                     " out of range (the mesh has " + std::to_string(nv) + " vertices)");
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!mesh.vertices[v].allFinite()) fail("vertex " + std::to_string(v) + " has a non-finite coordinate");
}

}  // namespace

void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
    const std::string ext = io_detail::lower_extension(path);
    std::string (*format)(const Mesh&, const WriteOptions&) = nullptr;
    if (ext == ".obj") format = format_obj;
    else if (ext == ".ply") format = format_ply;
    else if (ext == ".stl") format = format_stl;
    else if (ext != ".3mf")
        throw IoError(path + ": cannot write: unknown mesh file extension " +
                      (ext.empty() ? std::string("(none)") : "'" + ext + "'") + " (supported: .obj, .ply, .stl, .3mf)");
    check_writable(path, mesh, options);
    if (ext == ".3mf") return write_file_atomic(path, io_detail::format_3mf(path, mesh, options));
    write_file_atomic(path, format(mesh, options));
}

}  // namespace meshquilt
