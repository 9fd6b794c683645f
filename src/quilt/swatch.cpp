// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/swatch.h"

#include "core/intersect.h"
#include "meshquilt/analysis.h"
#include "meshquilt/quilt.h"
#include "quilt/kernel.h"
#include "quilt/trim.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace meshquilt::quilt {

namespace {
/// refine_translation's polish: at most this many point-to-plane steps, until the median sample lies
/// within kPolishDone swatch mean edges of the swatch (rounding) ...
constexpr int kPolishSteps = 12;
constexpr double kPolishDone = 1e-7;
/// ... with this weight of point to point beside them (per sample, against 1 for a face normal
/// lying in the plane). It is given up as soon as a step leaves the median sample further than this
/// share of its distance before the step, and kept if the median then lies within kPolishExact.
constexpr double kPolishPointWeight = 0.05;
constexpr double kPolishGain = 0.5;
constexpr double kPolishExact = 1e-3;
}  // namespace

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string num(const Vec3& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g, %.4g, %.4g", p.x(), p.y(), p.z());
    return buf;
}

double mesh_area(const Mesh& m) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) a += face_area(m, f);
    return a;
}

double window_density(const Mesh& m, double x0, double y0, double x1, double y1) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Vec3 c = face_centroid(m, f);
        if (c.x() < x0 || c.x() > x1 || c.y() < y0 || c.y() > y1) continue;
        a += face_area(m, f);
    }
    return a / ((x1 - x0) * (y1 - y0));
}

Vec3 area_centroid(const Mesh& m) {
    Vec3 c = Vec3::Zero();
    double total = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const double a = face_area(m, f);
        c += a * face_centroid(m, f);
        total += a;
    }
    return total > 0 ? Vec3(c / total) : Vec3(bounding_box(m).min);
}

Mesh translated(const Mesh& m, const Vec3& t) {
    Mesh out = m;
    for (Vec3& v : out.vertices) v += t;
    return out;
}


namespace {

/// Beyond the paper: the in-plane turn that makes a swatch's threads run along x and y, when the
/// swatch was turned in its plane (its threads at an angle to its axes, so that no thread's xy box
/// is long: is_elongated knows threads by their box). The threads' principal axes (genus-0
/// components more than 3 times longer than wide along them) vote by length for an angle modulo
/// 90 degrees (warp and weft alike). The turn is taken only when the votes agree, it is more than a
/// degree, and it shrinks the footprint to kAlignedFootprint of its area or less: a swatch cut square
/// around diagonal threads stays as it is (turned, its box would grow). 0 when not turned.
double thread_turn(const Mesh& m, const std::vector<int>& comp, int count) {
    const auto n = static_cast<std::size_t>(count);
    std::vector<std::vector<int>> verts(n);
    std::vector<long> faces(n, 0);
    std::vector<int> owner(m.vertices.size(), -1);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const auto c = static_cast<std::size_t>(comp[f]);
        ++faces[c];
        for (int k = 0; k < 3; ++k) {
            const int v = m.faces[f][k];
            if (owner[static_cast<std::size_t>(v)] < 0) {
                owner[static_cast<std::size_t>(v)] = comp[f];
                verts[c].push_back(v);
            }
        }
    }
    double vc = 0.0, vs = 0.0, total = 0.0;
    int threads = 0;
    for (std::size_t c = 0; c < n; ++c) {
        if (verts[c].size() < 3 || 2 * static_cast<long>(verts[c].size()) <= faces[c]) continue;  // rings are no threads
        Vec2 mean = Vec2::Zero();
        for (int v : verts[c]) mean += m.vertices[static_cast<std::size_t>(v)].head<2>();
        mean /= static_cast<double>(verts[c].size());
        Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
        for (int v : verts[c]) {
            const Vec2 q = m.vertices[static_cast<std::size_t>(v)].head<2>() - mean;
            cov += q * q.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
        const Vec2 along = eig.eigenvectors().col(1), across = eig.eigenvectors().col(0);
        double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a, lo_c = lo_a, hi_c = -lo_a;
        for (int v : verts[c]) {
            const Vec2 p = m.vertices[static_cast<std::size_t>(v)].head<2>();
            lo_a = std::min(lo_a, along.dot(p));
            hi_a = std::max(hi_a, along.dot(p));
            lo_c = std::min(lo_c, across.dot(p));
            hi_c = std::max(hi_c, across.dot(p));
        }
        const double length = hi_a - lo_a;
        if (!(length > 3.0 * (hi_c - lo_c))) continue;
        const double angle = std::atan2(along.y(), along.x());
        vc += length * std::cos(4.0 * angle);
        vs += length * std::sin(4.0 * angle);
        total += length;
        ++threads;
    }
    if (threads < 2 || std::hypot(vc, vs) < kAlignedAgreement * total) return 0.0;
    const double turn = -std::atan2(vs, vc) / 4.0;
    if (std::fabs(turn) < M_PI / 180.0) return 0.0;
    auto footprint = [&](double t) {
        const double c = std::cos(t), sn = std::sin(t);
        Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const Vec3& v : m.vertices) {
            const Vec2 p(c * v.x() - sn * v.y(), sn * v.x() + c * v.y());
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        return (hi - lo).prod();
    };
    return footprint(turn) <= kAlignedFootprint * footprint(0.0) ? turn : 0.0;
}

/// Each vertex's element (component of its faces) and each element's orientation: +1 when it
/// encloses positive volume (outward normals), -1 when inside out.
void element_orientation(const Mesh& m, const std::vector<int>& comp, int count, std::vector<int>* vcomp, std::vector<double>* sign) {
    vcomp->assign(m.vertices.size(), 0);
    std::vector<double> volume(static_cast<std::size_t>(count), 0.0);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Tri& t = m.faces[f];
        for (int k = 0; k < 3; ++k) (*vcomp)[static_cast<std::size_t>(t[k])] = comp[f];
        volume[static_cast<std::size_t>(comp[f])] += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
    }
    sign->resize(volume.size());
    for (std::size_t c = 0; c < volume.size(); ++c) (*sign)[c] = volume[c] < 0.0 ? -1.0 : 1.0;
}

