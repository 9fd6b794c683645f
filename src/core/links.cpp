// SPDX-License-Identifier: AGPL-3.0-or-later
#include "core/links.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
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

bool links_once(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() >= 3 && b.size() >= 3 && std::lround(std::fabs(linking_number(a, b))) == 1;
}

}  // namespace meshquilt
