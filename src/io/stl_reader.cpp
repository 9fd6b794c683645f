// SPDX-License-Identifier: AGPL-3.0-or-later
// STL, ASCII and binary. Binary files may start with "solid" too, so the size decides first: a
// file of exactly 84 + 50 n bytes, n read at byte 80, is binary. Otherwise a file that starts with
// "solid" and continues with "facet" or "endsolid" is ASCII; anything else is taken as binary and
// checked against its triangle count. STL stores three corners per triangle and no connectivity:
// corners with identical coordinates become one vertex (+0 and -0 are the same coordinate).

#include "io/io_detail.h"

#include <cstdint>
#include <unordered_map>

namespace meshquilt::io_detail {

namespace {

struct PointKey {
    double x, y, z;
    bool operator==(const PointKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct PointHash {
    std::size_t operator()(const PointKey& k) const {
        auto bits = [](double d) {
            std::uint64_t u;
            std::memcpy(&u, &d, sizeof u);
            return u;
        };
        std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ULL;
        h ^= bits(k.y) + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
        h ^= bits(k.z) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

/// Builds the indexed mesh, merging corners with identical coordinates.
class VertexWelder {
public:
    explicit VertexWelder(Mesh& mesh, std::size_t expected_corners) : mesh_(mesh) {
        index_.reserve(expected_corners / 4 + 16);
    }
    int add(double x, double y, double z) {
        // Adding 0.0 turns -0.0 into +0.0, so both hash and compare alike.
        const PointKey key{x + 0.0, y + 0.0, z + 0.0};
        auto [it, inserted] = index_.try_emplace(key, static_cast<int>(mesh_.vertices.size()));
        if (inserted) mesh_.vertices.emplace_back(x, y, z);
        return it->second;
    }

private:
    Mesh& mesh_;
    std::unordered_map<PointKey, int, PointHash> index_;
};

std::uint32_t read_u32_le(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

float read_f32_le(const unsigned char* p) {
    const std::uint32_t u = read_u32_le(p);
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

/// "solid" followed, after the rest of its line, by "facet" or "endsolid".
bool looks_ascii(std::string_view data) {
    TextScanner scan(data, false);
    if (!iequals(scan.next(), "solid")) return false;
    scan.skip_line();
    const std::string_view next = scan.next();
    return iequals(next, "facet") || iequals(next, "endsolid");
}

Mesh read_binary(const std::string& path, std::string_view data) {
    if (data.size() < 84)
        fail(path, "truncated: a binary STL needs an 84-byte header, the file has " + std::to_string(data.size()) +
                       " bytes (and it is not ASCII STL either)");
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    const std::uint32_t n = read_u32_le(bytes + 80);
    const std::size_t holds = (data.size() - 84) / 50;
    if (n > holds)
        fail(path, "truncated: header says " + std::to_string(n) + " triangles, file holds " + std::to_string(holds));
    if (n > kMaxElements / 3) fail(path, "too many triangles (" + std::to_string(n) + ")");
    // Trailing bytes past the n triangles (some exporters pad) are ignored.
    Mesh mesh;
    mesh.faces.reserve(n);
    VertexWelder weld(mesh, 3 * static_cast<std::size_t>(n));
    for (std::uint32_t t = 0; t < n; ++t) {
        const unsigned char* rec = bytes + 84 + 50 * static_cast<std::size_t>(t) + 12;  // skip the normal
        int corner[3];
        for (int k = 0; k < 3; ++k) {
            const float x = read_f32_le(rec + 12 * k), y = read_f32_le(rec + 12 * k + 4), z = read_f32_le(rec + 12 * k + 8);
            if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
                fail(path, "triangle " + std::to_string(t) + ": non-finite vertex coordinate");
            corner[k] = weld.add(x, y, z);
        }
        mesh.faces.emplace_back(corner[0], corner[1], corner[2]);
    }
    return mesh;
}

void expect(const std::string& path, TextScanner& scan, const char* word) {
    const std::string_view token = scan.next();
    if (!iequals(token, word))
        fail_at(path, scan.line(),
                std::string("expected '") + word + "', found " + (token.empty() ? std::string("the end of the file") : quoted(token)));
}

Mesh read_ascii(const std::string& path, std::string_view data) {
    Mesh mesh;
    VertexWelder weld(mesh, data.size() / 40);
    TextScanner scan(data, false);
    std::vector<int> corners;
    while (!scan.at_end()) {
        expect(path, scan, "solid");
        scan.skip_line();  // the solid's name
        for (;;) {
            const std::string_view token = scan.next();
            if (iequals(token, "endsolid")) {
                scan.skip_line();
                break;
            }
            if (!iequals(token, "facet"))
                fail_at(path, scan.line(),
                        "expected 'facet' or 'endsolid', found " + (token.empty() ? std::string("the end of the file") : quoted(token)));
            expect(path, scan, "normal");
            for (int k = 0; k < 3; ++k) {  // the normal is recomputed from the corners, never trusted
                double ignored = 0.0;
                const std::string_view c = scan.next();
                if (parse_double(c, ignored) == NumberStatus::Bad)
                    fail_at(path, scan.line(), "cannot read normal component " + quoted(c));
            }
            expect(path, scan, "outer");
            expect(path, scan, "loop");
            corners.clear();
            for (;;) {
                const std::string_view word = scan.next();
                if (iequals(word, "endloop")) break;
                if (!iequals(word, "vertex"))
                    fail_at(path, scan.line(),
                            "expected 'vertex' or 'endloop', found " + (word.empty() ? std::string("the end of the file") : quoted(word)));
                double xyz[3];
                for (double& c : xyz) {
                    const std::string_view t = scan.next();
                    switch (parse_double(t, c)) {
                    case NumberStatus::Ok: break;
                    case NumberStatus::NonFinite: fail_at(path, scan.line(), "non-finite vertex coordinate " + quoted(t));
                    case NumberStatus::Bad: fail_at(path, scan.line(), "cannot read vertex coordinate " + quoted(t));
                    }
                }
                if (static_cast<long long>(mesh.vertices.size()) >= kMaxElements) fail_at(path, scan.line(), "too many vertices");
                corners.push_back(weld.add(xyz[0], xyz[1], xyz[2]));
            }
            if (corners.size() < 3)
                fail_at(path, scan.line(), "facet with " + std::to_string(corners.size()) + " vertices (a facet needs at least 3)");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.faces.emplace_back(corners[0], corners[k], corners[k + 1]);
            expect(path, scan, "endfacet");
        }
    }
    return mesh;
}

}  // namespace

Mesh read_stl(const std::string& path, std::string_view data) {
    if (data.size() >= 84) {
        const std::uint32_t n = read_u32_le(reinterpret_cast<const unsigned char*>(data.data()) + 80);
        if (84 + 50 * static_cast<std::uint64_t>(n) == data.size()) return read_binary(path, data);
    }
    if (looks_ascii(data)) return read_ascii(path, data);
    return read_binary(path, data);
}

}  // namespace meshquilt::io_detail