/// `m` with every vertex moved by `d` along its outward vertex normal (d < 0: inwards).
Mesh offset_along_normals(const Mesh& m, const std::vector<Vec3>& normal, const std::vector<int>& vcomp, const std::vector<double>& sign, double d) {
    Mesh out = m;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) out.vertices[v] += d * sign[static_cast<std::size_t>(vcomp[v])] * normal[v];
    return out;
}

/// Offsets of a swatch's closed elements along their outward vertex normals, and what thinning
/// (SwatchData::thinned) must check of them.
struct NormalOffsets {
    const Mesh& m;
    const std::vector<int>& comp;
    int count;
    std::vector<int> vcomp;
    std::vector<double> sign;
    std::vector<Vec3> normal;
    std::vector<Box3> box;
    double cap = 0.0;       ///< kMaxThinning of the smallest element's smallest extent
    double diagonal = 0.0;  ///< the median element's xy diagonal

    NormalOffsets(const Mesh& mesh, const std::vector<int>& c, int n) : m(mesh), comp(c), count(n), normal(vertex_normals(mesh)), box(static_cast<std::size_t>(n)) {
        element_orientation(m, comp, count, &vcomp, &sign);
        for (std::size_t v = 0; v < m.vertices.size(); ++v) box[static_cast<std::size_t>(vcomp[v])].extend(m.vertices[v]);
        double extent = std::numeric_limits<double>::infinity();
        std::vector<double> diag;
        for (const Box3& b : box) {
            extent = std::min(extent, b.size().minCoeff());
            diag.push_back(std::hypot(b.size().x(), b.size().y()));
        }
        cap = SwatchData::kMaxThinning * extent;
        std::nth_element(diag.begin(), diag.begin() + static_cast<std::ptrdiff_t>(diag.size() / 2), diag.end());
        diagonal = diag[diag.size() / 2];
    }
    /// The swatch with every element grown by `d` (d < 0: thinned).
    Mesh at(double d) const { return offset_along_normals(m, normal, vcomp, sign, d); }
    bool apart(double d) const { return intersecting_element_pairs(at(d), comp, 1).empty(); }
    std::vector<double> volumes(const Mesh& mesh) const {
        std::vector<double> vol(static_cast<std::size_t>(count), 0.0);
        for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
            const Tri& t = mesh.faces[f];
            vol[static_cast<std::size_t>(comp[f])] += sign[static_cast<std::size_t>(comp[f])] * mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
        }
        return vol;
    }
    /// Thinned by `d` (> 0): every element keeps kMinThinVolume of its volume and none intersects
    /// itself or another; the thinned swatch, or nothing.
    std::optional<Mesh> thinned(double d) const {
        if (!(d > 0.0) || d > cap) return std::nullopt;
        Mesh thin = at(-d);
        const std::vector<double> before = volumes(m), after = volumes(thin);
        for (std::size_t c = 0; c < after.size(); ++c)
            if (!(after[c] >= SwatchData::kMinThinVolume * before[c])) return std::nullopt;
        if (!intersecting_element_pairs(thin, comp, 1).empty() || count_self_intersections(thin, 1) > 0) return std::nullopt;
        return thin;
    }
};

