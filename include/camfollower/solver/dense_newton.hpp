// SPDX-License-Identifier: BSD-3-Clause
// The Newmark stepper's Newton algebra for small, dense models (fixed-size Eigen): the matrix
// A0 + (1 + alpha) U V^T, A0 inverted once per step size, solved by Sherman-Morrison (rank one),
// Woodbury (small ranks) or a dense LU (larger ranks). The sparse counterpart is
// solver/sparse_newton.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/constants.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"
#include "camfollower/solver/step_limit.hpp"

namespace camfollower {

// The Newton matrix's algebra for dense systems: A0 = M / (beta dt^2) + (1 + alpha)(gamma / (beta dt) C
// + K) inverted once per step size, the tangent as dense low-rank columns, Sherman-Morrison / Woodbury
// / dense LU by rank.
template <class System>
class DenseNewtonSolve {
public:
    using Vector = typename System::Vector;
    using Matrix = typename System::Matrix;
    using Tangent = LowRank<Vector>;
    // Ranks up to this are solved by Woodbury with a fixed-capacity k x k matrix (no allocation).
    static constexpr int max_woodbury_rank = 8;
    // Above this the levels' factorizations alone take seconds to minutes: the sparse backend's job.
    static constexpr int max_dofs = 1000;
    // The eigen solve bounding the inverse (a Newton shortcut) only where it is cheap.
    static constexpr int max_eigen_dofs = 200;

    DenseNewtonSolve(const System& system, const SolverSettings& s)
        : system_(system), s_(s), p_(newmark_parameters(s)), n_(system.size()), uv_(n_, std::max(1, max_rank(system))) {
        const Matrix& M = system.mass();
        if (M.rows() != n_ || M.cols() != n_ || system.damping().rows() != n_ || system.damping().cols() != n_ ||
            system.stiffness().rows() != n_ || system.stiffness().cols() != n_)
            detail::fail("system: mass, damping and stiffness must be ", n_, " x ", n_, " (size())");
        for (int k = 0; k < n_; ++k)
            if (!(M(k, k) > 0.0))
                detail::fail("system: mass matrix diagonal must be > 0, got M(", k, ", ", k, ") = ", M(k, k));
        if (n_ > max_dofs)
            detail::fail("linear_solver '", linear_solver_name(s_), "' (dense) is limited to ", max_dofs,
                         " DOFs (it factorizes n x n "
                         "matrices for every step size); this system has ",
                         n_, ": use 'sparse' or 'auto'");
        // The cheap refusal first: sqrt(K_kk / M_kk), a Rayleigh quotient, bounds omega_max from below,
        // so a fixed step beyond the scheme's limit for it is beyond the true limit too; O(n), before the
        // O(n^3) factorizations below (start() checks the exact limit).
        if (!s_.tolerance && p_.beta < 0.5 * p_.gamma) {
            double omega_low = 0.0;
            for (int k = 0; k < n_; ++k)
                omega_low = std::max(omega_low, std::sqrt(std::max(system.stiffness()(k, k), 0.0) / M(k, k)));
            const double limit = newmark_step_limit(p_.gamma, p_.beta, omega_low);
            if (s_.time_step > limit)
                detail::fail("time_step = ", s_.time_step,
                             " s exceeds the stability limit of Newmark with beta = ", p_.beta,
                             " < gamma / 2: at most ", limit, " s (a mode at ", omega_low / (2.0 * pi),
                             " Hz or faster); reduce "
                             "time_step, use beta = 1/4 or method 'auto'");
        }
        const int levels = s_.max_halvings + 1;
        for (int level = 0; level < levels; ++level) {
            const double dt = s_.time_step / double(1 << level);
            A0_[level] = system.mass() / (p_.beta * dt * dt) +
                         (1.0 + p_.alpha) * (p_.damping_gamma / (p_.beta * dt) * system.damping() + system.stiffness());
            Aa_[level] = (p_.beta * dt * dt) * A0_[level];
            // An explicit inverse applied as one matrix-vector product beats two triangular solves for
            // the small, well-conditioned matrices of lumped models.
            A0_inv_[level] = A0_[level].partialPivLu().inverse();
            // 1 / lambda_min(A0) when A0 is symmetric positive definite (0 disables the bound).
            inverse_bound_[level] = 0.0;
            if (n_ <= max_eigen_dofs && (A0_[level] - A0_[level].transpose()).cwiseAbs().maxCoeff() <=
                                            1e-14 * A0_[level].cwiseAbs().maxCoeff()) {
                const Eigen::SelfAdjointEigenSolver<Matrix> eig(A0_[level], Eigen::EigenvaluesOnly);
                if (eig.info() == Eigen::Success && eig.eigenvalues()[0] > 0.0)
                    inverse_bound_[level] = 1.0 / eig.eigenvalues()[0];
            }
        }
        const int cap = uv_.capacity();
        Z_.resize(n_, cap);
        U_cached_.resize(n_, cap);
        x_.resize(n_);
        full_.resize(n_, n_);
        if constexpr (Matrix::RowsAtCompileTime == Eigen::Dynamic) lu_ = Eigen::PartialPivLU<Matrix>(n_);
    }

