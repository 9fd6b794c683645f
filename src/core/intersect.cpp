// SPDX-License-Identifier: AGPL-3.0-or-later
// Exact triangle intersection tests behind a box-tree broad phase (see intersect.h).
//
// Broad phase: a binary tree of axis-aligned boxes (faces in Morton order of their box centres,
// split at the middle, leaves of <= 4 faces) per mesh or per element, traversed against another
// tree (or itself) with early exit. Boxes are the exact min/max of the double coordinates and are closed,
// so touching faces always reach the narrow phase.
// Narrow phase: CGAL's Exact_predicates_inexact_constructions_kernel do_intersect (filtered exact
// predicates, no constructions), with degenerate faces handled as segments or points, and exact
// rules for faces that share a vertex or an edge (count_self_intersections).

#include "core/intersect.h"

#include "meshquilt/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_3/Point_3_Point_3.h>
#include <CGAL/Intersections_3/Point_3_Segment_3.h>
#include <CGAL/Intersections_3/Point_3_Triangle_3.h>
#include <CGAL/Intersections_3/Segment_3_Segment_3.h>
#include <CGAL/Intersections_3/Segment_3_Triangle_3.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>

namespace meshquilt {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using S3 = K::Segment_3;
using T3 = K::Triangle_3;

inline P3 pt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// ------------------------------------------------------------------------------------------
// Validation

std::string where(const char* what) { return what ? std::string(what) + ": " : std::string(); }

/// Throws InvalidInput on an index out of range or a non-finite coordinate used by a face.
void check_mesh(const Mesh& m, const char* what) {
    const auto n = static_cast<long long>(m.vertices.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const long long i = m.faces[f][k];
            if (i < 0 || i >= n) {
                std::ostringstream s;
                s << where(what) << "face " << f << " has vertex index " << i << " out of range [0, " << n
                  << "); fix the face list";
                throw InvalidInput(s.str());
            }
            if (!m.vertices[static_cast<std::size_t>(i)].allFinite()) {
                std::ostringstream s;
                s << where(what) << "vertex " << i << " (used by face " << f
                  << ") has a non-finite coordinate; fix or drop it";
                throw InvalidInput(s.str());
            }
        }
    }
}

// ------------------------------------------------------------------------------------------
// Primitives: a face as the triangle, segment or point that it covers

enum class Kind : std::uint8_t { Triangle, Segment, Point };

struct Prim {
    std::array<Vec3, 3> c;        ///< corners, in face order
    std::array<int, 3> v{0, 0, 0};  ///< canonical vertex ids (only for self-intersection tests)
    Kind kind = Kind::Triangle;
    std::uint8_t s0 = 0, s1 = 1;  ///< Segment: corners that are its end points
};

Prim make_prim(const Vec3& a, const Vec3& b, const Vec3& c) {
    Prim p;
    p.c = {a, b, c};
    const P3 A = pt(a), B = pt(b), C = pt(c);
    if (!CGAL::collinear(A, B, C)) return p;
    if (A == B && B == C) {
        p.kind = Kind::Point;
        return p;
    }
    p.kind = Kind::Segment;
    // The end points are the two corners between which the third lies.
    if (CGAL::collinear_are_ordered_along_line(B, A, C)) {
        p.s0 = 1, p.s1 = 2;
    } else if (CGAL::collinear_are_ordered_along_line(A, B, C)) {
        p.s0 = 0, p.s1 = 2;
    } else {
        p.s0 = 0, p.s1 = 1;
    }
    return p;
}

inline T3 tri(const Prim& p) { return {pt(p.c[0]), pt(p.c[1]), pt(p.c[2])}; }
inline S3 seg(const Prim& p) { return {pt(p.c[p.s0]), pt(p.c[p.s1])}; }

/// Exact: do the point sets of two primitives intersect?
bool prims_intersect(const Prim& a, const Prim& b) {
    if (a.kind == Kind::Triangle && b.kind == Kind::Triangle) return CGAL::do_intersect(tri(a), tri(b));
    if (static_cast<int>(a.kind) > static_cast<int>(b.kind)) return prims_intersect(b, a);
    // Now a.kind <= b.kind (Triangle < Segment < Point).
    switch (a.kind) {
        case Kind::Triangle:
            return b.kind == Kind::Segment ? CGAL::do_intersect(tri(a), seg(b))
                                           : CGAL::do_intersect(tri(a), pt(b.c[0]));
        case Kind::Segment:
            return b.kind == Kind::Segment ? CGAL::do_intersect(seg(a), seg(b))
                                           : CGAL::do_intersect(seg(a), pt(b.c[0]));
        case Kind::Point:
            return a.c[0] == b.c[0];
    }
    return false;
}

// ------------------------------------------------------------------------------------------
// Faces sharing a vertex or an edge (self-intersection rules; see intersect.h)