/// Beyond the paper: the thinning of SwatchData::thinned for a swatch `m` of closed elements
/// (components `comp`) some of which intersect. The least inward offset that parts every pair is
/// found by bisection (12 steps) up to kMaxThinning of the smallest element's smallest extent;
/// more is taken so that the thinned elements stand apart as a well-made swatch's do (kThinGap:
/// the bundled mail's linked rings are 0.04 of a ring's xy diagonal apart): elements that barely
/// miss each other collide as soon as a patch's map moves them a little. Thinned, no element may
/// intersect itself or another one; otherwise 0 and `m` is left as it is. A tube's vertex
/// normals point across the wire, so a ring or thread loses the offset from its wire's radius and
/// keeps its centre line: the lattice is the swatch's.
double thin_apart(Mesh* m, const std::vector<int>& comp, int count) {
    if (count < 2 || !quilt::is_closed_oriented(*m)) return 0.0;
    const NormalOffsets off(*m, comp, count);
    if (!(off.cap > 0.0) || !off.apart(-off.cap)) return 0.0;
    double lo = 0.0, hi = off.cap;
    for (int it = 0; it < 12; ++it) {
        const double mid = 0.5 * (lo + hi);
        (off.apart(-mid) ? hi : lo) = mid;
    }
    // The thinning taken: the least that parts them plus half of kThinGap times the median
    // element's xy diagonal (so the thinned elements are that far apart), or if that is too much,
    // half as much more, a tenth more, or none more: the first that `thinned` accepts.
    const double more = 0.5 * SwatchData::kThinGap * off.diagonal;
    for (double share : {1.0, 0.5, 0.1, 0.0})
        if (std::optional<Mesh> thin = off.thinned(std::min(off.cap, hi + share * more))) {
            *m = std::move(*thin);
            return std::min(off.cap, hi + share * more);
        }
    return 0.0;
}

/// Beyond the paper: a chain mail whose rings do not intersect but stand closer than kThinGap of
/// a ring's xy diagonal (a tight mail: a thick wire, a steep tilt) is thinned to that clearance
/// too: its rings collide on a surface as soon as a patch moves them a little, as an
/// intersecting mail's thinned to a bare miss did. Only for a swatch of rings (closed, genus >= 1,
/// not threads): pavings and pebbles keep narrow joints on purpose. The least outward offset at
/// which two rings touch is found by bisection; the thinning is what is missing of half the
/// clearance. 0 when the rings are far enough apart already or `thinned` refuses.
double thin_tight_rings(Mesh* m, const std::vector<int>& comp, int count) {
    if (count < 2 || !quilt::is_closed_oriented(*m)) return 0.0;
    std::vector<int> faces(static_cast<std::size_t>(count), 0);
    std::vector<std::set<int>> verts(static_cast<std::size_t>(count));
    for (std::size_t f = 0; f < m->faces.size(); ++f) {
        ++faces[static_cast<std::size_t>(comp[f])];
        for (int k = 0; k < 3; ++k) verts[static_cast<std::size_t>(comp[f])].insert(m->faces[f][k]);
    }
    const NormalOffsets off(*m, comp, count);
    for (int c = 0; c < count; ++c) {
        const Vec3 d = off.box[static_cast<std::size_t>(c)].size();
        const bool thread = std::max(d.x(), d.y()) > 3.0 * std::min(d.x(), d.y());
        if (2 * verts[static_cast<std::size_t>(c)].size() > static_cast<std::size_t>(faces[static_cast<std::size_t>(c)]) || thread) return 0.0;
    }
    const double half = 0.5 * SwatchData::kThinGap * off.diagonal;
    if (off.apart(half)) return 0.0;
    double lo = 0.0, hi = half;  // apart when grown by lo, touching when grown by hi
    for (int it = 0; it < 12; ++it) {
        const double mid = 0.5 * (lo + hi);
        (off.apart(mid) ? lo : hi) = mid;
    }
    const double d = half - lo;
    std::optional<Mesh> thin = off.thinned(d);
    if (!thin) return 0.0;
    *m = std::move(*thin);
    return d;
}