    const Matrix& mass() const { return system_.mass(); }
    const Matrix& damping() const { return system_.damping(); }
    const Matrix& stiffness() const { return system_.stiffness(); }
    const Matrix& residual_matrix(int level) const { return Aa_[level]; }  // r = Aa a + ...
    double inverse_bound(int level) const { return inverse_bound_[level]; }
    Tangent& tangent() { return uv_; }
    int rank() const { return uv_.rank; }
    void fill_tangent(const workspace_t<System>& ws, const Vector& q, const Vector& v, double cq, double cv) {
        camfollower::tangent(system_, ws, q, v, cq, cv, uv_);
    }
    // sum_k max|U_k| |V_k|_1: the tangent's contribution to the residual's rounding floor.
    double tangent_norm() const {
        double norm = 0.0;
        for (int k = 0; k < uv_.rank; ++k) norm += uv_.U.col(k).cwiseAbs().maxCoeff() * uv_.V.col(k).cwiseAbs().sum();
        return norm;
    }
    // True when (1 + alpha) U V^T is symmetric positive semi-definite: every V column a non-negative
    // multiple of its U column.
    bool tangent_is_spd() const {
        for (int k = 0; k < uv_.rank; ++k) {
            const auto u = uv_.U.col(k);
            const auto w = uv_.V.col(k);
            const double s = w.dot(u) / u.squaredNorm();
            if (!(s >= 0.0) || (w - s * u).squaredNorm() > 1e-24 * w.squaredNorm()) return false;
        }
        return true;
    }
    void new_step() { cached_rank_ = 0; }

    // dq = -(A0 + (1 + alpha) U V^T)^-1 r.
    void solve(int level, double one_alpha, const Vector& r, Vector& dq) {
        update_woodbury_columns(level, one_alpha);
        const int k = uv_.rank;
        if (solved_by_lu(level, one_alpha, r, dq)) return;
        x_.noalias() = A0_inv_[level] * r;
        if (k == 0) {
            dq = -x_;
        } else if (k == 1) {  // Sherman-Morrison
            const auto w = uv_.V.col(0);
            const auto z = Z_.col(0);
            dq = -(x_ - z * (w.dot(x_) / (1.0 + w.dot(z))));
        } else {  // Woodbury: (A0 + Z' V^T)^-1 r = x - Z (I + V^T Z)^-1 V^T x
            Small S = Small::Identity(k, k);
            S.noalias() += uv_.V.leftCols(k).transpose() * Z_.leftCols(k);
            SmallVector y = uv_.V.leftCols(k).transpose() * x_;
            y = S.partialPivLu().solve(y);
            dq = -x_;
            dq.noalias() += Z_.leftCols(k) * y;
        }
    }

