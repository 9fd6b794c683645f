// SPDX-License-Identifier: AGPL-3.0-or-later
// Guidance field files (docs/surface.md): one value per line,
//   face F x y z      a tangent vector on face F (0-based)
//   vertex V x y z    a tangent vector at vertex V (0-based)
//   stroke x y z x y z [x y z ...]   a polyline on the surface
// '#' starts a comment; blank lines are ignored.

#include "meshquilt/errors.h"
#include "meshquilt/surface.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace meshquilt {

GuidanceField read_guidance_field(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot open field file");
    GuidanceField field;
    std::string line;
    int lineno = 0;
    auto fail = [&](const std::string& what) { throw InvalidInput(path + ":" + std::to_string(lineno) + ": " + what); };
    auto read_numbers = [&](std::istringstream& ss) {
        std::vector<double> v;
        std::string tok;
        while (ss >> tok) {
            if (tok[0] == '#') break;
            char* end = nullptr;
            const double d = std::strtod(tok.c_str(), &end);
            if (end == tok.c_str() || *end != '\0') fail("'" + tok + "' is not a number");
            if (!std::isfinite(d)) fail("non-finite number '" + tok + "'");
            v.push_back(d);
        }
        return v;
    };
    while (std::getline(in, line)) {
        ++lineno;
        if (lineno > 50'000'000) fail("too many lines");
        std::istringstream ss(line);
        std::string kind;
        if (!(ss >> kind) || kind[0] == '#') continue;
        if (kind == "face" || kind == "vertex") {
            long long index = -1;
            std::string tok;
            if (!(ss >> tok)) fail("'" + kind + "' needs an index and three numbers");
            char* end = nullptr;
            index = std::strtoll(tok.c_str(), &end, 10);
            if (end == tok.c_str() || *end != '\0' || index < 0 || index > 2'000'000'000)
                fail("'" + tok + "' is not a valid " + kind + " index");
            const std::vector<double> v = read_numbers(ss);
            if (v.size() != 3) fail("'" + kind + "' needs exactly three vector components, got " + std::to_string(v.size()));
            const Vec3 vec(v[0], v[1], v[2]);
            if (vec.norm() == 0.0) fail("zero vector");
            if (kind == "face") field.faces.push_back({static_cast<int>(index), vec});
            else field.vertices.push_back({static_cast<int>(index), vec});
        } else if (kind == "stroke") {
            const std::vector<double> v = read_numbers(ss);
            if (v.size() < 6 || v.size() % 3 != 0) fail("'stroke' needs at least two points of three numbers each");
            std::vector<Vec3> pts;
            for (std::size_t i = 0; i < v.size(); i += 3) pts.emplace_back(v[i], v[i + 1], v[i + 2]);
            field.strokes.push_back(std::move(pts));
        } else {
            fail("unknown record '" + kind + "' (expected face, vertex or stroke)");
        }
    }
    if (in.bad()) throw IoError(path + ": read error");
    if (field.empty()) throw InvalidInput(path + ": field file holds no values");
    return field;
}

}  // namespace meshquilt