/// Sign of the orientation of (p, q, r, s) when floating point certifies it, else 0 ("unknown").
/// Shewchuk's orient3d stage-A filter (Adaptive precision floating-point arithmetic, 1997): the
/// determinant of the rounded differences is within o3derrboundA * permanent of the exact value.
/// Magnitudes near underflow or overflow are reported as unknown. Used only to skip work; every
/// "unknown" falls back to CGAL's exact predicates.
int certified_orientation(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
    const double adx = p.x() - s.x(), bdx = q.x() - s.x(), cdx = r.x() - s.x();
    const double ady = p.y() - s.y(), bdy = q.y() - s.y(), cdy = r.y() - s.y();
    const double adz = p.z() - s.z(), bdz = q.z() - s.z(), cdz = r.z() - s.z();
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                             (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                             (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
    if (!(permanent > 1e-200 && permanent < 1e200)) return 0;
    constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
    const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
    return det > bound ? 1 : det < -bound ? -1 : 0;
}

/// True when floating point certifies that the non-degenerate triangles (a, b, c) and (a, d, e)
/// meet only in a: the corners of one, other than a, lie strictly on one side of the other's
/// plane. A cheap exact shortcut that avoids CGAL's exact fallback when the other plane is (nearly)
/// coplanar with a corner, as happens all the time for planar quads split into two triangles.
bool certainly_apart_at_vertex(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e) {
    const int sb = certified_orientation(a, d, e, b);
    if (sb != 0 && sb == certified_orientation(a, d, e, c)) return true;
    const int sd = certified_orientation(a, b, c, d);
    return sd != 0 && sd == certified_orientation(a, b, c, e);
}

/// A sound floating-point shortcut for faces (a, b, c) and (b, a, d) sharing edge ab: true when the
/// parts of c - a and d - a perpendicular to ab point more than 90 degrees apart, which rules out
/// the only bad case (coplanar, same side, where they are exactly parallel). Each part must be at
/// least 1e-4 of its vector's length, so rounding (relative ~1e-16 of the lengths) cannot turn an
/// exact cosine of +1 into a negative one. Otherwise false: undecided, use the exact test.
bool clearly_opposite(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 e = b - a, ce = c - a, de = d - a;
    const double ee = e.squaredNorm();
    if (!(ee > 0.0)) return false;
    const Vec3 cp = ce - (ce.dot(e) / ee) * e;
    const Vec3 dp = de - (de.dot(e) / ee) * e;
    constexpr double kMinPart = 1e-8;  // squared: parts >= 1e-4 of the lengths
    return cp.squaredNorm() > kMinPart * ce.squaredNorm() && dp.squaredNorm() > kMinPart * de.squaredNorm() &&
           cp.dot(dp) < 0.0;
}

/// A piece of a face hanging from the shared vertex `a`: the triangle (a, x, y) or the segment
/// [a, x].
struct Piece {
    bool triangle;
    Vec3 x, y;
};

/// Exact: do two pieces hanging from the same point `a` share a point other than `a`?
bool pieces_overlap(const Vec3& a, const Piece& p, const Piece& q) {
    const P3 A = pt(a);
    if (p.triangle && q.triangle) {
        if (certainly_apart_at_vertex(a, p.x, p.y, q.x, q.y)) return false;
        // Their common part is convex and contains a; its far end lies on an opposite edge.
        const T3 tp(A, pt(p.x), pt(p.y)), tq(A, pt(q.x), pt(q.y));
        return CGAL::do_intersect(S3(pt(p.x), pt(p.y)), tq) || CGAL::do_intersect(S3(pt(q.x), pt(q.y)), tp);
    }
    if (p.triangle != q.triangle) {
        const Piece& t = p.triangle ? p : q;
        const Piece& s = p.triangle ? q : p;
        // [a, x] meets triangle (a, d, e) beyond a iff x is in it or [a, x] crosses [d, e].
        return CGAL::do_intersect(pt(s.x), T3(A, pt(t.x), pt(t.y))) ||
               CGAL::do_intersect(S3(pt(t.x), pt(t.y)), S3(A, pt(s.x)));
    }
    // Two segments from a overlap beyond a iff they are collinear and point the same way.
    return CGAL::collinear(A, pt(p.x), pt(q.x)) && !CGAL::collinear_are_ordered_along_line(pt(p.x), A, pt(q.x));
}

/// Exact: do two faces that share at least one canonical vertex have points in common other than
/// the shared vertex or edge? (Both faces with the same three vertices: true.)
bool adjacent_faces_overlap(const Prim& f, const Prim& g) {
    if (f.kind == Kind::Triangle && g.kind == Kind::Triangle) {
        // The common case, as below without the bookkeeping for flat faces: a triangle's corners
        // lie apart, so its three canonical vertices are distinct.
        int shared = 0, fi[2] = {0, 0}, fo = 0, go = 0, gmask = 0;
        for (int i = 0; i < 3; ++i) {
            bool in_g = false;
            for (int j = 0; j < 3; ++j)
                if (f.v[static_cast<std::size_t>(i)] == g.v[static_cast<std::size_t>(j)]) {
                    in_g = true;
                    gmask |= 1 << j;
                }
            if (in_g) {
                if (shared < 2) fi[shared] = i;
                ++shared;
            } else {
                fo = i;
            }
        }
        for (int j = 0; j < 3; ++j)
            if (!(gmask & (1 << j))) go = j;
        if (shared == 0) return prims_intersect(f, g);
        if (shared == 3) return true;
        if (shared == 2) {
            const Vec3 &a = f.c[static_cast<std::size_t>(fi[0])], &b = f.c[static_cast<std::size_t>(fi[1])];
            const Vec3 &c = f.c[static_cast<std::size_t>(fo)], &d = g.c[static_cast<std::size_t>(go)];
            if (clearly_opposite(a, b, c, d)) return false;
            const P3 A = pt(a), B = pt(b), C = pt(c), D = pt(d);
            return CGAL::coplanar(A, B, C, D) && CGAL::coplanar_orientation(A, B, C, D) == CGAL::POSITIVE;
        }
        // One shared corner: the other two of each, in face order.
        const int fs = fi[0];
        const Vec3& a = f.c[static_cast<std::size_t>(fs)];
        int gs = 0;
        while (!(gmask & (1 << gs))) ++gs;
        const Piece pf{true, f.c[static_cast<std::size_t>(fs == 0 ? 1 : 0)], f.c[static_cast<std::size_t>(fs == 2 ? 1 : 2)]};
        const Piece pg{true, g.c[static_cast<std::size_t>(gs == 0 ? 1 : 0)], g.c[static_cast<std::size_t>(gs == 2 ? 1 : 2)]};
        return pieces_overlap(a, pf, pg);
    }
    // Distinct canonical vertices of each face, with a position for each.
    struct Corners {
        int n = 0;
        std::array<int, 3> id{};
        std::array<Vec3, 3> pos{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    };
    auto distinct = [](const Prim& p) {
        Corners c;
        for (int k = 0; k < 3; ++k) {
            if (std::find(c.id.begin(), c.id.begin() + c.n, p.v[k]) == c.id.begin() + c.n) {
                c.id[c.n] = p.v[k];
                c.pos[c.n] = p.c[k];
                ++c.n;
            }
        }
        return c;
    };
    const Corners F = distinct(f), G = distinct(g);
    auto in = [](const Corners& c, int id) { return std::find(c.id.begin(), c.id.begin() + c.n, id) != c.id.begin() + c.n; };
    int shared = 0;
    for (int k = 0; k < F.n; ++k) shared += in(G, F.id[k]) ? 1 : 0;

    if (shared == 0) return prims_intersect(f, g);
    if (shared == 3) return true;  // the same face twice
    if (shared == 2) {
        if (F.n < 3 || G.n < 3) return false;  // one face is just the shared edge
        Vec3 a = Vec3::Zero(), b = Vec3::Zero(), c = Vec3::Zero(), d = Vec3::Zero();
        int m = 0;
        for (int k = 0; k < 3; ++k) {
            if (in(G, F.id[k])) (m++ == 0 ? a : b) = F.pos[k];
            else c = F.pos[k];
        }
        for (int k = 0; k < 3; ++k)
            if (!in(F, G.id[k])) d = G.pos[k];
        const bool f_flat = f.kind != Kind::Triangle, g_flat = g.kind != Kind::Triangle;
        if (!f_flat && !g_flat && clearly_opposite(a, b, c, d)) return false;
        const P3 A = pt(a), B = pt(b), C = pt(c), D = pt(d);
        if (!f_flat && !g_flat)  // distinct planes meet only in line ab; one plane: same side overlaps
            return CGAL::coplanar(A, B, C, D) && CGAL::coplanar_orientation(A, B, C, D) == CGAL::POSITIVE;
        if (f_flat != g_flat) return false;  // the flat one lies on line ab, where the other is just [a, b]
        // Both on line ab: they overlap beyond [a, b] iff both reach past b, or both past a.
        return (CGAL::collinear_are_strictly_ordered_along_line(A, B, C) &&
                CGAL::collinear_are_strictly_ordered_along_line(A, B, D)) ||
               (CGAL::collinear_are_strictly_ordered_along_line(B, A, C) &&
                CGAL::collinear_are_strictly_ordered_along_line(B, A, D));
    }
    // One shared vertex a. Each face is a triangle hanging from a, or (when flat) the union of
    // the segments from a to its other corners.
    Vec3 a = Vec3::Zero();
    for (int k = 0; k < F.n; ++k)
        if (in(G, F.id[k])) a = F.pos[k];
    auto pieces = [&](const Prim& p, const Corners& c, std::array<Piece, 2>& out) {
        std::array<Vec3, 2> rest{Vec3::Zero(), Vec3::Zero()};
        int r = 0;
        for (int k = 0; k < c.n; ++k)
            if (c.pos[k] != a) rest[r++] = c.pos[k];
        if (p.kind == Kind::Triangle) {
            out[0] = {true, rest[0], rest[1]};
            return 1;
        }
        for (int k = 0; k < r; ++k) out[k] = {false, rest[k], rest[k]};
        return r;
    };
    std::array<Piece, 2> pf, pg;
    const int nf = pieces(f, F, pf), ng = pieces(g, G, pg);
    for (int i = 0; i < nf; ++i)
        for (int j = 0; j < ng; ++j)
            if (pieces_overlap(a, pf[i], pg[j])) return true;
    return false;
}

// ------------------------------------------------------------------------------------------
// Boxes and box trees

struct Box {
    std::array<double, 3> lo{kInf, kInf, kInf};
    std::array<double, 3> hi{-kInf, -kInf, -kInf};
    static constexpr double kInf = std::numeric_limits<double>::infinity();

    void extend(const Box& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    [[nodiscard]] double half_perimeter() const { return (hi[0] - lo[0]) + (hi[1] - lo[1]) + (hi[2] - lo[2]); }
};

inline bool overlap(const Box& a, const Box& b) {
    return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
           a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

Box box_of(const Prim& p) {
    Box b;
    for (const Vec3& c : p.c)
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = std::min(b.lo[k], c[k]);
            b.hi[k] = std::max(b.hi[k], c[k]);
        }
    return b;
}

Box3 to_box3(const Box& b) {
    Box3 r;
    if (b.lo[0] > b.hi[0]) return r;
    r.min = Vec3(b.lo[0], b.lo[1], b.lo[2]);
    r.max = Vec3(b.hi[0], b.hi[1], b.hi[2]);
    return r;
}

/// A static binary tree over item boxes. Items are referred to by the ids given to `build`.
class BoxTree {
public:
    struct Node {
        Box box;
        int first = 0;  ///< leaf: first item slot; inner: index of the left child (right is first + 1)
        int count = 0;  ///< leaf: number of items (> 0); inner: 0
    };
    static constexpr int kLeafSize = 4;

    /// `ids` index into `boxes`; the tree keeps its own copy of the boxes, in leaf order.
    void build(const std::vector<Box>& boxes, const std::vector<int>& ids) {
        nodes_.clear();
        ids_.clear();
        boxes_.clear();
        if (ids.empty()) return;
        // Items in Morton (Z) order of their box centres; every node then covers a contiguous run
        // of items and is split at its middle (a linear BVH). Sorting once is much cheaper than a
        // median selection per level, and the order is deterministic (ties broken by id).
        std::array<double, 3> lo{Box::kInf, Box::kInf, Box::kInf}, hi{-Box::kInf, -Box::kInf, -Box::kInf};
        for (int id : ids) {
            const Box& b = boxes[static_cast<std::size_t>(id)];
            for (std::size_t d = 0; d < 3; ++d) {
                lo[d] = std::min(lo[d], b.lo[d] + b.hi[d]);
                hi[d] = std::max(hi[d], b.lo[d] + b.hi[d]);
            }
        }
        std::array<double, 3> scale{};
        for (std::size_t d = 0; d < 3; ++d) scale[d] = hi[d] > lo[d] ? 2097151.0 / (hi[d] - lo[d]) : 0.0;
        std::vector<std::pair<std::uint64_t, int>> order(ids.size());
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const Box& b = boxes[static_cast<std::size_t>(ids[k])];
            std::uint64_t code = 0;
            for (std::size_t d = 0; d < 3; ++d) {
                double q = (b.lo[d] + b.hi[d] - lo[d]) * scale[d];
                q = q > 0.0 ? std::min(q, 2097151.0) : 0.0;  // also maps NaN (from overflow) to 0
                code |= spread_bits(static_cast<std::uint64_t>(q)) << d;
            }
            order[k] = {code, ids[k]};
        }
        std::sort(order.begin(), order.end());
        ids_.resize(order.size());
        boxes_.resize(order.size());
        for (std::size_t k = 0; k < order.size(); ++k) {
            ids_[k] = order[k].second;
            boxes_[k] = boxes[static_cast<std::size_t>(order[k].second)];
        }
        nodes_.reserve(2 * (ids.size() / 2 + 1));
        nodes_.emplace_back();
        build_node(0, 0, static_cast<int>(ids_.size()));
    }

    [[nodiscard]] bool empty() const { return nodes_.empty(); }
    [[nodiscard]] std::size_t size() const { return ids_.size(); }
    [[nodiscard]] const Node& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
    [[nodiscard]] const Box& root_box() const { return nodes_.front().box; }
    [[nodiscard]] int id(int slot) const { return ids_[static_cast<std::size_t>(slot)]; }
    [[nodiscard]] const Box& item_box(int slot) const { return boxes_[static_cast<std::size_t>(slot)]; }

private:
    /// Spreads the low 21 bits of x so that bit i moves to bit 3i.
    static std::uint64_t spread_bits(std::uint64_t x) {
        x &= 0x1fffffULL;
        x = (x | x << 32) & 0x1f00000000ffffULL;
        x = (x | x << 16) & 0x1f0000ff0000ffULL;
        x = (x | x << 8) & 0x100f00f00f00f00fULL;
        x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
        x = (x | x << 2) & 0x1249249249249249ULL;
        return x;
    }

    /// Items [begin, end) are in Morton order; split at the middle, boxes bottom-up.
    void build_node(int node, int begin, int end) {
        if (end - begin <= kLeafSize) {
            Box b;
            for (int k = begin; k < end; ++k) b.extend(boxes_[static_cast<std::size_t>(k)]);
            Node& n = nodes_[static_cast<std::size_t>(node)];
            n.box = b;
            n.first = begin;
            n.count = end - begin;
            return;
        }
        const int mid = begin + (end - begin) / 2;
        const int left = static_cast<int>(nodes_.size());
        nodes_.emplace_back();
        nodes_.emplace_back();
        build_node(left, begin, mid);
        build_node(left + 1, mid, end);
        Box b = nodes_[static_cast<std::size_t>(left)].box;
        b.extend(nodes_[static_cast<std::size_t>(left) + 1].box);
        Node& n = nodes_[static_cast<std::size_t>(node)];
        n.box = b;
        n.first = left;
        n.count = 0;
    }

    std::vector<Node> nodes_;
    std::vector<int> ids_;
    std::vector<Box> boxes_;
};

using NodePair = std::pair<int, int>;

/// Pushes the child pairs of node pair (a, b) whose boxes overlap. Returns false (pushing nothing)
/// when both are leaves. With `self` (A and B the same tree), the diagonal pair (a, a) splits into
/// (l, l), (r, r), (l, r), so each unordered pair of distinct items is reached once.
template <class Push>
bool split_pair(const BoxTree& A, const BoxTree& B, bool self, int a, int b, Push&& push) {
    const BoxTree::Node& na = A.node(a);
    const BoxTree::Node& nb = B.node(b);
    if (na.count > 0 && nb.count > 0) return false;
    if (self && a == b) {
        const int l = na.first, r = na.first + 1;
        push(l, l);
        push(r, r);
        if (overlap(A.node(l).box, A.node(r).box)) push(l, r);
        return true;
    }
    const bool split_a = na.count == 0 && (nb.count > 0 || na.box.half_perimeter() >= nb.box.half_perimeter());
    if (split_a) {
        for (int c = na.first; c < na.first + 2; ++c)
            if (overlap(A.node(c).box, nb.box)) push(c, b);
    } else {
        for (int c = nb.first; c < nb.first + 2; ++c)
            if (overlap(na.box, B.node(c).box)) push(a, c);
    }
    return true;
}

/// Calls fn(id_a, id_b) for overlapping items of a leaf pair; returns true if fn asked to stop.
template <class Fn>
bool visit_leaves(const BoxTree& A, const BoxTree& B, bool self, int a, int b, Fn& fn) {
    const BoxTree::Node& na = A.node(a);
    const BoxTree::Node& nb = B.node(b);
    if (self && a == b) {
        for (int i = na.first; i < na.first + na.count; ++i)
            for (int j = i + 1; j < na.first + na.count; ++j)
                if (overlap(A.item_box(i), A.item_box(j)) && fn(A.id(i), A.id(j))) return true;
        return false;
    }
    for (int i = na.first; i < na.first + na.count; ++i) {
        const Box& bi = A.item_box(i);
        if (!overlap(bi, nb.box)) continue;
        for (int j = nb.first; j < nb.first + nb.count; ++j)
            if (overlap(bi, B.item_box(j)) && fn(A.id(i), B.id(j))) return true;
    }
    return false;
}

/// Depth-first traversal from node pair (a, b). fn(id_a, id_b) -> bool (true: stop).
template <class Fn>
bool traverse_from(const BoxTree& A, const BoxTree& B, bool self, NodePair start, Fn& fn,
                   std::vector<NodePair>& stack) {
    stack.clear();
    stack.push_back(start);
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        const bool split = split_pair(A, B, self, a, b, [&](int x, int y) { stack.emplace_back(x, y); });
        if (!split && visit_leaves(A, B, self, a, b, fn)) return true;
    }
    return false;
}

/// Every pair of overlapping items of A and B (or, with `self`, of distinct items of A), passed to
/// fn(id_a, id_b) -> bool (true: stop). Big traversals are split into independent sub-traversals
/// run with TBB, so fn must then be thread-safe. Returns true if some fn call asked to stop.
template <class Fn>
bool traverse(const BoxTree& A, const BoxTree& B, bool self, Fn fn) {
    if (A.empty() || B.empty()) return false;
    if (!self && !overlap(A.root_box(), B.root_box())) return false;
    constexpr std::size_t kParallelItems = 8192;
    std::vector<NodePair> stack;
    if (A.size() + (self ? 0 : B.size()) < kParallelItems) return traverse_from(A, B, self, {0, 0}, fn, stack);

    // Breadth-first expansion into enough independent node pairs, then one task per pair.
    std::vector<NodePair> frontier{{0, 0}}, next;
    constexpr std::size_t kTasks = 256;
    while (frontier.size() < kTasks) {
        next.clear();
        bool split_any = false;
        for (const auto& [a, b] : frontier) {
            const bool split = split_pair(A, B, self, a, b, [&](int x, int y) { next.emplace_back(x, y); });
            if (!split) next.emplace_back(a, b);
            split_any = split_any || split;
        }
        frontier.swap(next);
        if (!split_any) break;
    }
    std::atomic<bool> stop{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frontier.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<NodePair> st;
        auto guarded = [&](int x, int y) {
            if (stop.load(std::memory_order_relaxed)) return true;
            if (fn(x, y)) {
                stop.store(true);
                return true;
            }
            return false;
        };
        for (std::size_t k = r.begin(); k != r.end() && !stop.load(std::memory_order_relaxed); ++k)
            traverse_from(A, B, self, frontier[k], guarded, st);
    });
    return stop.load();
}

// ------------------------------------------------------------------------------------------
// A mesh (or a subset of its faces) prepared for intersection queries

constexpr std::size_t kParallelFaces = 4096;

/// Primitives and boxes for every face of `m` (already checked).
void make_prims(const Mesh& m, std::vector<Prim>& prims, std::vector<Box>& boxes) {
    prims.resize(m.faces.size());
    boxes.resize(m.faces.size());
    auto one = [&](std::size_t f) {
        const Tri& t = m.faces[f];
        prims[f] = make_prim(m.vertices[static_cast<std::size_t>(t[0])], m.vertices[static_cast<std::size_t>(t[1])],
                             m.vertices[static_cast<std::size_t>(t[2])]);
        boxes[f] = box_of(prims[f]);
    };
    if (m.faces.size() < kParallelFaces) {
        for (std::size_t f = 0; f < m.faces.size(); ++f) one(f);
    } else {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.faces.size(), 1024),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t f = r.begin(); f != r.end(); ++f) one(f);
                          });
    }
}

