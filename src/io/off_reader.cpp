// SPDX-License-Identifier: AGPL-3.0-or-later
// Object File Format (Geomview OFF), ASCII: an "OFF" keyword (optionally with the ST, C and N
// prefixes), counts "V F E", V vertex lines and F polygon lines "n i1 ... in". `#` comments and
// per-vertex or per-face extras (colours, normals, texture coordinates) are skipped.

#include "io/io_detail.h"

#include <algorithm>
#include <string>

namespace meshquilt::io_detail {

namespace {

long long read_count(const std::string& path, TextScanner& scan, const char* what) {
    const std::string_view token = scan.next();
    if (token.empty()) fail(path, std::string("truncated: the header has no ") + what + " count");
    long long n = 0;
    if (!parse_int(token, n) || n < 0)
        fail_at(path, scan.line(), std::string("bad ") + what + " count " + quoted(token));
    return n;
}

}  // namespace

Mesh read_off(const std::string& path, std::string_view data) {
    TextScanner scan(data, true);
    const std::string_view keyword = scan.next();
    const long keyword_line = scan.line();
    if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
        fail_at(path, keyword_line, "not an OFF file: it starts with " + quoted(keyword) + ", not 'OFF'");
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.find_first_of("4n") != std::string_view::npos)
        fail_at(path, keyword_line, "unsupported OFF variant " + quoted(keyword) + " (only 3D OFF is read)");
    if (prefix.find_first_not_of("STCN") != std::string_view::npos)
        fail_at(path, keyword_line, "not an OFF file: unknown keyword " + quoted(keyword));
    {
        // "OFF BINARY" would be the only non-number that may follow the keyword.
        TextScanner peek = scan;
        if (iequals(peek.next(), "BINARY")) fail_at(path, keyword_line, "binary OFF is not supported");
    }
    const long long nv = read_count(path, scan, "vertex");
    const long long nf = read_count(path, scan, "face");
    const std::string_view edges = scan.next_on_line();  // optional and unused
    long long ne = 0;
    if (!edges.empty() && (!parse_int(edges, ne) || ne < 0)) fail_at(path, scan.line(), "bad edge count " + quoted(edges));
    scan.skip_line();
    // Each vertex needs at least "0 0 0\n" and each face "3 0 0 0": a larger claim is a lie.
    const auto size = static_cast<long long>(data.size());
    if (nv > kMaxElements || nv > size / 6)
        fail(path, "header says " + std::to_string(nv) + " vertices, more than a " + std::to_string(size) +
                       "-byte file can hold");
    if (nf > kMaxElements || nf > size / 7)
        fail(path, "header says " + std::to_string(nf) + " faces, more than a " + std::to_string(size) +
                       "-byte file can hold");

    Mesh mesh;
    mesh.vertices.reserve(static_cast<std::size_t>(nv));
    mesh.faces.reserve(static_cast<std::size_t>(nf));
    for (long long v = 0; v < nv; ++v) {
        double xyz[3];
        for (double& c : xyz) {
            const std::string_view token = scan.next();
            if (token.empty())
                fail(path, "truncated: header says " + std::to_string(nv) + " vertices, file holds " + std::to_string(v));
            switch (parse_double(token, c)) {
            case NumberStatus::Ok: break;
            case NumberStatus::NonFinite: fail_at(path, scan.line(), "non-finite vertex coordinate " + quoted(token));
            case NumberStatus::Bad: fail_at(path, scan.line(), "cannot read vertex coordinate " + quoted(token));
            }
        }
        mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
        scan.skip_line();  // colours, normals, texture coordinates
    }
    std::vector<int> corners;
    for (long long f = 0; f < nf; ++f) {
        const std::string_view count_token = scan.next();
        if (count_token.empty())
            fail(path, "truncated: header says " + std::to_string(nf) + " faces, file holds " + std::to_string(f));
        const long line = scan.line();
        long long n = 0;
        if (!parse_int(count_token, n)) fail_at(path, line, "bad face corner count " + quoted(count_token));
        if (n < 3) fail_at(path, line, "face with " + std::to_string(n) + " corners (a face needs at least 3)");
        corners.clear();
        for (long long k = 0; k < n; ++k) {
            const std::string_view token = scan.next_on_line();
            if (token.empty())
                fail_at(path, line, "face has " + std::to_string(k) + " of the " + std::to_string(n) + " indices it announces");
            long long index = 0;
            if (!parse_int(token, index)) fail_at(path, line, "bad face index " + quoted(token));
            if (index < 0 || index >= nv)
                fail_at(path, line,
                        "face index " + std::to_string(index) + " out of range (the file has " + std::to_string(nv) +
                            " vertices)");
            corners.push_back(static_cast<int>(index));
        }
        for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.faces.emplace_back(corners[0], corners[k], corners[k + 1]);
        scan.skip_line();  // face colour
    }
    return mesh;
}

}  // namespace meshquilt::io_detail
