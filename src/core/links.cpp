// SPDX-License-Identifier: AGPL-3.0-or-later
#include "core/links.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace meshquilt {

std::vector<Vec3> ring_centerline(const Mesh& ring, int bins) {
    if (bins < 3) throw std::invalid_argument("ring_centerline: bins must be >= 3");
    std::vector<char> used(ring.vertices.size(), 0);
    for (const Tri& t : ring.faces)
        for (int k = 0; k < 3; ++k) used.at(static_cast<std::size_t>(t[k])) = 1;
    std::vector<Vec3> pts;
    for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v]) pts.push_back(ring.vertices[v]);
    if (pts.size() < 3) return pts;

    Vec3 c = Vec3::Zero();
    for (const Vec3& p : pts) c += p;
    c /= static_cast<double>(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& p : pts) cov += (p - c) * (p - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // eigenvalues ascending
    const Vec3 n = eig.eigenvectors().col(0);
    const Vec3 u = eig.eigenvectors().col(2);
    const Vec3 w = n.cross(u);

    std::vector<Vec3> sum(static_cast<std::size_t>(bins), Vec3::Zero());
    std::vector<int> count(static_cast<std::size_t>(bins), 0);
    for (const Vec3& p : pts) {
        const Vec3 d = p - c;
        // Bins start at an irrational fraction of a bin past u, so that the columns of a regular
        // ring mesh (at rational multiples of 2 pi) do not sit on bin boundaries.
        constexpr double kBinPhase = 0.2763932022500210;
        const double angle = std::atan2(d.dot(w), d.dot(u));  // [-pi, pi]
        const double x = (angle + M_PI) / (2.0 * M_PI) * bins + kBinPhase;
        int b = static_cast<int>(std::floor(x)) % bins;
        b = std::clamp(b, 0, bins - 1);
        sum[static_cast<std::size_t>(b)] += p;
        ++count[static_cast<std::size_t>(b)];
    }
    std::vector<Vec3> line;
    for (int b = 0; b < bins; ++b)
        if (count[static_cast<std::size_t>(b)] > 0) line.push_back(sum[static_cast<std::size_t>(b)] / count[static_cast<std::size_t>(b)]);
    return line;
}

double linking_number(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.size() < 3 || b.size() < 3) throw std::invalid_argument("linking_number: each curve needs >= 3 points");
    // Klenin & Langowski 2000, Eq. 4-5: for segment p1p2 of a and p3p4 of b, the signed solid angle
    // of the quadrilateral p1 p3 p2 p4 (seen as the two segments' mutual Gauss map area) is
    //   Omega = [asin(n1.n2) + asin(n2.n3) + asin(n3.n4) + asin(n4.n1)] * sign((r34 x r12) . r13),
    // with unit normals n1 = r13 x r14, n2 = r14 x r24, n3 = r24 x r23, n4 = r23 x r13. Lk = sum / 4 pi.
    auto unit = [](const Vec3& v, bool& ok) {
        const double l = v.norm();
        ok = ok && l > 0.0;
        return l > 0.0 ? Vec3(v / l) : Vec3::Zero();
    };
    auto asin_clamped = [](double x) { return std::asin(std::clamp(x, -1.0, 1.0)); };
    double total = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Vec3& p1 = a[i];
        const Vec3& p2 = a[(i + 1) % a.size()];
        const Vec3 r12 = p2 - p1;
        for (std::size_t j = 0; j < b.size(); ++j) {
            const Vec3& p3 = b[j];
            const Vec3& p4 = b[(j + 1) % b.size()];
            const Vec3 r13 = p3 - p1, r14 = p4 - p1, r23 = p3 - p2, r24 = p4 - p2, r34 = p4 - p3;
            const double triple = r34.cross(r12).dot(r13);
            if (triple == 0.0) continue;  // coplanar segments: no contribution
            bool ok = true;
            const Vec3 n1 = unit(r13.cross(r14), ok), n2 = unit(r14.cross(r24), ok), n3 = unit(r24.cross(r23), ok),
                       n4 = unit(r23.cross(r13), ok);
            if (!ok) continue;
            const double omega = asin_clamped(n1.dot(n2)) + asin_clamped(n2.dot(n3)) + asin_clamped(n3.dot(n4)) +
                                 asin_clamped(n4.dot(n1));
            total += triple > 0.0 ? omega : -omega;
        }
    }
    return total / (4.0 * M_PI);
}