std::vector<int> iota_ids(std::size_t n) {
    std::vector<int> ids(n);
    std::iota(ids.begin(), ids.end(), 0);
    return ids;
}

/// One id per distinct vertex position (the smallest index at that position) for every vertex
/// that a face uses (these are finite); unused vertices keep their own index.
std::vector<int> canonical_vertex_ids(const Mesh& m) {
    std::vector<char> used(m.vertices.size(), 0);
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(t[k])] = 1;
    std::vector<int> order;
    for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v]) order.push_back(static_cast<int>(v));
    const auto& V = m.vertices;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        const Vec3& p = V[static_cast<std::size_t>(a)];
        const Vec3& q = V[static_cast<std::size_t>(b)];
        if (p.x() != q.x()) return p.x() < q.x();
        if (p.y() != q.y()) return p.y() < q.y();
        if (p.z() != q.z()) return p.z() < q.z();
        return a < b;
    });
    std::vector<int> canon = iota_ids(V.size());
    for (std::size_t k = 0; k < order.size();) {
        std::size_t e = k + 1;
        const Vec3& p = V[static_cast<std::size_t>(order[k])];
        while (e < order.size() && V[static_cast<std::size_t>(order[e])] == p) ++e;
        for (std::size_t j = k; j < e; ++j) canon[static_cast<std::size_t>(order[j])] = order[k];
        k = e;
    }
    return canon;
}