/// Beyond the paper: a thread modelled as an open sheet (a ribbon of a ribbon weave, a strip of a
/// basket) made a closed strip `*thickness` thick: the sheet offset by half of it to either side
/// along its vertex normals, the two sides joined along its rim. False (and `e` untouched) unless
/// `e` is an open, oriented sheet whose rim is simple loops, a thread (is_elongated), and the strip
/// comes out closed and free of self-intersections.
bool solidify_sheet(Mesh* e, double* thickness) {
    if (e->faces.empty() || is_closed_oriented(*e) || !is_elongated(*e)) return false;
    std::set<std::pair<int, int>> directed;
    for (const Tri& f : e->faces)
        for (int k = 0; k < 3; ++k)
            if (!directed.emplace(f[k], f[(k + 1) % 3]).second) return false;  // not oriented, or not manifold
    std::vector<std::vector<int>> loops;
    if (!boundary_loops(*e, &loops) || loops.empty()) return false;
    const double t = SwatchData::kSolidifyShare * 2.0 * thread_width(*e);  // a sheet's area over its length
    if (!(t > 0.0) || !std::isfinite(t)) return false;
    const std::vector<Vec3> normal = vertex_normals(*e);
    const auto nv = static_cast<int>(e->vertices.size());
    Mesh strip;
    strip.vertices.reserve(2 * e->vertices.size());
    for (std::size_t v = 0; v < e->vertices.size(); ++v) {
        if (!normal[v].allFinite()) return false;
        strip.vertices.push_back(e->vertices[v] + 0.5 * t * normal[v]);
    }
    for (std::size_t v = 0; v < e->vertices.size(); ++v) strip.vertices.push_back(e->vertices[v] - 0.5 * t * normal[v]);
    for (const Tri& f : e->faces) strip.faces.push_back(f);
    for (const Tri& f : e->faces) strip.faces.push_back(Tri(f[2] + nv, f[1] + nv, f[0] + nv));
    // The rim: each loop runs as its faces traverse it (a -> b), and the wall's faces use b -> a.
    for (const auto& loop : loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const int a = loop[i], b = loop[(i + 1) % loop.size()];
            strip.faces.push_back(Tri(b, a, a + nv));
            strip.faces.push_back(Tri(b, a + nv, b + nv));
        }
    if (!is_closed_oriented(strip) || count_self_intersections(strip, 1) > 0) return false;
    *e = std::move(strip);
    *thickness = t;
    return true;
}

/// The swatch `m` with its open threads made closed strips (solidify_sheet); the other elements as
/// they are. Returns how many were made strips (0: `m` untouched), `*thickness` the thickest strip.
int solidify_open_threads(Mesh* m, double* thickness) {
    std::vector<Mesh> parts = split_components(*m);
    int done = 0;
    for (Mesh& e : parts) {
        double t = 0.0;
        if (solidify_sheet(&e, &t)) {
            ++done;
            *thickness = std::max(*thickness, t);
        }
    }
    if (done > 0) *m = join_meshes(parts);
    return done;
}

}  // namespace

void thicken_elements(Mesh* mesh, const std::vector<int>& element_of_face, const std::vector<double>& offset) {
    int count = 0;
    for (int e : element_of_face) count = std::max(count, e + 1);
    std::vector<int> vcomp;
    std::vector<double> sign;
    element_orientation(*mesh, element_of_face, count, &vcomp, &sign);
    const std::vector<Vec3> normal = vertex_normals(*mesh);
    for (std::size_t v = 0; v < mesh->vertices.size(); ++v) {
        const auto e = static_cast<std::size_t>(vcomp[v]);
        if (e < offset.size()) mesh->vertices[v] += offset[e] * sign[e] * normal[v];
    }
}

int thicken_output(const SwatchData& sw, Mesh* mesh, const std::vector<int>& element_of_face, std::vector<double> offset) {
    if (!(sw.thinned > 0.0)) return 0;
    if (!sw.tight) {
        thicken_elements(mesh, element_of_face, offset);
        return 0;
    }
    const Mesh thin = *mesh;  // disjoint: the stage removed what intersected
    const std::vector<double> full = offset;
    constexpr int kSteps = 4;  // an element of a pair that meets loses a quarter of its thickening per round
    std::vector<int> less(offset.size(), 0);
    for (int round = 0;; ++round) {
        thicken_elements(mesh, element_of_face, offset);
        const auto pairs = intersecting_element_pairs(*mesh, element_of_face);
        if (pairs.empty()) break;
        *mesh = thin;
        if (round == 3 * kSteps) {  // not settled (never seen): every element as thin as it was quilted
            std::fill(less.begin(), less.end(), 1);
            break;
        }
        std::vector<char> shrink(offset.size(), 0);
        for (const auto& [a, b] : pairs) shrink[static_cast<std::size_t>(a)] = shrink[static_cast<std::size_t>(b)] = 1;
        for (std::size_t e = 0; e < offset.size(); ++e)
            if (shrink[e] && less[e] < kSteps) offset[e] = full[e] * (kSteps - ++less[e]) / kSteps;
    }
    return static_cast<int>(std::count_if(less.begin(), less.end(), [](int l) { return l > 0; }));
}

