// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/field.h"

#include "core/triangle_index.h"
#include "meshquilt/errors.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <numeric>

namespace meshquilt::quilt {

std::vector<std::array<int, 3>> face_neighbours(const Mesh& mesh) {
    std::vector<std::array<int, 3>> nb(mesh.faces.size(), {-1, -1, -1});
    // Half-edges sorted by their undirected key; a manifold edge has exactly two.
    struct He {
        std::uint64_t key;
        int face, k;
    };
    std::vector<He> hes;
    hes.reserve(3 * mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::uint64_t>(mesh.faces[f][k]), b = static_cast<std::uint64_t>(mesh.faces[f][(k + 1) % 3]);
            hes.push_back({std::min(a, b) << 32 | std::max(a, b), static_cast<int>(f), k});
        }
    std::sort(hes.begin(), hes.end(), [](const He& x, const He& y) { return x.key != y.key ? x.key < y.key : x.face < y.face; });
    for (std::size_t i = 0; i < hes.size();) {
        std::size_t j = i;
        while (j < hes.size() && hes[j].key == hes[i].key) ++j;
        if (j - i == 2) {
            nb[static_cast<std::size_t>(hes[i].face)][static_cast<std::size_t>(hes[i].k)] = hes[i + 1].face;
            nb[static_cast<std::size_t>(hes[i + 1].face)][static_cast<std::size_t>(hes[i + 1].k)] = hes[i].face;
        }
        i = j;
    }
    return nb;
}

double symmetric_angle(const Vec3& a, const Vec3& b, const Vec3& normal, int symmetry) {
    const Vec3 n = normal.normalized();
    const Vec3 pa = a - a.dot(n) * n, pb = b - b.dot(n) * n;
    double angle = std::atan2(pa.cross(pb).dot(n), pa.dot(pb));  // (-pi, pi]
    const double period = 2.0 * M_PI / std::max(1, symmetry);
    angle = std::fmod(std::fabs(angle), period);
    return std::min(angle, period - angle);
}

namespace {

struct Frame {
    Vec3 e1, e2, n;
};

std::vector<Frame> face_frames(const Mesh& m) {
    std::vector<Frame> fr(m.faces.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Tri& t = m.faces[f];
        Vec3 n = face_cross(m, f);
        n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitZ();
        Vec3 e1 = m.vertices[t[1]] - m.vertices[t[0]];
        e1 -= e1.dot(n) * n;
        e1 = e1.norm() > 0 ? Vec3(e1.normalized()) : n.unitOrthogonal();
        fr[f] = {e1, n.cross(e1), n};
    }
    return fr;
}

using SpMat = Eigen::SparseMatrix<double>;
using Trip = Eigen::Triplet<double>;

/// x^T A x = sum over interior edges of |z_g - r_fg z_f|^2, z_f = x[2f] + i x[2f+1] the N-th power
/// of face f's direction in its own frame, r_fg the transport of N-th powers across the edge.
std::vector<Trip> connection_laplacian(const Mesh& m, const std::vector<std::array<int, 3>>& nb, const std::vector<Frame>& fr, int N) {
    std::vector<Trip> tr;
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int g = nb[f][static_cast<std::size_t>(k)];
            if (g < 0 || static_cast<std::size_t>(g) < f) continue;
            const Vec3 e = m.vertices[m.faces[f][(k + 1) % 3]] - m.vertices[m.faces[f][k]];
            const Frame& a = fr[f];
            const Frame& b = fr[static_cast<std::size_t>(g)];
            const double tf = std::atan2(e.dot(a.e2), e.dot(a.e1)), tg = std::atan2(e.dot(b.e2), e.dot(b.e1));
            const double c = std::cos(N * (tg - tf)), s = std::sin(N * (tg - tf));
            const int F = 2 * static_cast<int>(f), G = 2 * g;
            // residual = z_g - R z_f with R = [[c, -s], [s, c]]
            for (int d = 0; d < 2; ++d) {
                tr.emplace_back(F + d, F + d, 1.0);
                tr.emplace_back(G + d, G + d, 1.0);
            }
            // -R^T at (F, G) block and -R at (G, F)
            tr.emplace_back(G, F, -c);
            tr.emplace_back(G, F + 1, s);
            tr.emplace_back(G + 1, F, -s);
            tr.emplace_back(G + 1, F + 1, -c);
            tr.emplace_back(F, G, -c);
            tr.emplace_back(F + 1, G, s);
            tr.emplace_back(F, G + 1, -s);
            tr.emplace_back(F + 1, G + 1, -c);
        }
    return tr;
}

std::vector<int> face_components(const std::vector<std::array<int, 3>>& nb, int* count) {
    std::vector<int> comp(nb.size(), -1);
    int c = 0;
    std::vector<int> stack;
    for (std::size_t s = 0; s < nb.size(); ++s) {
        if (comp[s] >= 0) continue;
        comp[s] = c;
        stack.assign(1, static_cast<int>(s));
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int g : nb[static_cast<std::size_t>(f)])
                if (g >= 0 && comp[static_cast<std::size_t>(g)] < 0) {
                    comp[static_cast<std::size_t>(g)] = c;
                    stack.push_back(g);
                }
        }
        ++c;
    }
    *count = c;
    return comp;
}