bool shares_vertex(const Prim& f, const Prim& g) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (f.v[i] == g.v[j]) return true;
    return false;
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Free functions

bool triangles_intersect(const Triangle3& a, const Triangle3& b) {
    for (const auto* t : {&a, &b})
        for (const Vec3& p : *t)
            if (!p.allFinite()) throw InvalidInput("triangles_intersect: non-finite coordinate");
    return prims_intersect(make_prim(a[0], a[1], a[2]), make_prim(b[0], b[1], b[2]));
}

bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
    if (!a.allFinite() || !b.allFinite() || !c.allFinite())
        throw InvalidInput("is_degenerate_triangle: non-finite coordinate");
    return CGAL::collinear(pt(a), pt(b), pt(c));
}

bool meshes_intersect(const Mesh& a, const Mesh& b) {
    check_mesh(a, "meshes_intersect, first mesh");
    check_mesh(b, "meshes_intersect, second mesh");
    if (a.faces.empty() || b.faces.empty()) return false;
    std::vector<Prim> pa, pb;
    std::vector<Box> ba, bb;
    make_prims(a, pa, ba);
    make_prims(b, pb, bb);
    BoxTree ta, tb;
    ta.build(ba, iota_ids(ba.size()));
    tb.build(bb, iota_ids(bb.size()));
    return traverse(ta, tb, false, [&](int i, int j) {
        return prims_intersect(pa[static_cast<std::size_t>(i)], pb[static_cast<std::size_t>(j)]);
    });
}

