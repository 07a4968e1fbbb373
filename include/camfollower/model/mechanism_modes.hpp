// SPDX-License-Identifier: BSD-3-Clause
// Undamped natural frequencies and mode shapes of a mechanism linearized about its quasi-static
// equilibrium at a cam angle: K_t phi = omega^2 M phi, K_t the tangent stiffness with the contacts.
// Every mode (count <= 0) or a few on a small model: the dense symmetric solver. The lowest `count`
// modes of a large model (a flexible camshaft): shift-invert Lanczos on the sparse factor of
// K_t - sigma M (Spectra), with a small negative shift so that rigid-body modes (omega = 0) are found
// as well. The one modal analysis of C++, Python and the command line.
#pragma once

#include <algorithm>
#include <numeric>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include "camfollower/error.hpp"
#include "camfollower/model/mechanism.hpp"

namespace camfollower {

struct MechanismModes {
    Eigen::VectorXd frequencies_hz;     // ascending
    Eigen::MatrixXd shapes;             // columns, mass-normalized (phi^T M phi = I)
    Eigen::MatrixXd tangent_stiffness;  // K_t, N/m (and N m/rad on rotations)
};

// Above this many DOFs lowest_modes() uses the sparse shift-invert solver.
inline constexpr int dense_modes_limit = 200;

// The lowest `count` modes (all of them for count <= 0: a dense solve, seconds above ~2000 DOFs) at
// cam angle theta (rad).
template <int N>
MechanismModes lowest_modes(const Mechanism<N>& m, double theta, int count = 0) {
    detail::require_finite(theta, "theta");
    const int n = m.size();
    if (count > n) detail::fail("count must be <= the number of DOFs (", n, "), got ", count);
    const auto Kt = m.tangent_stiffness(theta, m.static_equilibrium(theta));
    MechanismModes r;
    r.tangent_stiffness = Kt;
    if (n <= dense_modes_limit || count <= 0) {
        const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(Kt),
                                                                            Eigen::MatrixXd(m.mass()));
        if (eig.info() != Eigen::Success) detail::fail("modal analysis: the eigen solver did not converge");
        const int keep = count > 0 ? count : n;
        r.frequencies_hz = eig.eigenvalues().head(keep).cwiseMax(0.0).cwiseSqrt() / two_pi;
        r.shapes = eig.eigenvectors().leftCols(keep);
        return r;
    }
    const Eigen::SparseMatrix<double> K = Eigen::MatrixXd(Kt).sparseView(), M = m.sparse_mass();
    // The shift: a little below zero, on the scale of the lowest diagonal stiffness-to-mass ratio.
    double ratio = std::numeric_limits<double>::infinity();
    for (int k = 0; k < n; ++k)
        if (K.coeff(k, k) > 0.0) ratio = std::min(ratio, K.coeff(k, k) / M.coeff(k, k));
    const double sigma = -1e-3 * (std::isfinite(ratio) ? ratio : 1.0);
    using Op = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
    using BOp = Spectra::SparseSymMatProd<double>;
    Op op(K, M);
    BOp bop(M);
    const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max(2 * count + 1, count + 20));
    Spectra::SymGEigsShiftSolver<Op, BOp, Spectra::GEigsMode::ShiftInvert> eigs(op, bop, count, ncv, sigma);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
    if (eigs.info() != Spectra::CompInfo::Successful)
        detail::fail("modal analysis: the shift-invert eigen solver did not converge for the lowest ", count, " modes");
    const Eigen::VectorXd values = eigs.eigenvalues();
    const Eigen::MatrixXd vectors = eigs.eigenvectors();
    std::vector<int> order(std::size_t(values.size()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b]; });
    r.frequencies_hz.resize(count);
    r.shapes.resize(n, count);
    for (int k = 0; k < count; ++k) {
        r.frequencies_hz[k] = std::sqrt(std::max(values[order[std::size_t(k)]], 0.0)) / two_pi;
        r.shapes.col(k) = vectors.col(order[std::size_t(k)]);
    }
    return r;
}

}  // namespace camfollower