Vec3 shadow_direction() {
    // Away from the axes and their diagonals, so that the rows and columns of a modelled ring do
    // not line up in the shadow.
    return Vec3(0.5714, 0.3162, 0.7571).normalized();
}

int crossing_linking_number(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.size() < 3 || b.size() < 3) throw std::invalid_argument("crossing_linking_number: each curve needs >= 3 points");
    auto gauss = [&] { return static_cast<int>(std::lround(linking_number(a, b))); };
    // The shadows on the plane normal to shadow_direction.
    const Vec3 d = shadow_direction();
    const Vec3 e1 = d.cross(Vec3(0.0, 0.0, 1.0)).normalized(), e2 = d.cross(e1);
    struct Shadow {
        std::vector<Eigen::Vector2d> p;
        std::vector<Eigen::Vector2d> lo, hi;  ///< per segment i (point i to i + 1): its box
    };
    auto shadow = [&](const std::vector<Vec3>& c) {
        Shadow s;
        for (const Vec3& q : c) s.p.emplace_back(q.dot(e1), q.dot(e2));
        for (std::size_t i = 0; i < c.size(); ++i) {
            const Eigen::Vector2d &u = s.p[i], &v = s.p[(i + 1) % c.size()];
            s.lo.push_back(u.cwiseMin(v));
            s.hi.push_back(u.cwiseMax(v));
        }
        return s;
    };
    const Shadow sa = shadow(a), sb = shadow(b);
    // Shewchuk's error bound for the orientation of three points (ccwerrboundA): a determinant
    // larger than it in magnitude has the sign of the exact one of the rounded shadow points.
    constexpr double kOrientBound = (3.0 + 16.0 * std::numeric_limits<double>::epsilon()) * std::numeric_limits<double>::epsilon();
    bool unsure = false;
    auto side = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
        const double l = (q.x() - p.x()) * (r.y() - p.y()), m = (q.y() - p.y()) * (r.x() - p.x());
        const double det = l - m;
        if (!(std::fabs(det) > kOrientBound * (std::fabs(l) + std::fabs(m)))) unsure = true;
        return det > 0.0;
    };
    int twice = 0;  // the sum of the crossings' signs: twice the linking number
    for (std::size_t i = 0; i < a.size() && !unsure; ++i) {
        const std::size_t i1 = (i + 1) % a.size();
        for (std::size_t j = 0; j < b.size(); ++j) {
            if ((sa.lo[i].array() > sb.hi[j].array()).any() || (sb.lo[j].array() > sa.hi[i].array()).any()) continue;
            const std::size_t j1 = (j + 1) % b.size();
            const bool apart = side(sa.p[i], sa.p[i1], sb.p[j]) == side(sa.p[i], sa.p[i1], sb.p[j1]) ||
                               side(sb.p[j], sb.p[j1], sa.p[i]) == side(sb.p[j], sb.p[j1], sa.p[i1]);
            if (unsure) break;
            if (apart) continue;
            // The shadows cross: the sign is the Gauss integrand's on the pair,
            // (p2 - p1) x (p4 - p3) . (p1 - p3) (linking_number's `triple`).
            const Vec3 r12 = a[i1] - a[i], r34 = b[j1] - b[j], r31 = a[i] - b[j];
            const double triple = r12.cross(r34).dot(r31);
            if (!(std::fabs(triple) > 1e-12 * r12.norm() * r34.norm() * r31.norm())) {
                unsure = true;  // the segments nearly meet
                break;
            }
            twice += triple > 0.0 ? 1 : -1;
        }
    }
    if (unsure || twice % 2 != 0) return gauss();
    return twice / 2;
}

bool links_once(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() >= 3 && b.size() >= 3 && std::abs(crossing_linking_number(a, b)) == 1;
}

}  // namespace meshquilt