std::vector<std::pair<int, int>> intersecting_element_pairs(const Mesh& mesh, const std::vector<int>& element_of_face,
                                                            std::size_t max_pairs) {
    const char* what = "intersecting_element_pairs";
    if (element_of_face.size() != mesh.faces.size())
        throw InvalidInput(std::string(what) + ": element_of_face has " + std::to_string(element_of_face.size()) +
                           " entries for " + std::to_string(mesh.faces.size()) + " faces");
    check_mesh(mesh, what);
    std::vector<std::pair<int, int>> result;
    if (mesh.faces.empty() || max_pairs == 0) return result;

    // Dense element index per face (element ids need not be contiguous).
    for (std::size_t f = 0; f < element_of_face.size(); ++f)
        if (element_of_face[f] < 0)
            throw InvalidInput(std::string(what) + ": face " + std::to_string(f) + " has negative element id " +
                               std::to_string(element_of_face[f]));
    // ids: the distinct element ids, ascending; dense[f]: index of face f's element in ids.
    std::vector<int> ids;
    std::vector<int> dense(element_of_face.size());
    const int max_id = *std::max_element(element_of_face.begin(), element_of_face.end());
    if (static_cast<std::size_t>(max_id) <= 4 * element_of_face.size() + 1024) {
        std::vector<int> index_of(static_cast<std::size_t>(max_id) + 1, -1);
        for (int e : element_of_face) index_of[static_cast<std::size_t>(e)] = 0;
        for (std::size_t e = 0; e < index_of.size(); ++e)
            if (index_of[e] == 0) {
                index_of[e] = static_cast<int>(ids.size());
                ids.push_back(static_cast<int>(e));
            }
        for (std::size_t f = 0; f < dense.size(); ++f) dense[f] = index_of[static_cast<std::size_t>(element_of_face[f])];
    } else {
        ids = element_of_face;
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        for (std::size_t f = 0; f < dense.size(); ++f)
            dense[f] = static_cast<int>(std::lower_bound(ids.begin(), ids.end(), element_of_face[f]) - ids.begin());
    }
    const std::size_t E = ids.size();
    if (E < 2) return result;

    // Faces grouped by element (CSR), in face order.
    std::vector<int> start(E + 1, 0);
    for (int e : dense) ++start[static_cast<std::size_t>(e) + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<int> faces_by_element(dense.size());
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (std::size_t f = 0; f < dense.size(); ++f)
            faces_by_element[static_cast<std::size_t>(fill[static_cast<std::size_t>(dense[f])]++)] = static_cast<int>(f);
    }

    std::vector<Prim> prims;
    std::vector<Box> boxes;
    make_prims(mesh, prims, boxes);

    std::vector<BoxTree> trees(E);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, E, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t e = r.begin(); e != r.end(); ++e)
            trees[e].build(boxes, std::vector<int>(faces_by_element.begin() + start[e], faces_by_element.begin() + start[e + 1]));
    });

    // Broad phase on element boxes.
    std::vector<Box> element_boxes(E);
    for (std::size_t e = 0; e < E; ++e) element_boxes[e] = trees[e].root_box();
    BoxTree element_tree;
    element_tree.build(element_boxes, iota_ids(E));
    std::vector<std::pair<int, int>> candidates;
    {
        std::vector<NodePair> stack;
        auto collect = [&](int i, int j) {
            candidates.emplace_back(std::min(i, j), std::max(i, j));
            return false;
        };
        traverse_from(element_tree, element_tree, true, {0, 0}, collect, stack);
    }
    std::sort(candidates.begin(), candidates.end());  // dense order == id order

    // Narrow phase per candidate, in order-preserving blocks so that max_pairs keeps a prefix.
    std::vector<char> hit(candidates.size(), 0);
    const std::size_t block = 1024;
    for (std::size_t b0 = 0; b0 < candidates.size() && result.size() < max_pairs; b0 += block) {
        const std::size_t b1 = std::min(candidates.size(), b0 + block);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(b0, b1, 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t k = r.begin(); k != r.end(); ++k) {
                const auto [i, j] = candidates[k];
                hit[k] = traverse(trees[static_cast<std::size_t>(i)], trees[static_cast<std::size_t>(j)], false,
                                  [&](int f, int g) {
                                      return prims_intersect(prims[static_cast<std::size_t>(f)], prims[static_cast<std::size_t>(g)]);
                                  })
                             ? 1
                             : 0;
            }
        });
        for (std::size_t k = b0; k < b1 && result.size() < max_pairs; ++k)
            if (hit[k])
                result.emplace_back(ids[static_cast<std::size_t>(candidates[k].first)],
                                    ids[static_cast<std::size_t>(candidates[k].second)]);
    }
    return result;
}