    // X = -(A0 + (1 + alpha) U V^T)^-1 R for a block of right-hand sides (the variational equations,
    // solver/step_sensitivity.hpp), with the tangent of the last fill_tangent(). Nothing allocated
    // for fixed-size blocks, nor for dynamic ones once the scratch has its size.
    template <class Block>
    void solve_columns(int level, double one_alpha, const Block& R, Block& X) {
        update_woodbury_columns(level, one_alpha);
        const int k = uv_.rank;
        if (solved_by_lu(level, one_alpha, R, X)) return;
        X.noalias() = A0_inv_[level] * R;
        if (k > 0) {  // Sherman-Morrison or Woodbury, as solve(), on a k x 2n scratch y
            auto correct = [&](auto&& y) {
                y.noalias() = uv_.V.leftCols(k).transpose() * X;
                if (k == 1) {
                    y /= 1.0 + uv_.V.col(0).dot(Z_.col(0));
                } else {
                    Small S = Small::Identity(k, k);
                    S.noalias() += uv_.V.leftCols(k).transpose() * Z_.leftCols(k);
                    const Eigen::PartialPivLU<Small> lu(S);
                    for (int c = 0; c < y.cols(); ++c) {
                        const SmallVector column = y.col(c);
                        y.col(c) = lu.solve(column);
                    }
                }
                X.noalias() -= Z_.leftCols(k) * y;
            };
            if constexpr (Block::ColsAtCompileTime != Eigen::Dynamic) {
                correct(Eigen::Matrix<double, Eigen::Dynamic, Block::ColsAtCompileTime, 0, max_woodbury_rank,
                                      Block::ColsAtCompileTime>(k, R.cols()));
            } else {
                block_.resize(uv_.capacity(), R.cols());
                correct(block_.topRows(k));
            }
        }
        X = -X;
    }

    // M a = rhs.
    Vector solve_mass(const Vector& rhs) const { return system_.mass().partialPivLu().solve(rhs); }

    // beta < gamma / 2 is only conditionally stable (step_limit: the modes of the tangent at the start,
    // their damping included for a processed velocity).
    template <class StateType>
    void check_stability_limit(const StateType& s0) {
        check_step_limit(system_, s0, p_, s_.time_step);
    }

    // Highest undamped natural angular frequency (rad/s) at state s0, contacts linearized.
    template <class StateType>
    double highest_angular_frequency(const StateType& s0) const {
        return camfollower::highest_angular_frequency(system_, s0);
    }

private:
    // x = -(A0 + (1 + alpha) U V^T)^-1 r by a dense LU of the full matrix when the rank is beyond
    // Woodbury's (or 'dense_lu' is asked); false when Woodbury applies.
    template <class Rhs, class Out>
    bool solved_by_lu(int level, double one_alpha, const Rhs& r, Out& x) {
        const int k = uv_.rank;
        if (!(s_.linear_solver == LinearSolver::dense_lu || k > max_woodbury_rank || 2 * k > n_)) return false;
        full_ = A0_[level];
        if (k > 0) full_.noalias() += one_alpha * uv_.U.leftCols(k) * uv_.V.leftCols(k).transpose();
        lu_.compute(full_);
        x.noalias() = lu_.solve(r);
        x = -x;
        return true;
    }

    // Z = A0^-1 (1 + alpha) U for the active columns; a column is recomputed only when U changed
    // (contact directions depend on time only, so usually once per step).
    void update_woodbury_columns(int level, double one_alpha) {
        for (int k = 0; k < uv_.rank; ++k) {
            if (k < cached_rank_ && cached_level_ == level && U_cached_.col(k) == uv_.U.col(k)) continue;
            U_cached_.col(k) = uv_.U.col(k);
            Z_.col(k).noalias() = A0_inv_[level] * uv_.U.col(k);
            Z_.col(k) *= one_alpha;
        }
        cached_rank_ = uv_.rank;
        cached_level_ = level;
    }

    using Columns = typename LowRank<Vector>::Columns;
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_woodbury_rank, max_woodbury_rank>;
    using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_woodbury_rank, 1>;

    const System& system_;
    SolverSettings s_;
    NewmarkParameters p_;  // gamma, beta, alpha of the method
    int n_;
    std::array<Matrix, SolverSettings::max_levels> A0_, Aa_, A0_inv_;
    std::array<double, SolverSettings::max_levels> inverse_bound_{};
    // Scratch, sized once: nothing is allocated inside the time loop.
    LowRank<Vector> uv_;
    Columns Z_, U_cached_;
    int cached_rank_ = 0, cached_level_ = -1;
    Vector x_;
    Eigen::MatrixXd block_;  // V^T X of solve_columns()
    Matrix full_;
    Eigen::PartialPivLU<Matrix> lu_;
};

}  // namespace camfollower