std::string SwatchData::intersect_warning() const {
    if (tight)
        return "the swatch's rings stand closer than " + num(kThinGap) +
               " of their width to one another: they were quilted thinned by " + num(thinned) +
               " swatch units along their normals, so that they keep clear of one another on a curved base, and thickened back";
    if (intersecting_pairs == 0) return {};
    const std::string pairs = (intersecting_pairs >= kMaxCountedPairs ? "at least " : "") + std::to_string(intersecting_pairs) +
                              (intersecting_pairs == 1 ? " pair" : " pairs");
    if (thinned > 0.0)
        return "the swatch's elements intersect one another (" + pairs + "): they were quilted thinned by " + num(thinned) +
               " swatch units along their normals and thickened back, so output elements meet where the swatch's do and may touch elsewhere";
    return "the swatch's elements intersect one another (" + pairs +
           ") and cannot be thinned apart (they are open, or overlap more deeply than a quarter of the smallest one's thickness): "
           "a new element that meets an old one is left out, so the output may be sparse";
}

std::string SwatchData::solidify_warning() const {
    if (solidified == 0) return {};
    return "the swatch's " + std::to_string(solidified) + (solidified == 1 ? " thread is an open sheet" : " threads are open sheets") +
           " (ribbons): each was made a closed strip " + num(solidify_thickness) + " swatch units thick (" + num(kSolidifyShare) +
           " of its width), so that it is cut, stitched and woven as a closed thread is; the output's threads are such strips";
}

std::string SwatchData::turn_warning() const {
    if (turn == 0.0) return {};
    return "the swatch's threads run at " + num(std::round(-turn * 1800.0 / M_PI) / 10.0) +
           " degrees to its sides: it was turned in its plane so that they run along x and y";
}