namespace {
/// An element's faces for self-intersection tests: primitives whose corners are canonical vertex
/// ids (coincident vertices share one), and their box tree.
struct SelfTest {
    std::vector<Prim> prims;
    BoxTree tree;
    explicit SelfTest(const Mesh& element) {
        std::vector<Box> boxes;
        make_prims(element, prims, boxes);
        const std::vector<int> canon = canonical_vertex_ids(element);
        for (std::size_t f = 0; f < prims.size(); ++f)
            for (int k = 0; k < 3; ++k) prims[f].v[static_cast<std::size_t>(k)] = canon[static_cast<std::size_t>(element.faces[f][k])];
        tree.build(boxes, iota_ids(boxes.size()));
    }
    /// Do faces i and j intersect other than properly at what they share?
    [[nodiscard]] bool bad(int i, int j) const {
        const Prim& f = prims[static_cast<std::size_t>(i)];
        const Prim& g = prims[static_cast<std::size_t>(j)];
        return shares_vertex(f, g) ? adjacent_faces_overlap(f, g) : prims_intersect(f, g);
    }
};
}  // namespace

int count_self_intersections(const Mesh& element, std::size_t max) {
    check_mesh(element, "count_self_intersections");
    if (element.faces.size() < 2 || max == 0) return 0;
    const std::size_t cap = std::min<std::size_t>(max, static_cast<std::size_t>(std::numeric_limits<int>::max()));
    const SelfTest self(element);
    std::atomic<std::size_t> count{0};
    traverse(self.tree, self.tree, true, [&](int i, int j) { return self.bad(i, j) && count.fetch_add(1) + 1 >= cap; });
    return static_cast<int>(std::min(count.load(), cap));
}

std::vector<char> self_intersecting_faces(const Mesh& element) {
    check_mesh(element, "self_intersecting_faces");
    std::vector<char> hit(element.faces.size(), 0);
    if (element.faces.size() < 2) return hit;
    const SelfTest self(element);
    std::vector<NodePair> stack;
    auto mark = [&](int i, int j) {
        if (self.bad(i, j)) hit[static_cast<std::size_t>(i)] = hit[static_cast<std::size_t>(j)] = 1;
        return false;
    };
    traverse_from(self.tree, self.tree, true, {0, 0}, mark, stack);
    return hit;
}

// ------------------------------------------------------------------------------------------
// ElementCollider

namespace {

struct CellKey {
    std::int64_t x, y, z;
    bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const {
        std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ULL;
        h ^= static_cast<std::uint64_t>(k.y) + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(k.z) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

/// Geometry of one element, ready for exact tests.
struct Prepared {
    std::vector<Prim> prims;
    BoxTree tree;
    Box box;

    void prepare(const Mesh& m) {
        std::vector<Box> boxes;
        make_prims(m, prims, boxes);
        tree.build(boxes, iota_ids(boxes.size()));
        box = tree.empty() ? Box{} : tree.root_box();
    }
};

bool prepared_intersect(const Prepared& a, const Prepared& b) {
    if (a.tree.empty() || b.tree.empty() || !overlap(a.box, b.box)) return false;
    return traverse(a.tree, b.tree, false, [&](int i, int j) {
        return prims_intersect(a.prims[static_cast<std::size_t>(i)], b.prims[static_cast<std::size_t>(j)]);
    });
}

}  // namespace

struct ElementCollider::Impl {
    struct Entry {
        Prepared geometry;
        bool oversized = false;
        std::array<std::int64_t, 3> cell_lo{}, cell_hi{};
    };