/// Turns each component's smoothest field as a whole (its smoothness does not change: the
/// energy is invariant under a constant rotation) to follow the component's open boundary as well
/// as it can: by the length-weighted mean, in N-th powers, of the boundary edges' directions
/// against the field on their faces. Applied only where those directions agree (the mean keeps at
/// least a third of the total length): along the rims of a tube, not around a round hole (whose
/// directions cancel). Sharp edges were tried too and left out: on the coarse eight 8 edges just
/// above 45 degrees turned the whole field, and its test outputs moved by chance (pebbles 1.09 ->
/// 1.17 of the swatch's density in one region).
void align_to_edges(const Mesh& m, const std::vector<std::array<int, 3>>& nb, const std::vector<Frame>& fr, int N,
                    const std::vector<int>& comp, int ncomp, Eigen::VectorXd* x) {
    std::vector<std::complex<double>> sum(static_cast<std::size_t>(ncomp), 0.0);
    std::vector<double> weight(static_cast<std::size_t>(ncomp), 0.0);
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            if (nb[f][static_cast<std::size_t>(k)] >= 0) continue;  // not a boundary edge
            const Vec3 e = m.vertices[m.faces[f][(k + 1) % 3]] - m.vertices[m.faces[f][k]];
            const double len = e.norm();
            if (!(len > 0)) continue;
            const std::complex<double> z(x->coeff(static_cast<Eigen::Index>(2 * f)), x->coeff(static_cast<Eigen::Index>(2 * f + 1)));
            if (std::abs(z) == 0.0) continue;
            const double phi = std::atan2(e.dot(fr[f].e2), e.dot(fr[f].e1));
            const auto c = static_cast<std::size_t>(comp[f]);
            sum[c] += len * std::polar(1.0, N * phi) * std::conj(z) / std::abs(z);
            weight[c] += len;
        }
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const auto c = static_cast<std::size_t>(comp[f]);
        if (!(weight[c] > 0) || std::abs(sum[c]) < weight[c] / 3.0) continue;
        const std::complex<double> turn = sum[c] / std::abs(sum[c]);
        const std::complex<double> z(x->coeff(static_cast<Eigen::Index>(2 * f)), x->coeff(static_cast<Eigen::Index>(2 * f + 1)));
        const std::complex<double> r = turn * z;
        (*x)[static_cast<Eigen::Index>(2 * f)] = r.real();
        (*x)[static_cast<Eigen::Index>(2 * f + 1)] = r.imag();
    }
}

struct Constraint {
    int face;
    Vec3 vector;  ///< tangent, length = scale
};

}  // namespace

