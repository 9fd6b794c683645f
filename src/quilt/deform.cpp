// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/deform.h"

#include "meshquilt/errors.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>

namespace meshquilt::quilt {

std::vector<Vec3> laplacian_deform(const Mesh& mesh, const std::vector<PointConstraint>& constraints, double mu) {
    const int n = static_cast<int>(mesh.vertices.size());
    if (constraints.empty() || n == 0) return mesh.vertices;

    // Uniform Laplacian, Eq. 4: L(v_i) = v_i - (1/|N(i)|) sum_{j in N(i)} v_j.
    std::vector<std::vector<int>> nbr(static_cast<std::size_t>(n));
    for (const Tri& f : mesh.faces)
        for (int k = 0; k < 3; ++k) {
            nbr[f[k]].push_back(f[(k + 1) % 3]);
            nbr[f[k]].push_back(f[(k + 2) % 3]);
        }
    std::vector<Eigen::Triplet<double>> lt;
    for (int i = 0; i < n; ++i) {
        auto& N = nbr[i];
        std::sort(N.begin(), N.end());
        N.erase(std::unique(N.begin(), N.end()), N.end());
        lt.emplace_back(i, i, 1.0);
        for (int j : N) lt.emplace_back(i, j, -1.0 / static_cast<double>(N.size()));
    }
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(lt.begin(), lt.end());

    const int m = static_cast<int>(constraints.size());
    std::vector<Eigen::Triplet<double>> ct;
    Eigen::MatrixXd c(m, 3);
    for (int k = 0; k < m; ++k) {
        const auto& pc = constraints[static_cast<std::size_t>(k)];
        for (int j = 0; j < 3; ++j)
            if (pc.bary[j] != 0.0) ct.emplace_back(k, pc.v[static_cast<std::size_t>(j)], pc.bary[j]);
        c.row(k) = pc.target.transpose();
    }
    Eigen::SparseMatrix<double> C(m, n);
    C.setFromTriplets(ct.begin(), ct.end());

    Eigen::MatrixXd V(n, 3);
    for (int i = 0; i < n; ++i) V.row(i) = mesh.vertices[i].transpose();

    // Normal equations of the least-squares problem, with eps * |w - v|^2 to pin unconstrained parts.
    const double eps = 1e-8;
    Eigen::SparseMatrix<double> I(n, n);
    I.setIdentity();
    const Eigen::SparseMatrix<double> LtL = Eigen::SparseMatrix<double>(L.transpose()) * L;
    const Eigen::SparseMatrix<double> A = LtL + mu * Eigen::SparseMatrix<double>(C.transpose()) * C + eps * I;
    const Eigen::MatrixXd b = LtL * V + mu * (C.transpose() * c) + eps * V;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success) throw BackendFailure("element deformation: sparse factorisation failed");
    const Eigen::MatrixXd W = solver.solve(b);
    if (solver.info() != Eigen::Success || !W.allFinite()) throw BackendFailure("element deformation: solve failed");
    std::vector<Vec3> out(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = W.row(i).transpose();
    return out;
}

}  // namespace meshquilt::quilt