    ElementColliderOptions options;
    double cell = 0.0;                          ///< fixed by the first non-empty element
    std::vector<std::unique_ptr<Entry>> entries;  ///< by id; null once removed
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> grid;
    std::vector<int> oversized;                 ///< ids of elements not in the grid (sorted)
    std::size_t alive = 0;

    /// Cell range of a box; false if it covers more than the allowed number of cells.
    bool cell_range(const Box& b, std::array<std::int64_t, 3>& lo, std::array<std::int64_t, 3>& hi) const {
        double cells = 1.0;
        for (int k = 0; k < 3; ++k) {
            // floor(x / cell) is monotone in x, so overlapping boxes get overlapping cell ranges.
            const double l = std::floor(b.lo[static_cast<std::size_t>(k)] / cell);
            const double h = std::floor(b.hi[static_cast<std::size_t>(k)] / cell);
            constexpr double kLimit = 4.0e18;
            if (!(std::abs(l) < kLimit && std::abs(h) < kLimit)) return false;
            lo[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(l);
            hi[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(h);
            cells *= h - l + 1.0;
        }
        return cells <= static_cast<double>(options.max_cells_per_element);
    }

    template <class Fn>
    static void for_cells(const std::array<std::int64_t, 3>& lo, const std::array<std::int64_t, 3>& hi, Fn&& fn) {
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t z = lo[2]; z <= hi[2]; ++z) fn(CellKey{x, y, z});
    }

    /// Ids of stored elements whose boxes overlap `b`, that are not ignored and are at least
    /// `first_id`, ascending.
    std::vector<int> near(const Box& b, const std::vector<int>& ignore_sorted, int first_id) const {
        std::vector<int> out;
        std::array<std::int64_t, 3> lo{}, hi{};
        if (cell > 0.0 && cell_range(b, lo, hi)) {
            for_cells(lo, hi, [&](const CellKey& key) {
                const auto it = grid.find(key);
                if (it != grid.end()) out.insert(out.end(), it->second.begin(), it->second.end());
            });
            out.insert(out.end(), oversized.begin(), oversized.end());
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        } else {
            for (std::size_t id = 0; id < entries.size(); ++id)
                if (entries[id]) out.push_back(static_cast<int>(id));
        }
        out.erase(std::remove_if(out.begin(), out.end(),
                                 [&](int id) {
                                     return id < first_id || std::binary_search(ignore_sorted.begin(), ignore_sorted.end(), id) ||
                                            !overlap(entries[static_cast<std::size_t>(id)]->geometry.box, b);
                                 }),
                  out.end());
        return out;
    }

    /// The candidate's faces that reach into a nearby element's box, prepared (`faces`: their
    /// indices in `candidate`), and the ids of those elements. Empty when nothing is near.
    struct Query {
        Prepared c;
        std::vector<int> faces, ids;
        std::vector<Box> boxes;  ///< per prim of c
    };
    Query prepare_query(const Mesh& candidate, const std::vector<int>& ignore, int first_id) const {
        Query q;
        check_mesh(candidate, "ElementCollider candidate");
        if (candidate.faces.empty() || alive == 0 || static_cast<std::size_t>(std::max(first_id, 0)) >= entries.size()) return q;
        std::vector<Box> face_boxes(candidate.faces.size());
        Box all;
        for (std::size_t f = 0; f < candidate.faces.size(); ++f) {
            Box& b = face_boxes[f];
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = candidate.vertices[static_cast<std::size_t>(candidate.faces[f][k])];
                for (std::size_t d = 0; d < 3; ++d) {
                    b.lo[d] = std::min(b.lo[d], p[static_cast<Eigen::Index>(d)]);
                    b.hi[d] = std::max(b.hi[d], p[static_cast<Eigen::Index>(d)]);
                }
            }
            all.extend(b);
        }
        std::vector<int> ign(ignore);
        std::sort(ign.begin(), ign.end());
        q.ids = near(all, ign, first_id);
        if (q.ids.empty()) return q;

        // Only faces that reach into some nearby element's box can touch it.
        std::vector<Box> near_boxes;
        near_boxes.reserve(q.ids.size());
        for (int id : q.ids) near_boxes.push_back(entries[static_cast<std::size_t>(id)]->geometry.box);
        std::vector<Box> kept_boxes;
        for (std::size_t f = 0; f < candidate.faces.size(); ++f) {
            const Box& b = face_boxes[f];
            if (std::none_of(near_boxes.begin(), near_boxes.end(), [&](const Box& n) { return overlap(b, n); })) continue;
            const Tri& t = candidate.faces[f];
            q.c.prims.push_back(make_prim(candidate.vertices[static_cast<std::size_t>(t[0])],
                                          candidate.vertices[static_cast<std::size_t>(t[1])],
                                          candidate.vertices[static_cast<std::size_t>(t[2])]));
            q.faces.push_back(static_cast<int>(f));
            kept_boxes.push_back(b);
        }
        if (q.c.prims.empty()) {
            q.ids.clear();
            return q;
        }
        q.c.tree.build(kept_boxes, iota_ids(kept_boxes.size()));
        q.c.box = q.c.tree.root_box();
        q.boxes = std::move(kept_boxes);
        return q;
    }

