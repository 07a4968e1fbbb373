// SPDX-License-Identifier: BSD-3-Clause
// The Newton matrix's algebra for large models (a flexible camshaft with many cams), on SuiteSparse:
// the linear backend of Newmark (solver/newmark.hpp) for systems with sparse matrices
// (core/system.hpp: sparse_mass(), tangent_pattern(), the SparseLowRank tangent).
//
// The Newton matrix A0 + (1 + alpha) U V^T has the fixed pattern of M, C, K and the DOFs each
// contact couples (tangent_pattern()); its symbolic analysis is done once. With no contact active A0
// is factored once per step size and reused. Otherwise the matrix is refactored numerically at each
// Newton iteration: CHOLMOD (supernodal Cholesky) when it is symmetric positive definite (no contact
// damping), KLU (sparse LU for circuit-like matrices) otherwise. A low-rank (Woodbury) correction of
// the A0 factor would cost one sparse solve per active contact, O(N^2) for N cams on one shaft; the
// shaft's tree-like pattern makes the refactorization O(N).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/KLUSupport>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>

#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/newmark.hpp"

namespace camfollower {

template <class System>
class SparseNewtonSolve {
public:
    using Vector = typename System::Vector;
    using Sparse = Eigen::SparseMatrix<double>;
    using Tangent = SparseLowRank;
    static_assert(Vector::RowsAtCompileTime == Eigen::Dynamic, "the sparse backend needs a dynamic-size system");

    SparseNewtonSolve(const System& system, const SolverSettings& s)
        : system_(system), s_(s), p_(newmark_parameters(s)), n_(system.size()) {
        const Sparse& M = system.sparse_mass();
        const Sparse& C = system.sparse_damping();
        const Sparse& K = system.sparse_stiffness();
        for (const Sparse* A : {&M, &C, &K})
            if (A->rows() != n_ || A->cols() != n_)
                detail::fail("system: sparse mass, damping and stiffness must be ", n_, " x ", n_, " (size())");
        for (int k = 0; k < n_; ++k)
            if (!(M.coeff(k, k) > 0.0))
                detail::fail("system: mass matrix diagonal must be > 0, got M(", k, ", ", k, ") = ", M.coeff(k, k));
        if (p_.processed)
            detail::fail("the sparse backend keeps the trapezoidal velocity: Newmark with gamma = 1/2 and beta = ",
                         p_.beta, " < 1/4 needs process_velocity = false on it (simulate() sets it)");

        // The fixed pattern: M, C, K and every DOF pair a tangent column can couple.
        std::vector<Eigen::Triplet<double>> t;
        for (const Sparse* A : {&M, &C, &K})
            for (int col = 0; col < A->outerSize(); ++col)
                for (Sparse::InnerIterator it(*A, col); it; ++it) t.emplace_back(int(it.row()), col, 0.0);
        std::size_t entries = 0;
        const std::vector<std::vector<int>> groups = system.tangent_pattern();
        for (const std::vector<int>& g : groups) {
            entries += g.size();
            for (int a : g)
                for (int b : g) t.emplace_back(a, b, 0.0);
        }
        J_.resize(n_, n_);
        J_.setFromTriplets(t.begin(), t.end());
        J_.makeCompressed();
        uv_.reserve(2 * groups.size() + 1, 4 * entries + 8);

        const int levels = s_.max_halvings + 1;
        for (int level = 0; level < levels; ++level) {
            const double dt = s_.time_step / double(1 << level);
            const double one_alpha = 1.0 + p_.alpha;
            Sparse A0 =
                (1.0 / (p_.beta * dt * dt)) * M + (one_alpha * p_.damping_gamma / (p_.beta * dt)) * C + one_alpha * K;
            A0.makeCompressed();
            Aa_[level] = (p_.beta * dt * dt) * A0;
            std::vector<double>& values = a0_values_[level];
            values.assign(std::size_t(J_.nonZeros()), 0.0);
            for (int col = 0; col < A0.outerSize(); ++col)
                for (Sparse::InnerIterator it(A0, col); it; ++it) values[position(int(it.row()), col)] += it.value();
            symmetric_[level] = max_abs(A0 - Sparse(A0.transpose())) <= 1e-14 * max_abs(A0);
            inverse_bound_[level] = symmetric_[level] ? inverse_of_smallest_eigenvalue(A0) : 0.0;
        }
        klu_.analyzePattern(J_);
        cholmod_.analyzePattern(J_);
        mass_.compute(M);
        if (mass_.info() != Eigen::Success) detail::fail("system: the mass matrix is not positive definite");
    }