DirectionField compute_field(const Mesh& m, const std::vector<std::array<int, 3>>& nb, int N, const GuidanceField& user,
                             const std::string& name) {
    const std::size_t F = m.faces.size();
    DirectionField out;
    out.symmetry = N;
    out.direction.assign(F, Vec3::UnitX());
    out.scale.assign(F, 1.0);
    if (F == 0) return out;
    const std::vector<Frame> fr = face_frames(m);

    // Constraints, projected onto the faces' planes.
    std::vector<Constraint> cons;
    auto tangent = [&](int f, const Vec3& v) {
        const Vec3& n = fr[static_cast<std::size_t>(f)].n;
        return Vec3(v - v.dot(n) * n);
    };
    for (std::size_t i = 0; i < user.faces.size(); ++i) {
        const auto& fv = user.faces[i];
        if (fv.face < 0 || static_cast<std::size_t>(fv.face) >= F)
            throw InvalidInput(name + ": field value " + std::to_string(i + 1) + " names face " + std::to_string(fv.face) +
                               ", but the base has " + std::to_string(F) + " faces");
        if (!fv.vector.allFinite() || tangent(fv.face, fv.vector).norm() < 1e-12 * std::max(1.0, fv.vector.norm()))
            throw InvalidInput(name + ": field vector of face " + std::to_string(fv.face) + " is zero, not finite or normal to the face");
        const Vec3 t = tangent(fv.face, fv.vector);
        cons.push_back({fv.face, t.normalized() * fv.vector.norm()});
    }
    if (!user.vertices.empty()) {
        std::vector<std::vector<int>> faces_of(m.vertices.size());
        for (std::size_t f = 0; f < F; ++f)
            for (int k = 0; k < 3; ++k) faces_of[static_cast<std::size_t>(m.faces[f][k])].push_back(static_cast<int>(f));
        for (const auto& vv : user.vertices) {
            if (vv.vertex < 0 || static_cast<std::size_t>(vv.vertex) >= m.vertices.size())
                throw InvalidInput(name + ": field names vertex " + std::to_string(vv.vertex) + ", but the base has " +
                                   std::to_string(m.vertices.size()) + " vertices");
            if (!vv.vector.allFinite() || vv.vector.norm() == 0.0)
                throw InvalidInput(name + ": field vector of vertex " + std::to_string(vv.vertex) + " is zero or not finite");
            for (int f : faces_of[static_cast<std::size_t>(vv.vertex)]) {
                const Vec3 t = tangent(f, vv.vector);
                if (t.norm() > 1e-9 * vv.vector.norm()) cons.push_back({f, t.normalized() * vv.vector.norm()});
            }
        }
    }
    if (!user.strokes.empty()) {
        const TriangleIndex index(m);
        for (std::size_t s = 0; s < user.strokes.size(); ++s) {
            const auto& st = user.strokes[s];
            if (st.size() < 2) throw InvalidInput(name + ": stroke " + std::to_string(s + 1) + " has fewer than 2 points");
            for (std::size_t i = 0; i + 1 < st.size(); ++i) {
                const Vec3 d = st[i + 1] - st[i];
                if (!d.allFinite()) throw InvalidInput(name + ": stroke " + std::to_string(s + 1) + " has a non-finite point");
                if (d.norm() == 0.0) continue;
                // The segment's ends and middle constrain the faces nearest to them.
                for (double t : {0.0, 0.5, 1.0}) {
                    const ClosestHit h = index.closest(st[i] + t * d);
                    if (h.face < 0) continue;
                    const Vec3 tv = tangent(h.face, d);
                    if (tv.norm() > 1e-9 * d.norm()) cons.push_back({h.face, tv.normalized()});
                }
            }
        }
    }

    const std::vector<Trip> lap = connection_laplacian(m, nb, fr, N);
    Eigen::VectorXd x(2 * F);
    if (cons.empty()) {
        // Smoothest field: inverse iteration on (A + eps M) x' = M x, normalised per component.
        std::vector<double> area(F);
        double total = 0.0;
        for (std::size_t f = 0; f < F; ++f) total += (area[f] = std::max(face_area(m, f), 1e-300));
        const double mean = total / static_cast<double>(F);
        std::vector<Trip> tr = lap;
        for (std::size_t f = 0; f < F; ++f)
            for (int d = 0; d < 2; ++d) tr.emplace_back(2 * static_cast<int>(f) + d, 2 * static_cast<int>(f) + d, 1e-6 * area[f] / mean);
        SpMat A(static_cast<Eigen::Index>(2 * F), static_cast<Eigen::Index>(2 * F));
        A.setFromTriplets(tr.begin(), tr.end());
        Eigen::SimplicialLDLT<SpMat> solver(A);
        if (solver.info() != Eigen::Success) throw BackendFailure("direction field: factorisation failed");
        int ncomp = 0;
        const std::vector<int> comp = face_components(nb, &ncomp);
        for (std::size_t f = 0; f < F; ++f) {  // deterministic, generic start
            x[static_cast<Eigen::Index>(2 * f)] = std::cos(0.7 * static_cast<double>(f));
            x[static_cast<Eigen::Index>(2 * f + 1)] = std::sin(1.3 * static_cast<double>(f)) + 0.5;
        }
        for (int it = 0; it < 40; ++it) {
            Eigen::VectorXd b(2 * F);
            for (std::size_t f = 0; f < F; ++f)
                for (int d = 0; d < 2; ++d) b[static_cast<Eigen::Index>(2 * f + d)] = area[f] / mean * x[static_cast<Eigen::Index>(2 * f + d)];
            x = solver.solve(b);
            std::vector<double> norm(static_cast<std::size_t>(ncomp), 0.0);
            for (std::size_t f = 0; f < F; ++f)
                norm[static_cast<std::size_t>(comp[f])] += area[f] / mean * x.segment<2>(static_cast<Eigen::Index>(2 * f)).squaredNorm();
            for (std::size_t f = 0; f < F; ++f) {
                const double n = std::sqrt(norm[static_cast<std::size_t>(comp[f])]);
                if (n > 0) x.segment<2>(static_cast<Eigen::Index>(2 * f)) /= n;
            }
        }
        align_to_edges(m, nb, fr, N, comp, ncomp, &x);
    } else {
        // Smoothest field through the constraints (soft, weight w): (A + w C) x = w C z.
        const double w = 100.0;
        std::vector<Trip> tr = lap;
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * F));
        for (const Constraint& c : cons) {
            const Frame& f = fr[static_cast<std::size_t>(c.face)];
            const double phi = std::atan2(c.vector.dot(f.e2), c.vector.dot(f.e1));
            const int i = 2 * c.face;
            tr.emplace_back(i, i, w);
            tr.emplace_back(i + 1, i + 1, w);
            rhs[i] += w * std::cos(N * phi);
            rhs[i + 1] += w * std::sin(N * phi);
        }
        for (std::size_t f = 0; f < 2 * F; ++f) tr.emplace_back(static_cast<int>(f), static_cast<int>(f), 1e-9);
        SpMat A(static_cast<Eigen::Index>(2 * F), static_cast<Eigen::Index>(2 * F));
        A.setFromTriplets(tr.begin(), tr.end());
        Eigen::SimplicialLDLT<SpMat> solver(A);
        if (solver.info() != Eigen::Success) throw BackendFailure("direction field: factorisation failed");
        x = solver.solve(rhs);

        // Scale: harmonic interpolation of the constraint lengths over the dual graph.
        std::vector<Trip> ts;
        Eigen::VectorXd rs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(F));
        for (std::size_t f = 0; f < F; ++f) {
            for (int g : nb[f])
                if (g >= 0) {
                    ts.emplace_back(static_cast<int>(f), static_cast<int>(f), 1.0);
                    ts.emplace_back(static_cast<int>(f), g, -1.0);
                }
            ts.emplace_back(static_cast<int>(f), static_cast<int>(f), 1e-9);
        }
        for (const Constraint& c : cons) {
            ts.emplace_back(c.face, c.face, w);
            rs[c.face] += w * std::log(c.vector.norm());
        }
        // Components without any constraint keep scale 1 (log 0) through the tiny diagonal term.
        SpMat S(static_cast<Eigen::Index>(F), static_cast<Eigen::Index>(F));
        S.setFromTriplets(ts.begin(), ts.end());
        Eigen::SimplicialLDLT<SpMat> ss(S);
        if (ss.info() != Eigen::Success) throw BackendFailure("field scale: factorisation failed");
        const Eigen::VectorXd ls = ss.solve(rs);
        for (std::size_t f = 0; f < F; ++f) out.scale[f] = std::clamp(std::exp(ls[static_cast<Eigen::Index>(f)]), 0.05, 20.0);
    }
    for (std::size_t f = 0; f < F; ++f) {
        const double a = x[static_cast<Eigen::Index>(2 * f)], b = x[static_cast<Eigen::Index>(2 * f + 1)];
        const double phi = (a == 0.0 && b == 0.0) ? 0.0 : std::atan2(b, a) / N;
        out.direction[f] = std::cos(phi) * fr[f].e1 + std::sin(phi) * fr[f].e2;
    }
    return out;
}