    template <class Fn>  // fn(id) -> bool stop
    void for_each_colliding(const Mesh& candidate, const std::vector<int>& ignore, int first_id, Fn&& fn) const {
        const Query q = prepare_query(candidate, ignore, first_id);
        for (int id : q.ids)
            if (prepared_intersect(q.c, entries[static_cast<std::size_t>(id)]->geometry) && fn(id)) return;
    }
};

ElementCollider::ElementCollider(const ElementColliderOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->options = options;
    if (options.cell_size > 0.0 && std::isfinite(options.cell_size)) impl_->cell = options.cell_size;
}
ElementCollider::~ElementCollider() = default;
ElementCollider::ElementCollider(ElementCollider&&) noexcept = default;
ElementCollider& ElementCollider::operator=(ElementCollider&&) noexcept = default;

int ElementCollider::add(const Mesh& element) {
    check_mesh(element, "ElementCollider::add");
    Impl& s = *impl_;
    if (s.entries.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InvalidInput("ElementCollider::add: too many elements");
    const int id = static_cast<int>(s.entries.size());
    auto entry = std::make_unique<Impl::Entry>();
    entry->geometry.prepare(element);
    if (!entry->geometry.tree.empty()) {
        const Box& b = entry->geometry.box;
        if (s.cell <= 0.0) {
            const double extent = std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
            s.cell = extent > 0.0 && std::isfinite(extent) ? extent : 1.0;
        }
        if (s.cell_range(b, entry->cell_lo, entry->cell_hi)) {
            Impl::for_cells(entry->cell_lo, entry->cell_hi, [&](const CellKey& key) { s.grid[key].push_back(id); });
        } else {
            entry->oversized = true;
            s.oversized.push_back(id);  // ids grow, so the list stays sorted
        }
    }
    s.entries.push_back(std::move(entry));
    ++s.alive;
    return id;
}

void ElementCollider::remove(int id) {
    Impl& s = *impl_;
    if (id < 0 || static_cast<std::size_t>(id) >= s.entries.size() || !s.entries[static_cast<std::size_t>(id)]) return;
    const Impl::Entry& e = *s.entries[static_cast<std::size_t>(id)];
    if (e.oversized) {
        s.oversized.erase(std::lower_bound(s.oversized.begin(), s.oversized.end(), id));
    } else if (!e.geometry.tree.empty()) {
        Impl::for_cells(e.cell_lo, e.cell_hi, [&](const CellKey& key) {
            auto it = s.grid.find(key);
            if (it == s.grid.end()) return;
            auto& v = it->second;
            v.erase(std::remove(v.begin(), v.end(), id), v.end());
            if (v.empty()) s.grid.erase(it);
        });
    }
    s.entries[static_cast<std::size_t>(id)].reset();
    --s.alive;
}

std::vector<int> ElementCollider::colliding(const Mesh& candidate, const std::vector<int>& ignore, int first_id) const {
    std::vector<int> out;
    impl_->for_each_colliding(candidate, ignore, first_id, [&](int id) {
        out.push_back(id);
        return false;
    });
    return out;  // ascending: near() returns ids in order
}

bool ElementCollider::collides(const Mesh& candidate, const std::vector<int>& ignore, int first_id) const {
    bool any = false;
    impl_->for_each_colliding(candidate, ignore, first_id, [&](int) { return any = true; });
    return any;
}

std::vector<char> ElementCollider::colliding_faces(const Mesh& candidate, const std::vector<int>& ignore, std::size_t max_hits, int first_id) const {
    std::vector<char> hit(candidate.faces.size(), 0);
    const Impl::Query q = impl_->prepare_query(candidate, ignore, first_id);
    std::vector<NodePair> stack;
    std::size_t hits = 0;
    for (int id : q.ids) {
        const Prepared& e = impl_->entries[static_cast<std::size_t>(id)]->geometry;
        if (e.tree.empty() || !overlap(q.c.box, e.box)) continue;
        auto mark = [&](int i, int j) {
            char& h = hit[static_cast<std::size_t>(q.faces[static_cast<std::size_t>(i)])];
            if (!h && prims_intersect(q.c.prims[static_cast<std::size_t>(i)], e.prims[static_cast<std::size_t>(j)])) {
                h = 1;
                ++hits;
            }
            return hits > max_hits;
        };
        if (traverse_from(q.c.tree, e.tree, false, {0, 0}, mark, stack)) break;
    }
    return hit;
}

std::vector<char> ElementCollider::first_colliding_faces(const Mesh& candidate, const std::vector<int>& group, const std::vector<int>& ignore,
                                                         int first_id) const {
    if (!group.empty() && group.size() != candidate.faces.size())
        throw InvalidInput("ElementCollider::first_colliding_faces: one group per face of the candidate is needed");
    std::vector<char> hit(candidate.faces.size(), 0);
    const Impl::Query q = impl_->prepare_query(candidate, ignore, first_id);
    if (q.ids.empty()) return hit;
    // One tree per group, of the faces that reach into some nearby element's box.
    std::vector<std::pair<int, int>> order;  // (group, prim)
    for (std::size_t i = 0; i < q.faces.size(); ++i)
        order.emplace_back(group.empty() ? 0 : group[static_cast<std::size_t>(q.faces[i])], static_cast<int>(i));
    std::sort(order.begin(), order.end());
    std::vector<BoxTree> trees;
    for (std::size_t k = 0; k < order.size();) {
        std::vector<int> members;
        const int g = order[k].first;
        for (; k < order.size() && order[k].first == g; ++k) members.push_back(order[k].second);
        trees.emplace_back();
        trees.back().build(q.boxes, members);
    }
    std::vector<NodePair> stack;
    for (int id : q.ids) {
        const Prepared& e = impl_->entries[static_cast<std::size_t>(id)]->geometry;
        if (e.tree.empty() || !overlap(q.c.box, e.box)) continue;
        auto first = [&](int i, int j) {
            if (!prims_intersect(q.c.prims[static_cast<std::size_t>(i)], e.prims[static_cast<std::size_t>(j)])) return false;
            hit[static_cast<std::size_t>(q.faces[static_cast<std::size_t>(i)])] = 1;
            return true;
        };
        for (const BoxTree& t : trees)
            if (overlap(t.root_box(), e.box)) traverse_from(t, e.tree, false, {0, 0}, first, stack);
    }
    return hit;
}

std::size_t ElementCollider::size() const { return impl_->alive; }

int ElementCollider::next_id() const { return static_cast<int>(impl_->entries.size()); }

bool ElementCollider::contains(int id) const {
    return id >= 0 && static_cast<std::size_t>(id) < impl_->entries.size() && impl_->entries[static_cast<std::size_t>(id)] != nullptr;
}

Box3 ElementCollider::box(int id) const {
    const Impl& s = *impl_;
    if (id < 0 || static_cast<std::size_t>(id) >= s.entries.size() || !s.entries[static_cast<std::size_t>(id)]) return {};
    const Impl::Entry& e = *s.entries[static_cast<std::size_t>(id)];
    return e.geometry.tree.empty() ? Box3{} : to_box3(e.geometry.box);
}

}  // namespace meshquilt