SwatchData prepare_swatch(const Mesh& input) {
    SwatchData s;
    s.mesh = meshquilt::normalize_swatch(input);
    int count = 0;
    std::vector<int> comp = connected_components(s.mesh, &count);
    s.turn = thread_turn(s.mesh, comp, count);
    if (s.turn != 0.0) {
        const double c = std::cos(s.turn), sn = std::sin(s.turn);
        for (Vec3& v : s.mesh.vertices) v = Vec3(c * v.x() - sn * v.y(), sn * v.x() + c * v.y(), v.z());
        s.mesh = meshquilt::normalize_swatch(s.mesh);  // back to the origin; z stays the thin axis
        comp = connected_components(s.mesh, &count);
    }
    s.solidified = solidify_open_threads(&s.mesh, &s.solidify_thickness);
    if (s.solidified > 0) {
        s.mesh = meshquilt::normalize_swatch(s.mesh);  // the strips' sides may reach past the footprint's corner
        comp = connected_components(s.mesh, &count);
    }
    s.box = bounding_box(s.mesh);
    if (count >= 2) {
        s.intersecting_pairs = static_cast<int>(intersecting_element_pairs(s.mesh, comp, SwatchData::kMaxCountedPairs).size());
        if (s.intersecting_pairs > 0) {
            s.thinned = thin_apart(&s.mesh, comp, count);
        } else {
            s.thinned = thin_tight_rings(&s.mesh, comp, count);
            s.tight = s.thinned > 0.0;
        }
    }
    std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(count));
    for (std::size_t f = 0; f < comp.size(); ++f) faces_of[static_cast<std::size_t>(comp[f])].push_back(static_cast<int>(f));
    for (const auto& fl : faces_of) {
        Mesh e;
        std::map<int, int> map;
        for (int f : fl) {
            Tri t;
            for (int k = 0; k < 3; ++k) {
                const int v = s.mesh.faces[static_cast<std::size_t>(f)][k];
                auto it = map.find(v);
                if (it == map.end()) {
                    it = map.emplace(v, static_cast<int>(e.vertices.size())).first;
                    e.vertices.push_back(s.mesh.vertices[static_cast<std::size_t>(v)]);
                }
                t[k] = it->second;
            }
            e.faces.push_back(t);
        }
        s.element_closed.push_back(quilt::is_closed_oriented(e));
        // Euler: V - E + F = 2 - 2g on a closed surface, where E = 3F / 2.
        s.element_genus.push_back(s.element_closed.back() ? std::max(0, (2 - (static_cast<int>(e.vertices.size()) - static_cast<int>(e.faces.size()) / 2)) / 2) : 0);
        s.element_strand.push_back(s.element_closed.back() && s.element_genus.back() == 0 && quilt::is_strand(e));
        s.elements.push_back(std::move(e));
    }
    // Disjoint as given, or thinned apart (NormalOffsets::thinned checked that).
    s.elements_disjoint = s.intersecting_pairs == 0 || s.thinned > 0.0;
    const double swatch_xy = std::max(s.box.size().x() * s.box.size().y(), 1e-300);
    for (const Mesh& e : s.elements) {
        const Box3 b = bounding_box(e);
        s.largest_element_cover = std::max(s.largest_element_cover, b.size().x() * b.size().y() / swatch_xy);
    }
    double len = 0.0;
    for (const Tri& f : s.mesh.faces)
        for (int k = 0; k < 3; ++k) len += (s.mesh.vertices[f[k]] - s.mesh.vertices[f[(k + 1) % 3]]).norm();
    s.mean_edge = len / (3.0 * static_cast<double>(std::max<std::size_t>(1, s.mesh.faces.size())));
    s.area = mesh_area(s.mesh);
    if (s.elements.size() >= 2 && s.elements_disjoint) {
        // Gaps are looked for up to the median element's diagonal (or a tenth of the footprint's
        // shorter side, if larger).
        std::vector<Box3> box;
        std::vector<double> diagonal;
        for (const Mesh& e : s.elements) {
            box.push_back(bounding_box(e));
            diagonal.push_back(box.back().size().norm());
        }
        std::nth_element(diagonal.begin(), diagonal.begin() + static_cast<std::ptrdiff_t>(diagonal.size() / 2), diagonal.end());
        const double cap = std::max(0.1 * std::min(s.box.size().x(), s.box.size().y()), diagonal[diagonal.size() / 2]);
        std::vector<double> gap(s.elements.size(), cap);
        for (std::size_t i = 0; i < s.elements.size(); ++i)
            for (std::size_t j = 0; j < s.elements.size(); ++j)
                if (i != j) gap[i] = std::min(gap[i], quilt::element_gap(s.elements[i], box[i], s.elements[j], cap));
        std::sort(gap.begin(), gap.end());
        s.near_gap = gap[static_cast<std::size_t>(0.05 * static_cast<double>(gap.size() - 1))];
        // Layered: blobs whose projections lie partly under a neighbour's (scales, shingles).
        std::size_t blobs = 0, overlapped = 0;
        for (std::size_t i = 0; i < s.elements.size(); ++i) {
            if (!s.element_closed[i] || s.element_genus[i] != 0 || quilt::is_elongated(s.elements[i])) continue;
            ++blobs;
            for (std::size_t j = 0; j < s.elements.size(); ++j)
                if (i != j && quilt::projected_overlap_share(s.elements[i], s.elements[j]) >= kLayeredOverlap) {
                    ++overlapped;
                    break;
                }
        }
        s.layered = blobs >= 2 && static_cast<double>(overlapped) >= kLayeredShare * static_cast<double>(blobs);
    }
    return s;
}