int detect_symmetry(const SwatchData& sw) {
    // Area-weighted mean of e^{2i theta} and e^{4i theta} over elongated elements' principal axes.
    std::complex<double> m2 = 0.0, m4 = 0.0;
    double weight = 0.0, elongated = 0.0;
    for (const Mesh& e : sw.elements) {
        if (e.vertices.size() < 3) continue;
        Vec2 c = Vec2::Zero();
        for (const Vec3& v : e.vertices) c += v.head<2>();
        c /= static_cast<double>(e.vertices.size());
        Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
        for (const Vec3& v : e.vertices) cov += (v.head<2>() - c) * (v.head<2>() - c).transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
        const double l0 = std::max(es.eigenvalues()[0], 0.0), l1 = es.eigenvalues()[1];
        const double a = mesh_area(e);
        weight += a;
        if (l1 <= 0 || std::sqrt(l1 / std::max(l0, 1e-300)) < 2.0) continue;
        elongated += a;
        const Vec2 axis = es.eigenvectors().col(1);
        const double th = std::atan2(axis.y(), axis.x());
        m2 += a * std::polar(1.0, 2 * th);
        m4 += a * std::polar(1.0, 4 * th);
    }
    if (weight <= 0 || elongated < 0.3 * weight) return 4;
    if (std::abs(m2) / elongated > 0.6) return 2;
    return 4;
}

}  // namespace meshquilt::quilt
