// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/deform.h"

#include "meshquilt/errors.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>

namespace meshquilt::quilt {

std::vector<Vec3> laplacian_deform(const Mesh& mesh, const std::vector<PointConstraint>& constraints, double mu,
                                   const std::vector<char>& fixed) {
    const int n = static_cast<int>(mesh.vertices.size());
    if (constraints.empty() || n == 0) return mesh.vertices;
    auto is_fixed = [&](int i) { return static_cast<std::size_t>(i) < fixed.size() && fixed[static_cast<std::size_t>(i)]; };

    // Unknowns: the vertices that are not fixed, numbered 0..nf-1.
    std::vector<int> col(static_cast<std::size_t>(n), -1);
    int nf = 0;
    for (int i = 0; i < n; ++i)
        if (!is_fixed(i)) col[static_cast<std::size_t>(i)] = nf++;
    if (nf == 0) return mesh.vertices;
    Eigen::MatrixXd V(n, 3);
    for (int i = 0; i < n; ++i) V.row(i) = mesh.vertices[static_cast<std::size_t>(i)].transpose();

    // Uniform Laplacian, Eq. 4: L(v_i) = v_i - (1/|N(i)|) sum_{j in N(i)} v_j. Only rows that involve an
    // unknown matter; the fixed vertices' terms move to the right-hand side (d = L(v) - L_fixed v).
    std::vector<std::vector<int>> nbr(static_cast<std::size_t>(n));
    for (const Tri& f : mesh.faces)
        for (int k = 0; k < 3; ++k) {
            nbr[f[k]].push_back(f[(k + 1) % 3]);
            nbr[f[k]].push_back(f[(k + 2) % 3]);
        }
    std::vector<Eigen::Triplet<double>> lt;
    std::vector<Eigen::RowVector3d> rhs;
    int rows = 0;
    for (int i = 0; i < n; ++i) {
        auto& N = nbr[static_cast<std::size_t>(i)];
        std::sort(N.begin(), N.end());
        N.erase(std::unique(N.begin(), N.end()), N.end());
        bool touches = !is_fixed(i);
        for (int j : N) touches = touches || !is_fixed(j);
        if (!touches) continue;
        const double w = N.empty() ? 0.0 : 1.0 / static_cast<double>(N.size());
        Eigen::RowVector3d delta = V.row(i);
        for (int j : N) delta -= w * V.row(j);
        Eigen::RowVector3d r = delta;  // minus the fixed vertices' share of this row
        if (is_fixed(i)) r -= V.row(i);
        else lt.emplace_back(rows, col[static_cast<std::size_t>(i)], 1.0);
        for (int j : N) {
            if (is_fixed(j)) r += w * V.row(j);
            else lt.emplace_back(rows, col[static_cast<std::size_t>(j)], -w);
        }
        rhs.push_back(r);
        ++rows;
    }
    Eigen::SparseMatrix<double> L(rows, nf);
    L.setFromTriplets(lt.begin(), lt.end());
    Eigen::MatrixXd d(rows, 3);
    for (int r = 0; r < rows; ++r) d.row(r) = rhs[static_cast<std::size_t>(r)];

    const int m = static_cast<int>(constraints.size());
    std::vector<Eigen::Triplet<double>> ct;
    Eigen::MatrixXd c(m, 3);
    for (int k = 0; k < m; ++k) {
        const auto& pc = constraints[static_cast<std::size_t>(k)];
        Eigen::RowVector3d t = pc.target.transpose();
        for (int j = 0; j < 3; ++j) {
            if (pc.bary[j] == 0.0) continue;
            const int v = pc.v[static_cast<std::size_t>(j)];
            if (is_fixed(v)) t -= pc.bary[j] * V.row(v);
            else ct.emplace_back(k, col[static_cast<std::size_t>(v)], pc.bary[j]);
        }
        c.row(k) = t;
    }
    Eigen::SparseMatrix<double> C(m, nf);
    C.setFromTriplets(ct.begin(), ct.end());

    Eigen::MatrixXd Vf(nf, 3);
    for (int i = 0; i < n; ++i)
        if (!is_fixed(i)) Vf.row(col[static_cast<std::size_t>(i)]) = V.row(i);

    // Normal equations of the least-squares problem, with eps * |w - v|^2 to pin unconstrained parts.
    const double eps = 1e-8;
    Eigen::SparseMatrix<double> I(nf, nf);
    I.setIdentity();
    const Eigen::SparseMatrix<double> Lt = L.transpose();
    const Eigen::SparseMatrix<double> A = Lt * L + mu * Eigen::SparseMatrix<double>(C.transpose()) * C + eps * I;
    const Eigen::MatrixXd b = Lt * d + mu * (C.transpose() * c) + eps * Vf;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success) throw BackendFailure("element deformation: sparse factorisation failed");
    const Eigen::MatrixXd W = solver.solve(b);
    if (solver.info() != Eigen::Success || !W.allFinite()) throw BackendFailure("element deformation: solve failed");
    std::vector<Vec3> out = mesh.vertices;
    for (int i = 0; i < n; ++i)
        if (!is_fixed(i)) out[static_cast<std::size_t>(i)] = W.row(col[static_cast<std::size_t>(i)]).transpose();
    return out;
}

}  // namespace meshquilt::quilt