    const Sparse& mass() const { return system_.sparse_mass(); }
    const Sparse& damping() const { return system_.sparse_damping(); }
    const Sparse& stiffness() const { return system_.sparse_stiffness(); }
    const Sparse& residual_matrix(int level) const { return Aa_[level]; }
    double inverse_bound(int level) const { return inverse_bound_[level]; }
    const Tangent& tangent() const { return uv_; }
    int rank() const { return uv_.rank(); }
    // Which factorization the last solve used (for reports and tests).
    const char* last_factorization() const { return last_; }

    void fill_tangent(const workspace_t<System>& ws, const Vector& q, const Vector& v, double cq, double cv) {
        uv_.clear();
        if constexpr (is_nonlinear_system_v<System>) system_.tangent(ws, q, v, cq, cv, uv_);
        else (void)ws, (void)q, (void)v, (void)cq, (void)cv;
    }
    double tangent_norm() const {
        double norm = 0.0;
        for (int k = 0; k < uv_.rank(); ++k) {
            double u_max = 0.0, v_sum = 0.0;
            for (int e = uv_.begin(k); e < uv_.end(k); ++e)
                u_max = std::max(u_max, std::abs(uv_.u[std::size_t(e)])), v_sum += std::abs(uv_.v[std::size_t(e)]);
            norm += u_max * v_sum;
        }
        return norm;
    }
    // Every column pair symmetric positive semi-definite (v = s u, s >= 0) on distinct DOFs.
    bool tangent_is_spd() const {
        for (int k = 0; k < uv_.rank(); ++k) {
            double uu = 0.0, uv = 0.0, vv = 0.0;
            for (int e = uv_.begin(k); e < uv_.end(k); ++e) {
                const double u = uv_.u[std::size_t(e)], v = uv_.v[std::size_t(e)];
                uu += u * u, uv += u * v, vv += v * v;
                for (int f = uv_.begin(k); f < e; ++f)
                    if (uv_.dof[std::size_t(f)] == uv_.dof[std::size_t(e)]) return false;
            }
            if (uu == 0.0) continue;
            const double s = uv / uu;
            double residual = 0.0;
            for (int e = uv_.begin(k); e < uv_.end(k); ++e) {
                const double d = uv_.v[std::size_t(e)] - s * uv_.u[std::size_t(e)];
                residual += d * d;
            }
            if (!(s >= 0.0) || residual > 1e-24 * vv) return false;
        }
        return true;
    }
    void new_step() {}

    // dq = -(A0 + (1 + alpha) U V^T)^-1 r.
    void solve(int level, double one_alpha, const Vector& r, Vector& dq) {
        if (uv_.rank() == 0) {
            const Factor& f = a0_factor(level);
            last_ = f.cholmod ? "cholmod" : "klu";
            dq = f.cholmod ? Vector(f.cholmod->solve(r)) : Vector(f.klu->solve(r));
            dq = -dq;
            return;
        }
        std::copy(a0_values_[level].begin(), a0_values_[level].end(), J_.valuePtr());
        for (int k = 0; k < uv_.rank(); ++k)
            for (int a = uv_.begin(k); a < uv_.end(k); ++a) {
                const double u = one_alpha * uv_.u[std::size_t(a)];
                if (u == 0.0) continue;
                for (int b = uv_.begin(k); b < uv_.end(k); ++b)
                    J_.valuePtr()[position(uv_.dof[std::size_t(a)], uv_.dof[std::size_t(b)])] +=
                        u * uv_.v[std::size_t(b)];
            }
        const bool spd = symmetric_[level] && tangent_is_spd() && s_.sparse_factorization != SparseFactorization::klu;
        if (spd) {
            cholmod_.factorize(J_);
            if (cholmod_.info() == Eigen::Success) {
                last_ = "cholmod";
                dq = cholmod_.solve(r);
                dq = -dq;
                return;
            }
        }
        klu_.factorize(J_);
        if (klu_.info() != Eigen::Success)
            throw ConvergenceError("the sparse Newton matrix is singular (KLU factorization failed)");
        last_ = "klu";
        dq = klu_.solve(r);
        dq = -dq;
    }