Vec2 refine_translation(const TriangleIndex& index, const MatchMetric& metric, const std::vector<Sample>& samples,
                    const Vec2& start, double max_offset) {
    if (samples.size() < 8) return start;
    const double reach = 2.0 * metric.unit;
    const std::size_t step = std::max<std::size_t>(1, samples.size() / 512);
    // Calls visit(d, hit) for the samples, shifted by -t, with a swatch face within `reach`: d is
    // the sample's offset from its closest point; returns how many.
    auto each_hit = [&](const Vec2& t, const auto& visit) {
        int n = 0;
        for (std::size_t k = 0; k < samples.size(); k += step) {
            const Vec3 p = samples[k].position - Vec3(t.x(), t.y(), 0.0);
            double score = 0.0;
            const ClosestHit h = index.best_match(p, samples[k].normal, metric, &score);
            if (h.face < 0 || h.distance > reach) continue;
            visit(Vec3(p - h.point), h);
            ++n;
        }
        return n;
    };
    auto clamped = [&](Vec2 next) {
        const Vec2 off = next - start;
        if (off.norm() > max_offset) next = start + off * (max_offset / off.norm());
        return next;
    };
    Vec2 t = start;
    for (int it = 0; it < 4; ++it) {
        Vec2 sum = Vec2::Zero();
        const int n = each_hit(t, [&](const Vec3& d, const ClosestHit&) { sum += Vec2(d.x(), d.y()); });
        if (n < 8) break;
        const Vec2 next = clamped(t + sum / n);
        const double moved = (next - t).norm();
        t = next;
        if (moved < 1e-3 * metric.unit) break;
    }
    // Polish (session 45): where the samples are a copy of the swatch (a lattice's old elements),
    // point-to-plane steps take the shift to it exactly; the point-to-point steps above converge
    // slowly on curved elements. Kept only when the copy is then exact: the median sample within
    // kPolishExact mean edges of the swatch (samples beyond `reach` count as far).
    const std::size_t visited = (samples.size() + step - 1) / step;
    std::vector<double> off;
    auto median_off = [&] {
        off.resize(visited, std::numeric_limits<double>::infinity());
        std::nth_element(off.begin(), off.begin() + static_cast<std::ptrdiff_t>(off.size() / 2), off.end());
        return off[off.size() / 2] / metric.unit;
    };
    Vec2 u = t;
    double last = std::numeric_limits<double>::infinity();
    for (int it = 0;; ++it) {
        // Minimises sum ((d - s) . n)^2 + mu |d_xy - s|^2 over the step s (d: a sample's offset
        // from its closest swatch point, n: that face's normal; mu for flat tops, whose planes say
        // nothing about xy).
        Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
        Vec2 b = Vec2::Zero();
        off.clear();
        const int n = each_hit(u, [&](const Vec3& d, const ClosestHit& h) {
            const Vec3& nf = index.face_normal(h.face);
            const Vec2 nxy(nf.x(), nf.y());
            A += nxy * nxy.transpose() + kPolishPointWeight * Eigen::Matrix2d::Identity();
            b += nxy * d.dot(nf) + kPolishPointWeight * Vec2(d.x(), d.y());
            off.push_back(h.distance);
        });
        if (n < 8) return t;
        // A copy comes closer several times over at each step (a grid of spheres: 0.055, 0.0075,
        // 0.0004 mean edges, ..., 1e-7 at the fifth); samples that are no copy stay about as far
        // (chain mail on a surface), and the polish stops at the second pass.
        const double now = median_off();
        if (now < kPolishDone) return u;
        if (now > kPolishGain * last || it == kPolishSteps) return now < kPolishExact ? u : t;
        last = now;
        const Vec2 next = clamped(u + A.ldlt().solve(b));
        if (!next.allFinite()) return t;
        u = next;
    }
}

Placement place_swatch(const SwatchData& swatch, const TriangleIndex& index, const MatchMetric& metric,
                       const std::vector<Sample>& samples, int pi0, int pj0, int k, int sx, int sy, double cell, double tolerance,
                       std::mt19937_64& rng) {
    std::vector<Vec2> cands;
    for (int tj = pj0 + k - sy; tj <= pj0; ++tj)
        for (int ti = pi0 + k - sx; ti <= pi0; ++ti) cands.emplace_back(ti * cell, tj * cell);
    const MatchChoice choice = choose_translation(index, metric, samples, cands, tolerance, rng);
    Placement p;
    p.ti = static_cast<int>(std::lround(choice.translation.x() / cell));
    p.tj = static_cast<int>(std::lround(choice.translation.y() / cell));
    p.translation = refine_translation(index, metric, samples, choice.translation, 0.5 * cell);
    const Vec3 shift(p.translation.x(), p.translation.y(), 0.0);
    for (std::size_t e = 0; e < swatch.elements.size(); ++e) {
        const Vec3 c = area_centroid(swatch.elements[e]);
        if (c.x() < 0 || c.y() < 0 || c.x() >= sx * cell || c.y() >= sy * cell) continue;
        p.fresh.push_back({static_cast<int>(e), translated(swatch.elements[e], shift)});
    }
    return p;
}

std::vector<char> intersecting_to_remove(const std::vector<const Mesh*>& elements) {
    std::vector<char> drop(elements.size(), 0);
    const ElementMesh all = concatenate(elements);
    for (const auto& [a, b] : intersecting_element_pairs(all.mesh, all.element_of_face)) {
        const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
        if (drop[ia] || drop[ib]) continue;
        drop[elements[ia]->faces.size() < elements[ib]->faces.size() ? ia : ib] = 1;
    }
    return drop;
}

namespace {

/// A ring's vertices about their mean, sorted by x, to tell whether another ring is the same one
/// moved in the plane. Vertex and face order are not compared: a swatch merged from an STL soup, or
/// written by another modeller, lists each copy of a ring in an order of its own.
struct RingShape {
    explicit RingShape(const Mesh& m) : faces(m.faces.size()) {
        mean = Vec3::Zero();
        for (const Vec3& v : m.vertices) mean += v;
        if (!m.vertices.empty()) mean /= static_cast<double>(m.vertices.size());
        rel.reserve(m.vertices.size());
        for (const Vec3& v : m.vertices) rel.push_back(v - mean);
        std::sort(rel.begin(), rel.end(), [](const Vec3& p, const Vec3& q) { return p.x() < q.x(); });
    }
    /// Same vertex and face counts, means at one height, and every vertex within `tol` of one of
    /// `other`'s once both are taken about their means.
    bool translate_of(const RingShape& other, double tol) const {
        if (rel.size() != other.rel.size() || faces != other.faces || std::fabs(mean.z() - other.mean.z()) > tol) return false;
        const auto by_x = [](const Vec3& p, double x) { return p.x() < x; };
        for (const Vec3& p : rel) {
            bool found = false;
            for (auto it = std::lower_bound(other.rel.begin(), other.rel.end(), p.x() - tol, by_x);
                 it != other.rel.end() && it->x() <= p.x() + tol && !found; ++it)
                found = (*it - p).norm() <= tol;
            if (!found) return false;
        }
        return true;
    }
    std::size_t faces;
    Vec3 mean;
    std::vector<Vec3> rel;
};

}  // namespace

RingLattice ring_lattice(const SwatchData& swatch, const std::vector<char>& is_ring) {
    const std::size_t S = swatch.elements.size();
    RingLattice lattice;
    lattice.centre.resize(S);
    lattice.next.resize(S);
    for (std::size_t s = 0; s < S; ++s) lattice.centre[s] = area_centroid(swatch.elements[s]).head<2>();
    const std::vector<Vec2>& centre = lattice.centre;
    auto ring = [&](std::size_t s) { return s < is_ring.size() && is_ring[s]; };
    std::vector<double> nearest;
    for (std::size_t s = 0; s < S; ++s) {
        if (!ring(s)) continue;
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t t = 0; t < S; ++t)
            if (t != s && ring(t)) d = std::min(d, (centre[s] - centre[t]).norm());
        if (std::isfinite(d)) nearest.push_back(d);
    }
    if (nearest.size() < 2) return lattice;
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
    lattice.spacing = nearest[nearest.size() / 2];
    const double tol = 1e-3 * lattice.spacing;
    // Kinds: rings that are translates of one another in the plane.
    std::vector<int>& kind = lattice.kind;
    kind.assign(S, -1);
    std::vector<RingShape> kinds;
    for (std::size_t s = 0; s < S; ++s) {
        if (!ring(s)) continue;
        RingShape a(swatch.elements[s]);
        for (std::size_t k = 0; k < kinds.size() && kind[s] < 0; ++k)
            if (a.translate_of(kinds[k], tol)) kind[s] = static_cast<int>(k);
        if (kind[s] < 0) {
            kind[s] = static_cast<int>(kinds.size());
            kinds.push_back(std::move(a));
        }
    }
    // Each kind's neighbours: (offset, a ring of the neighbour's kind), once per offset and kind.
    std::vector<std::vector<std::pair<Vec2, std::size_t>>> offsets(kinds.size());
    for (std::size_t s = 0; s < S; ++s)
        for (std::size_t t = 0; t < S && ring(s); ++t) {
            if (t == s || !ring(t) || (centre[s] - centre[t]).norm() >= 1.5 * lattice.spacing) continue;
            auto& list = offsets[static_cast<std::size_t>(kind[s])];
            const Vec2 d = centre[t] - centre[s];
            if (std::none_of(list.begin(), list.end(), [&](const auto& o) { return (o.first - d).norm() <= tol && kind[o.second] == kind[t]; }))
                list.emplace_back(d, t);
        }
    for (std::size_t s = 0; s < S; ++s) {
        if (!ring(s)) continue;
        for (const auto& [d, t] : offsets[static_cast<std::size_t>(kind[s])]) {
            // The swatch's own ring where it has one, else ring t shifted there.
            const Vec2 want = centre[s] + d;
            std::size_t at = S;
            for (std::size_t u = 0; u < S && at == S; ++u)
                if (kind[u] == kind[t] && (centre[u] - want).norm() <= tol) at = u;
            if (at < S) lattice.next[s].push_back({static_cast<int>(at), Vec2::Zero()});
            else lattice.next[s].push_back({static_cast<int>(t), want - centre[t]});
        }
    }
    return lattice;
}

}  // namespace meshquilt::quilt