    Vector solve_mass(const Vector& rhs) const { return mass_.solve(rhs); }

    // beta < gamma / 2 (Fox-Goodwin with its trapezoidal velocity) is only conditionally stable: the
    // highest mode of the tangent at the start, from a dense eigen solve of the system's dense matrices
    // (about a second at 1000 DOFs).
    template <class StateType>
    void check_stability_limit(const StateType& s0) {
        check_step_limit(system_, s0, p_, s_.time_step);
    }

private:
    struct Factor {
        std::unique_ptr<Eigen::CholmodDecomposition<Sparse, Eigen::Lower>> cholmod;
        std::unique_ptr<Eigen::KLU<Sparse>> klu;
    };

    // Index into J_'s values of entry (row, col), which the pattern holds.
    int position(int row, int col) const {
        const int* begin = J_.innerIndexPtr() + J_.outerIndexPtr()[col];
        const int* end = J_.innerIndexPtr() + J_.outerIndexPtr()[col + 1];
        const int* it = std::lower_bound(begin, end, row);
        return int(it - J_.innerIndexPtr());
    }

    static double max_abs(const Sparse& A) {
        double m = 0.0;
        for (int k = 0; k < A.nonZeros(); ++k) m = std::max(m, std::abs(A.valuePtr()[k]));
        return m;
    }

    // 1 / lambda_min(A0) by shift-invert Lanczos (Spectra) about 0; 0 (no bound) if it fails.
    double inverse_of_smallest_eigenvalue(const Sparse& A0) const {
        if (n_ < 3) return 0.0;
        Spectra::SparseSymShiftSolve<double> op(A0);
        Spectra::SymEigsShiftSolver<Spectra::SparseSymShiftSolve<double>> eigs(op, 1, std::min<Eigen::Index>(n_, 20),
                                                                               0.0);
        eigs.init();
        eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
        if (eigs.info() != Spectra::CompInfo::Successful) return 0.0;
        const double lambda = eigs.eigenvalues()[0];
        // A 1 % margin for the eigenvalue's tolerance keeps the bound an upper bound.
        return lambda > 0.0 ? 1.01 / lambda : 0.0;
    }

    const Factor& a0_factor(int level) {
        Factor& f = a0_factors_[level];
        if (f.cholmod || f.klu) return f;
        std::copy(a0_values_[level].begin(), a0_values_[level].end(), J_.valuePtr());
        if (symmetric_[level] && s_.sparse_factorization != SparseFactorization::klu) {
            f.cholmod = std::make_unique<Eigen::CholmodDecomposition<Sparse, Eigen::Lower>>();
            f.cholmod->compute(J_);
            if (f.cholmod->info() == Eigen::Success) return f;
            f.cholmod.reset();
        }
        f.klu = std::make_unique<Eigen::KLU<Sparse>>();
        f.klu->compute(J_);
        if (f.klu->info() != Eigen::Success) detail::fail("the sparse Newton matrix A0 is singular");
        return f;
    }

    const System& system_;
    SolverSettings s_;
    NewmarkParameters p_;  // gamma, beta, alpha of the method
    int n_;
    Sparse J_;  // the Newton matrix on its fixed pattern, values rewritten at each solve
    std::array<Sparse, SolverSettings::max_levels> Aa_;
    std::array<std::vector<double>, SolverSettings::max_levels> a0_values_;
    std::array<bool, SolverSettings::max_levels> symmetric_{};
    std::array<double, SolverSettings::max_levels> inverse_bound_{};
    std::array<Factor, SolverSettings::max_levels> a0_factors_;
    Eigen::KLU<Sparse> klu_;
    Eigen::CholmodDecomposition<Sparse, Eigen::Lower> cholmod_;
    Eigen::CholmodDecomposition<Sparse, Eigen::Lower> mass_;
    SparseLowRank uv_;
    const char* last_ = "none";
};

template <class System>
using SparseNewmark = Newmark<System, SparseNewtonSolve<System>>;

}  // namespace camfollower
