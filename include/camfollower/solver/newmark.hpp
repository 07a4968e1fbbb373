// SPDX-License-Identifier: BSD-3-Clause
// Implicit Newmark-beta / HHT-alpha stepper with Newton-Raphson, for any system of the contract in
// core/system.hpp (M q'' + C q' + K q + f(t, q, q') = p(t)).
//
// Residual (HHT-alpha, alpha in [-1/3, 0]; alpha = 0 is plain Newmark), unknown the new acceleration:
//   r(a) = Aa a + b + (1 + alpha) f(q(a), v(a)),   Aa = M + (1 + alpha)(gamma dt C + beta dt^2 K),
//   q(a) = q_pred + beta dt^2 a, v(a) = v_pred + gamma dt a.
// In displacement units the Newton matrix is A0 + (1 + alpha) U V^T with
// A0 = M / (beta dt^2) + (1 + alpha)(gamma / (beta dt) C + K), constant for a given dt (inverted once
// per step size), and U V^T the system's low-rank tangent (rank = active contacts). How that matrix
// is solved is the linear backend's job: DenseNewtonSolve (here; small models, fixed-size Eigen)
// solves rank one by Sherman-Morrison, small ranks by Woodbury, larger ranks by a dense LU of the
// full matrix; SparseNewtonSolve (solver/sparse_newton.hpp) factors the sparse matrix on SuiteSparse.
// Convergence: residual below tolerance (or its rounding floor) and Newton increment below tolerance.
// When the tangent is symmetric positive semi-definite (V = U diag(s), s >= 0) the next increment is
// bounded by |r|_2 / lambda_min(A0) and the confirming solve is skipped: a step whose contact state
// does not change converges in one solve. A step that fails is retried as two halves (bounded).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "camfollower/core/system.hpp"
#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/error_scales.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/interrupt.hpp"

namespace camfollower {

enum class LinearSolver { sherman_morrison, dense_lu };
// Dense (small models, fixed-size Eigen) or sparse (SuiteSparse: solver/sparse_newton.hpp) Newton
// algebra; automatic picks sparse from sparse_backend_threshold DOFs on systems that support it.
enum class Backend { automatic, dense, sparse };
// The sparse backend's factorization: automatic is CHOLMOD when the Newton matrix is symmetric
// positive definite, KLU otherwise; klu always uses KLU.
enum class SparseFactorization { automatic, klu };
inline constexpr int sparse_backend_threshold = 100;  // DOFs; measured crossover: bench/camshaft.cpp
// The integration method: implicit Newmark/HHT at the fixed time_step (this file), explicit
// Dormand-Prince 5(4) or 8(5,3) (dop853) with adaptive steps under `tolerance` (solver/
// dormand_prince.hpp), or implicit Radau IIA of order 5 with adaptive steps (solver/radau.hpp),
// time_step then being the output interval only.
// newmark_adaptive: Newmark (gamma, beta: average acceleration or Fox-Goodwin) under `tolerance`, in
// steps of time_step / 2^level, the level chosen by the step's error estimate.
// automatic: Fox-Goodwin or average-acceleration Newmark at time_step, chosen at the start of a run
// from the model's highest mode; automatic_adaptive: dop853 or radau under `tolerance`, chosen from
// the model's fastest modes (solver/choose_method.hpp).
enum class Method { newmark, dormand_prince, automatic, dop853, radau, automatic_adaptive, newmark_adaptive };
// The adaptive Runge-Kutta methods (explicit and Radau IIA): tolerance, max_step and adaptive apply to them.
inline constexpr bool is_runge_kutta(Method m) {
    return m == Method::dormand_prince || m == Method::dop853 || m == Method::radau;
}
// The methods that read `tolerance` and `max_step`: the adaptive ones and the choice among them.
inline constexpr bool uses_tolerance(Method m) {
    return is_runge_kutta(m) || m == Method::automatic_adaptive || m == Method::newmark_adaptive;
}
inline constexpr bool is_newmark(Method m) { return m == Method::newmark || m == Method::newmark_adaptive; }
inline constexpr bool is_automatic(Method m) { return m == Method::automatic || m == Method::automatic_adaptive; }

// The solver's settings (named for its first method; `method` picks another).
struct NewmarkSettings {
    Method method = Method::newmark;
    double time_step = 3e-6;            // s (methods under a tolerance: the output interval)
    double tolerance = 1e-6;            // methods under a tolerance (uses_tolerance): relative error per step, displacements and forces
    double max_step = 0.0;              // methods under a tolerance: largest step, s (0: unbounded; newmark_adaptive: at most time_step)
    bool adaptive = true;               // dormand_prince, dop853, radau: false = fixed steps of max_step (or time_step), no error control
    double gamma = 0.5;
    double beta = 0.25;
    double hht_alpha = 0.0;             // in [-1/3, 0]
    double residual_tolerance = 1e-10;  // relative to the system's force scale
    double increment_tolerance = 1e-10; // relative to max |q| (+ 1 nm floor)
    int max_iterations = 25;
    int max_halvings = 6;               // newmark_adaptive: the smallest step is time_step / 2^max_halvings
    LinearSolver linear_solver = LinearSolver::sherman_morrison;  // dense backend: low-rank updates, or dense LU always
    Backend backend = Backend::automatic;
    SparseFactorization sparse_factorization = SparseFactorization::automatic;

    // HHT-alpha with its second-order, unconditionally stable gamma and beta.
    static NewmarkSettings hht(double alpha, double time_step = 3e-6) {
        NewmarkSettings s;
        s.hht_alpha = alpha;
        s.gamma = 0.5 - alpha;
        s.beta = 0.25 * (1.0 - alpha) * (1.0 - alpha);
        s.time_step = time_step;
        return s;
    }

    void validate() const {
        // Below a picosecond M / (beta dt^2) leaves the range of doubles for any mechanical mass.
        if (!(std::isfinite(time_step) && time_step >= 1e-12))
            detail::fail("time_step must be finite and > 0 (at least 1e-12 s), got ", time_step);
        detail::require_in_range(hht_alpha, -1.0 / 3.0, 0.0, "hht_alpha");
        detail::require_in_range(gamma, 0.5, 1.0, "gamma (below 1/2 the scheme adds negative damping)");
        if (!(std::isfinite(beta) && beta > 0.0 && beta <= 0.5)) detail::fail("beta must be in (0, 0.5], got ", beta);
        // HHT-alpha is stable only with its own gamma and beta (NewmarkSettings::hht).
        if (hht_alpha != 0.0 && (std::abs(gamma - (0.5 - hht_alpha)) > 1e-12 ||
                                 std::abs(beta - 0.25 * (1.0 - hht_alpha) * (1.0 - hht_alpha)) > 1e-12))
            detail::fail("hht_alpha = ", hht_alpha, " needs gamma = 1/2 - alpha = ", 0.5 - hht_alpha,
                         " and beta = (1 - alpha)^2 / 4 = ", 0.25 * (1.0 - hht_alpha) * (1.0 - hht_alpha), ", got gamma = ",
                         gamma, ", beta = ", beta, " (use NewmarkSettings::hht)");
        detail::require_positive(residual_tolerance, "residual_tolerance");
        detail::require_positive(increment_tolerance, "increment_tolerance");
        if (max_iterations < 1 || max_iterations > 1000)
            detail::fail("max_iterations must be in [1, 1000], got ", max_iterations);
        if (max_halvings < 0 || max_halvings > max_levels - 1)
            detail::fail("max_halvings must be in [0, ", max_levels - 1, "], got ", max_halvings);
        // Below 1e-13 the error estimate is rounding; above 0.1 it no longer measures anything.
        detail::require_in_range(tolerance, 1e-13, 0.1, "tolerance");
        // As for time_step: below a picosecond no mechanical model needs a step.
        if (!(std::isfinite(max_step) && (max_step == 0.0 || max_step >= 1e-12)))
            detail::fail("max_step must be 0 (unbounded) or finite and >= 1e-12 s, got ", max_step);
        if (method == Method::automatic_adaptive && !adaptive)
            detail::fail("method 'auto' with a tolerance chooses an adaptive method: adaptive = false needs a named "
                         "method ('dormand_prince', 'dop853' or 'radau')");
        if (method == Method::newmark_adaptive) {
            if (!adaptive)
                detail::fail("Newmark under a tolerance adapts its steps: adaptive = false with 'newmark' or 'fox_goodwin' "
                             "means no tolerance (fixed steps of time_step)");
            // The error estimate is Newmark's (Zienkiewicz & Xie); HHT-alpha's differs.
            if (hht_alpha != 0.0)
                detail::fail("Newmark under a tolerance needs hht_alpha = 0 (error control for HHT-alpha is not "
                             "implemented), got hht_alpha = ", hht_alpha);
        }
        if (is_automatic(method) && (gamma != 0.5 || beta != 0.25 || hht_alpha != 0.0))
            detail::fail("method 'auto' chooses gamma and beta itself: leave gamma = 1/2, beta = 1/4, hht_alpha = 0 "
                         "(got ", gamma, ", ", beta, ", ", hht_alpha, ")");
    }
    static constexpr int max_levels = 16;
};

// The linear-algebra choice by one name (config files, Python):
//   "auto"      dense low-rank below sparse_backend_threshold DOFs, sparse above (the default)
//   "low_rank"  dense backend, Sherman-Morrison / Woodbury ("sherman_morrison" is an alias)
//   "dense_lu"  dense backend, a full LU at every Newton iteration
//   "sparse"    sparse backend, CHOLMOD when the matrix is symmetric positive definite, else KLU
//   "klu"       sparse backend, KLU always
inline void set_linear_solver(NewmarkSettings& s, const std::string& name) {
    s.linear_solver = LinearSolver::sherman_morrison;
    s.sparse_factorization = SparseFactorization::automatic;
    if (name == "auto") s.backend = Backend::automatic;
    else if (name == "low_rank" || name == "sherman_morrison") s.backend = Backend::dense;
    else if (name == "dense_lu") s.backend = Backend::dense, s.linear_solver = LinearSolver::dense_lu;
    else if (name == "sparse") s.backend = Backend::sparse;
    else if (name == "klu") s.backend = Backend::sparse, s.sparse_factorization = SparseFactorization::klu;
    else detail::fail("linear_solver must be 'auto', 'low_rank', 'dense_lu', 'sparse' or 'klu', got '", name, "'");
}
inline const char* linear_solver_name(const NewmarkSettings& s) {
    if (s.backend == Backend::sparse) return s.sparse_factorization == SparseFactorization::klu ? "klu" : "sparse";
    if (s.linear_solver == LinearSolver::dense_lu) return "dense_lu";
    return s.backend == Backend::dense ? "low_rank" : "auto";
}

// The method by one name (config files, Python):
//   "newmark"         Newmark/HHT with the settings' gamma, beta and hht_alpha (default: average
//                     acceleration, second order, unconditionally stable)
//   "fox_goodwin"     Newmark with gamma = 1/2, beta = 1/12: fourth-order phase on undamped linear
//                     modes, stable below dt = sqrt(6) / omega_max (checked at the start)
//   "dormand_prince"  explicit Runge-Kutta 5(4), adaptive steps under `tolerance`, dense output
//   "dop853"          explicit Runge-Kutta 8(5,3), adaptive steps under `tolerance`, 7th-order dense
//                     output: half dormand_prince's steps, twice its evaluations per step
//   "radau"           implicit Radau IIA of order 5 (L-stable), adaptive steps under `tolerance`,
//                     dense output by its collocation polynomial: for models stiff at that accuracy
//   "auto"            fox_goodwin when time_step is within its stability limit, else newmark's
//                     average acceleration (choose_method); given a tolerance (set_tolerance),
//                     radau when the model's fastest modes are damped, else dop853
// "newmark" and "fox_goodwin" given a tolerance (set_tolerance) adapt their steps (newmark_adaptive).
inline void set_method(NewmarkSettings& s, const std::string& name) {
    if (name == "newmark") {
        s.method = Method::newmark;
    } else if (name == "fox_goodwin") {
        s.method = Method::newmark;
        s.hht_alpha = 0.0, s.gamma = 0.5, s.beta = 1.0 / 12.0;
    } else if (name == "dormand_prince") {
        s.method = Method::dormand_prince;
    } else if (name == "dop853") {
        s.method = Method::dop853;
    } else if (name == "radau") {
        s.method = Method::radau;
    } else if (name == "auto") {
        s.method = Method::automatic;
    } else {
        detail::fail("method must be 'newmark', 'fox_goodwin', 'dormand_prince', 'dop853', 'radau' or 'auto', got '", name, "'");
    }
}
inline const char* method_name(const NewmarkSettings& s) {
    if (s.method == Method::dormand_prince) return "dormand_prince";
    if (s.method == Method::dop853) return "dop853";
    if (s.method == Method::radau) return "radau";
    if (is_automatic(s.method)) return "auto";
    return s.gamma == 0.5 && s.beta == 1.0 / 12.0 && s.hht_alpha == 0.0 ? "fox_goodwin" : "newmark";
}
// Runs the method under `tolerance` (relative error per step), time_step becoming the output
// interval: "newmark" and "fox_goodwin" adapt their steps (newmark_adaptive), "auto" chooses between
// dop853 and radau (automatic_adaptive), the Runge-Kutta methods take it as given.
inline void set_tolerance(NewmarkSettings& s, double tolerance) {
    if (s.method == Method::newmark) s.method = Method::newmark_adaptive;
    if (s.method == Method::automatic) s.method = Method::automatic_adaptive;
    s.tolerance = tolerance;
}
// Method "auto" under `tolerance`: set_tolerance, refused for any other method.
inline void set_auto_tolerance(NewmarkSettings& s, double tolerance) {
    if (!is_automatic(s.method)) detail::fail("set_auto_tolerance: the method must be 'auto', got '", method_name(s), "'");
    set_tolerance(s, tolerance);
}

struct SolverStatistics {
    std::uint64_t steps = 0;              // accepted steps, substeps included
    std::uint64_t newton_iterations = 0;  // linear solves
    std::uint64_t halvings = 0;
    std::uint64_t evaluations = 0;        // adaptive methods: force evaluations
    std::uint64_t rejected_steps = 0;     // adaptive methods: steps retried smaller
    std::uint64_t stiff_steps = 0;        // explicit methods: steps bounded by stability, not accuracy
    int max_iterations_in_a_step = 0;
    double mean_iterations() const { return steps ? double(newton_iterations) / double(steps) : 0.0; }
    void add(const SolverStatistics& o) {
        steps += o.steps, newton_iterations += o.newton_iterations, halvings += o.halvings;
        evaluations += o.evaluations, rejected_steps += o.rejected_steps, stiff_steps += o.stiff_steps;
        max_iterations_in_a_step = std::max(max_iterations_in_a_step, o.max_iterations_in_a_step);
    }
};

// The integrator's state: time, displacement, velocity, acceleration, the nonlinear force at them
// (f(t, q, v) - p(t), needed by HHT) and the system's workspace (time terms prepared at t, path memory).
template <class System>
struct State {
    using Vector = typename System::Vector;
    double t = 0.0;
    Vector q, v, a, f;
    workspace_t<System> workspace;
};

// A state at (t, q, v) with a fresh workspace prepared at t and the nonlinear force there; the
// acceleration is the stepper's to set. Refuses a non-finite time or state and a wrong size.
template <class System>
State<System> state_at(const System& system, double t, const typename System::Vector& q,
                       const typename System::Vector& v) {
    detail::require_finite(t, "start time");
    const int n = system.size();
    if (q.size() != n || v.size() != n) detail::fail("initial q and v must have size ", n, ", got ", q.size(), ", ", v.size());
    if (!q.allFinite() || !v.allFinite()) detail::fail("initial q and v must be finite");
    State<System> s;
    s.t = t, s.q = q, s.v = v;
    s.workspace = make_workspace(system);
    prepare(system, t, s.workspace);
    s.f.resize(n);
    nonlinear_force(system, s.workspace, s.q, s.v, s.f);
    s.a.resize(n);
    return s;
}

// Lowest (above rigid-body modes) and highest undamped natural angular frequencies (rad/s) of
// `system` with its contacts' tangent at state s (NaN when the eigen solve fails): the time scales a
// run has to resolve. Allocates; call once per run.
struct FrequencyRange {
    double lowest = std::numeric_limits<double>::quiet_NaN(), highest = std::numeric_limits<double>::quiet_NaN();
};
template <class System>
FrequencyRange natural_frequency_range(const System& system, const State<System>& s) {
    using Matrix = typename System::Matrix;
    LowRank<typename System::Vector> uv(system.size(), std::max(1, max_rank(system)));
    uv.clear();
    tangent(system, s.workspace, s.q, s.v, 1.0, 0.0, uv);
    const Matrix t = uv.U.leftCols(uv.rank) * uv.V.leftCols(uv.rank).transpose();
    const Matrix Kt = system.stiffness() + 0.5 * (t + t.transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Kt, system.mass(), Eigen::EigenvaluesOnly);
    FrequencyRange r;
    if (eig.info() != Eigen::Success) return r;
    const double top = std::max(eig.eigenvalues().maxCoeff(), 0.0);
    r.highest = std::sqrt(top);
    for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k)
        if (eig.eigenvalues()[k] > 1e-12 * top) {
            r.lowest = std::sqrt(eig.eigenvalues()[k]);
            break;
        }
    return r;
}
template <class System>
double highest_angular_frequency(const System& system, const State<System>& s) {
    return natural_frequency_range(system, s).highest;
}

// The rate (rad/s) setting the error norms' velocity reference (ErrorScales): 2 pi / period for a
// camshaft-driven system, else its lowest natural frequency at s, else 1 / time_step.
template <class System>
double reference_rate(const System& system, const State<System>& s, double time_step) {
    if constexpr (detail::has_period<System>::value) {
        return 2.0 * pi / system.period();
    } else {
        const double lowest = natural_frequency_range(system, s).lowest;
        return std::isfinite(lowest) ? lowest : 1.0 / time_step;
    }
}

// Largest stable step of Newmark with beta < gamma / 2 (undamped: omega_max dt < 1 / sqrt(gamma / 2 -
// beta)), with a 10 % margin for the highest mode's variation along the motion (contact directions
// turn with the cam); +inf when the scheme is unconditionally stable.
inline double newmark_step_limit(double gamma, double beta, double omega_max) {
    if (beta >= 0.5 * gamma) return std::numeric_limits<double>::infinity();
    return 0.9 / (omega_max * std::sqrt(0.5 * gamma - beta));
}

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

    DenseNewtonSolve(const System& system, const NewmarkSettings& s)
        : system_(system), s_(s), n_(system.size()), uv_(n_, std::max(1, max_rank(system))) {
        const Matrix& M = system.mass();
        if (M.rows() != n_ || M.cols() != n_ || system.damping().rows() != n_ || system.damping().cols() != n_ ||
            system.stiffness().rows() != n_ || system.stiffness().cols() != n_)
            detail::fail("system: mass, damping and stiffness must be ", n_, " x ", n_, " (size())");
        for (int k = 0; k < n_; ++k)
            if (!(M(k, k) > 0.0)) detail::fail("system: mass matrix diagonal must be > 0, got M(", k, ", ", k, ") = ", M(k, k));
        if (n_ > max_dofs)
            detail::fail("linear_solver '", linear_solver_name(s_), "' (dense) is limited to ", max_dofs, " DOFs (it factorizes n x n "
                         "matrices for every step size); this system has ", n_, ": use 'sparse' or 'auto'");
        // The cheap refusal first: sqrt(K_kk / M_kk), a Rayleigh quotient, bounds omega_max from below,
        // so a fixed step beyond the scheme's limit for it is beyond the true limit too; O(n), before the
        // O(n^3) factorizations below (start() checks the exact limit).
        if (s_.method != Method::newmark_adaptive && s_.beta < 0.5 * s_.gamma) {
            double omega_low = 0.0;
            for (int k = 0; k < n_; ++k)
                omega_low = std::max(omega_low, std::sqrt(std::max(system.stiffness()(k, k), 0.0) / M(k, k)));
            const double limit = newmark_step_limit(s_.gamma, s_.beta, omega_low);
            if (s_.time_step > limit)
                detail::fail("time_step = ", s_.time_step, " s exceeds the stability limit of Newmark with beta = ", s_.beta,
                             " < gamma / 2: at most ", limit, " s (a mode at ", omega_low / (2.0 * pi), " Hz or faster); reduce "
                             "time_step, use beta = 1/4 or method 'auto'");
        }
        const int levels = s_.max_halvings + 1;
        for (int level = 0; level < levels; ++level) {
            const double dt = s_.time_step / double(1 << level);
            A0_[level] = system.mass() / (s_.beta * dt * dt) +
                         (1.0 + s_.hht_alpha) * (s_.gamma / (s_.beta * dt) * system.damping() + system.stiffness());
            Aa_[level] = (s_.beta * dt * dt) * A0_[level];
            // An explicit inverse applied as one matrix-vector product beats two triangular solves for
            // the small, well-conditioned matrices of lumped models.
            A0_inv_[level] = A0_[level].partialPivLu().inverse();
            // 1 / lambda_min(A0) when A0 is symmetric positive definite (0 disables the bound).
            inverse_bound_[level] = 0.0;
            if (n_ <= max_eigen_dofs && (A0_[level] - A0_[level].transpose()).cwiseAbs().maxCoeff() <= 1e-14 * A0_[level].cwiseAbs().maxCoeff()) {
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
        if (s_.linear_solver == LinearSolver::dense_lu || k > max_woodbury_rank || 2 * k > n_) {
            full_ = A0_[level];
            if (k > 0) full_.noalias() += one_alpha * uv_.U.leftCols(k) * uv_.V.leftCols(k).transpose();
            lu_.compute(full_);
            dq.noalias() = lu_.solve(r);
            dq = -dq;
            return;
        }
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

    // M a = rhs.
    Vector solve_mass(const Vector& rhs) const { return system_.mass().partialPivLu().solve(rhs); }

    // beta < gamma / 2 is only conditionally stable (newmark_step_limit); omega_max from the tangent
    // stiffness at the start.
    template <class StateType>
    void check_stability_limit(const StateType& s0) {
        if (s_.beta >= 0.5 * s_.gamma) return;
        const double omega_max = highest_angular_frequency(s0);
        if (!std::isfinite(omega_max)) return;
        const double limit = newmark_step_limit(s_.gamma, s_.beta, omega_max);
        if (s_.time_step > limit)
            detail::fail("time_step = ", s_.time_step, " s exceeds the stability limit ", limit, " s of Newmark with beta = ",
                         s_.beta, " < gamma / 2 (highest mode ", omega_max / (2.0 * pi),
                         " Hz); reduce time_step, use beta = 1/4 or method 'auto'");
    }

    // Highest undamped natural angular frequency (rad/s) at state s0, contacts linearized.
    template <class StateType>
    double highest_angular_frequency(const StateType& s0) const { return camfollower::highest_angular_frequency(system_, s0); }

private:
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
    NewmarkSettings s_;
    int n_;
    std::array<Matrix, NewmarkSettings::max_levels> A0_, Aa_, A0_inv_;
    std::array<double, NewmarkSettings::max_levels> inverse_bound_{};
    // Scratch, sized once: nothing is allocated inside the time loop.
    LowRank<Vector> uv_;
    Columns Z_, U_cached_;
    int cached_rank_ = 0, cached_level_ = -1;
    Vector x_;
    Matrix full_;
    Eigen::PartialPivLU<Matrix> lu_;
};

// to = from; a fixed-size vector as an inline copy (in the stepper's large functions GCC calls Eigen's
// assignment loop out of line for each 7-vector copy: 67 of ~2950 instructions per preset step).
namespace detail {
template <class V>
CAMFOLLOWER_FORCE_INLINE void copy_vector(const V& from, V& to) {
    if constexpr (V::SizeAtCompileTime != Eigen::Dynamic)
        std::memcpy(to.data(), from.data(), sizeof(typename V::Scalar) * std::size_t(V::SizeAtCompileTime));
    else
        to = from;
}
}  // namespace detail

// The stepper, on a linear backend (DenseNewtonSolve by default; SparseNewtonSolve in
// solver/sparse_newton.hpp for large models).
template <class System, class Linear = DenseNewtonSolve<System>>
class Newmark {
    static_assert(check_system<System>());

public:
    using Vector = typename System::Vector;
    using StateType = State<System>;

    Newmark(const System& system, const NewmarkSettings& settings)
        : system_(system), s_(validated(settings)), n_(system.size()), linear_(system, s_),
          control_error_(s_.method == Method::newmark_adaptive) {
        norm_M_ = row_sum_norm(linear_.mass());
        norm_C_ = row_sum_norm(linear_.damping());
        norm_K_ = row_sum_norm(linear_.stiffness());
        for (Vector* v : {&q_pred_, &v_pred_, &b_, &a_, &q_, &v_, &r_, &dq_}) v->resize(n_);
        if (control_error_) {
            for (Vector* v : {&eq_, &ev_, &da_, &da_old_, &ef_}) v->resize(n_);
            uvq_ = uvv_ = LowRank<Vector>(n_, std::max(1, max_rank(system)));
        }
    }

    // The stepper keeps a reference to the system: a temporary would dangle.
    Newmark(System&&, const NewmarkSettings&) = delete;

    const NewmarkSettings& settings() const { return s_; }
    const System& system() const { return system_; }
    double time_step() const { return s_.time_step; }  // under a tolerance: the output interval
    double force_scale() const { return force_scale_; }
    const Linear& linear_solver() const { return linear_; }

    // A state at (t, q, v) with the consistent acceleration M a = -(C v + K q + f). Sets the
    // residual scale from it and refuses a conditionally stable scheme beyond its step limit (under a
    // tolerance: bounds the steps by it).
    StateType start(double t, const Vector& q, const Vector& v) {
        StateType s = state_at(system_, t, q, v);
        Vector rhs = linear_.damping() * s.v;
        rhs += linear_.stiffness() * s.q;
        rhs += s.f;
        s.a = linear_.solve_mass(-rhs);
        const Vector Kq = linear_.stiffness() * s.q;
        force_scale_ = std::max({1.0, Kq.cwiseAbs().maxCoeff(), s.f.cwiseAbs().maxCoeff()});
        if (control_error_) start_error_control(s);
        else linear_.check_stability_limit(s);
        accepted(system_, s.workspace, s.q, s.v);  // path memory starts from the initial state
        events_.start(s.workspace, s.q, s.v);
        return s;
    }

    // Highest undamped natural angular frequency (rad/s) at a state, contacts linearized (NaN when
    // the eigen solve fails): what the step has to resolve.
    double highest_angular_frequency(const StateType& s) { return linear_.highest_angular_frequency(s); }
    // Contact losses and re-contacts since start(), located within their steps (solver/events.hpp).
    const std::vector<Event>& events() const { return events_.events(); }
    std::vector<Event> take_events() { return events_.take_events(); }

    // One step of the nominal size time_step, halving (recursively, bounded) when Newton fails; under
    // a tolerance, one output interval time_step in steps of time_step / 2^level (step_under_tolerance).
    void step(StateType& state, SolverStatistics& stats) {
        if (control_error_) step_under_tolerance(state, stats);
        else step_at_level(state, stats, 0);
    }

    // Polled every few steps within an output interval under a tolerance (solver/interrupt.hpp).
    void set_interrupt(std::function<bool()> keep_going) { interrupt_.set(std::move(keep_going)); }

    // The step level (step time_step / 2^level) the error control holds (0 without it).
    int level() const { return level_; }

private:
    void step_at_level(StateType& state, SolverStatistics& stats, int level) {
        int iterations = 0;
        double residual = 0.0;
        if (try_step(state, level, iterations, residual)) {
            stats.steps += 1;
            stats.newton_iterations += std::uint64_t(iterations);
            stats.max_iterations_in_a_step = std::max(stats.max_iterations_in_a_step, iterations);
            return;
        }
        stats.newton_iterations += std::uint64_t(iterations);
        if (level >= s_.max_halvings) {
            const double dt = s_.time_step / double(1 << level);
            if (!std::isfinite(residual))
                throw ConvergenceError(detail::concat(
                    "the state became non-finite at t = ", state.t, " s with time step ", dt, " s (", level,
                    " halvings): the integration is unstable", s_.beta < 0.25 ? " (beta < 1/4 is only conditionally "
                    "stable: reduce time_step below 2 / (omega_max sqrt(1 - 4 beta)) or use beta = 1/4)" : ""));
            throw ConvergenceError(detail::concat(
                "Newton-Raphson did not converge at t = ", state.t, " s with time step ", dt, " s (", level,
                " halvings) after ", iterations, " iterations; residual ", residual, " N (tolerance ",
                s_.residual_tolerance * force_scale_, " N)"));
        }
        stats.halvings += 1;
        step_at_level(state, stats, level + 1);
        step_at_level(state, stats, level + 1);
    }

    static NewmarkSettings validated(const NewmarkSettings& s) {
        s.validate();
        return s;
    }
    template <class A>
    static double row_sum_norm(const A& matrix) {
        Eigen::VectorXd sums = Eigen::VectorXd::Zero(matrix.rows());
        if constexpr (std::is_base_of_v<Eigen::SparseMatrixBase<A>, A>) {
            for (int col = 0; col < matrix.outerSize(); ++col)
                for (typename A::InnerIterator it(matrix, col); it; ++it) sums[it.row()] += std::abs(it.value());
        } else {
            sums = matrix.cwiseAbs().rowwise().sum();
        }
        return sums.size() ? sums.maxCoeff() : 0.0;
    }

    bool try_step(StateType& s, int level, int& iterations, double& residual) {
        const double dt = s_.time_step / double(1 << level);
        const double alpha = s_.hht_alpha, one_alpha = 1.0 + alpha;
        const auto& C = linear_.damping();
        const auto& K = linear_.stiffness();
        const double t1 = s.t + dt;
        prepare(system_, t1, s.workspace);
        q_pred_ = s.q + dt * s.v + (dt * dt * (0.5 - s_.beta)) * s.a;
        v_pred_ = s.v + (dt * (1.0 - s_.gamma)) * s.a;
        // r(a) = Aa a + b + (1 + alpha) f(q, v)
        b_.noalias() = C * v_pred_;
        b_.noalias() += K * q_pred_;
        if (alpha != 0.0) {
            b_ *= one_alpha;
            b_.noalias() -= alpha * (C * s.v);
            b_.noalias() -= alpha * (K * s.q);
            b_ -= alpha * s.f;
        }
        const double v_factor = s_.gamma / (s_.beta * dt);
        const double r_tol = s_.residual_tolerance * force_scale_;
        linear_.new_step();
        error_ = std::numeric_limits<double>::infinity();  // until Newton converges

        // The unknown is the new acceleration (q and v follow from it): unlike q, no rounding error
        // gets amplified by 1/(beta dt^2) in the residual.
        detail::copy_vector(s.a, a_);
        const double q_step = s_.beta * dt * dt, v_step = s_.gamma * dt;
        for (iterations = 0; iterations < s_.max_iterations;) {
            q_ = q_pred_ + q_step * a_;
            v_ = v_pred_ + v_step * a_;
            nonlinear_force(system_, s.workspace, q_, v_, s.f);
            r_.noalias() = linear_.residual_matrix(level) * a_;
            r_ += b_;
            r_ += one_alpha * s.f;
            residual = r_.cwiseAbs().maxCoeff();
            if (!std::isfinite(residual)) return fail_step(s);
            linear_.fill_tangent(s.workspace, q_, v_, 1.0, v_factor);
            const double q_max = q_.cwiseAbs().maxCoeff();
            const bool residual_ok = residual <= r_tol || residual <= rounding_floor(q_max);
            const double q_tol = s_.increment_tolerance * (q_max + 1e-9);
            // Skip the confirming solve when the next increment is bounded below tolerance.
            if (iterations > 0 && residual_ok && linear_.inverse_bound(level) > 0.0 &&
                r_.norm() * linear_.inverse_bound(level) <= q_tol && linear_.tangent_is_spd())
                return finish(s, t1, dt, false);  // s.f is already the force at (q_, v_)
            linear_.solve(level, one_alpha, r_, dq_);
            a_ += dq_ / q_step;
            ++iterations;
            if (residual_ok && dq_.cwiseAbs().maxCoeff() <= q_tol) {
                q_ = q_pred_ + q_step * a_;
                v_ = v_pred_ + v_step * a_;
                return finish(s, t1, dt, true);
            }
        }
        return fail_step(s);
    }

    // Rounding floor of the residual at the iterate (q_, v_, a_): a few ulps of its largest terms, the
    // contacts' included (a stiff contact turns the rounding of q into k eps |q| of force: preloads
    // that balance each other leave no large term in the residual to hide it). Needed only when the
    // residual is above tolerance.
    double rounding_floor(double q_max) const {
        return 64.0 * std::numeric_limits<double>::epsilon() *
               (norm_M_ * a_.cwiseAbs().maxCoeff() + norm_C_ * v_.cwiseAbs().maxCoeff() +
                (norm_K_ + linear_.tangent_norm()) * q_max);
    }

    // The converged iterate (q_, v_, a_): accepted, or under a tolerance refused when its error is
    // above it (the state left as it was).
    CAMFOLLOWER_FORCE_INLINE bool finish(StateType& s, double t1, double dt, bool evaluate_force) {
        if (evaluate_force) nonlinear_force(system_, s.workspace, q_, v_, s.f);
        if (control_error_ && !within_tolerance(s, dt)) return fail_step(s);
        accept(s, t1);
        return true;
    }

    CAMFOLLOWER_FORCE_INLINE void accept(StateType& s, double t1) {
        if constexpr (has_events_v<System>) {
            if (events_.changed(s.workspace, q_, v_)) record_crossings(s, t1);
        }
        s.t = t1;
        detail::copy_vector(q_, s.q);
        detail::copy_vector(v_, s.v);
        detail::copy_vector(a_, s.a);
        accepted(system_, s.workspace, s.q, s.v);
    }

    // The crossings in the step from s to (t1, q_, v_), in time order, located on the cubic through
    // both ends (rare: out of line).
    CAMFOLLOWER_NOINLINE void record_crossings(const StateType& s, double t1) {
        auto path = [&](double t, Vector& q, Vector& v) { EventWatch<System>::hermite(t, s.t, t1, s.q, s.v, q_, v_, q, v); };
        while (const Crossing c = events_.earliest(s.t, t1, path)) events_.record(c);
    }

    // A failed attempt leaves the state as it was, but for the force at the old state (HHT needs it)
    // and the workspace's time terms, both restored here.
    bool fail_step(StateType& s) {
        prepare(system_, s.t, s.workspace);
        nonlinear_force(system_, s.workspace, s.q, s.v, s.f);
        return false;
    }

    // Error control (newmark_adaptive). The steps are time_step / 2^level, level in [coarsest_level_,
    // max_halvings]: each level's Newton matrix is factored once at construction, as for the halvings,
    // and the steps land on the output grid (no interpolation). Levels change by the error estimate:
    // finer after a refused step (Newton's failure: one level; error e: enough levels for e 8^-m <=
    // 1/2), one level coarser at the end of an output interval whose every step predicts <= 0.8 at
    // twice the step. Changes are kept rare on purpose: at a constant step Fox-Goodwin's local
    // errors largely cancel from step to step (its fourth-order phase), and each change of the step
    // leaves one of them uncancelled (docs/solvers.md).
    void start_error_control(const StateType& s) {
        scales_.start(reference_rate(system_, s, s_.time_step), s.q, s.v);
        // A run from rest at zero has no size to measure displacements against; the explicit methods
        // then shrink their first steps without bound, the levels cannot. The static deflection under
        // the force scale stands in.
        if (norm_K_ > 0.0) scales_.floor_displacement(force_scale_ / norm_K_);
        double largest = s_.time_step;
        if (s_.max_step > 0.0) largest = std::min(largest, s_.max_step);
        const char* bound = s_.max_step > 0.0 && s_.max_step < s_.time_step ? "max_step" : "time_step";
        if (s_.beta < 0.5 * s_.gamma) {
            const double omega_max = camfollower::highest_angular_frequency(system_, s);
            if (std::isfinite(omega_max) && newmark_step_limit(s_.gamma, s_.beta, omega_max) < largest) {
                largest = newmark_step_limit(s_.gamma, s_.beta, omega_max);
                bound = "the stability limit";
            }
        }
        coarsest_level_ = 0;
        while (coarsest_level_ <= s_.max_halvings && s_.time_step / double(1 << coarsest_level_) > largest * (1.0 + 1e-12))
            ++coarsest_level_;
        if (coarsest_level_ > s_.max_halvings)
            detail::fail("Newmark under a tolerance: the largest step allowed by ", bound, " (", largest,
                         " s) is below the smallest step time_step / 2^max_halvings = ",
                         s_.time_step / double(1 << s_.max_halvings), " s; raise max_halvings (at most ",
                         NewmarkSettings::max_levels - 1, ") or shorten time_step");
        level_ = coarsest_level_;
        has_old_difference_ = false;
    }

    void step_under_tolerance(StateType& s, SolverStatistics& stats) {
        const int finest = s_.max_halvings;
        const std::uint32_t end = std::uint32_t(1) << finest;
        std::uint32_t done = 0;  // of the output interval, in its finest steps
        int level = level_;
        double largest_error = 0.0;  // of the interval's accepted steps
        while (done < end) {
            interrupt_();
            int iterations = 0;
            double residual = 0.0;
            const bool ok = try_step(s, level, iterations, residual);
            stats.newton_iterations += std::uint64_t(iterations);
            const std::uint32_t stride = std::uint32_t(1) << (finest - level);
            if (ok) {
                stats.steps += 1;
                stats.max_iterations_in_a_step = std::max(stats.max_iterations_in_a_step, iterations);
                done += stride;
                largest_error = std::max(largest_error, error_);
                continue;
            }
            const bool newton_failed = !std::isfinite(error_);
            if (level >= finest) {
                const double dt = s_.time_step / double(1 << level);
                if (newton_failed)
                    throw ConvergenceError(detail::concat(
                        "Newton-Raphson did not converge at t = ", s.t, " s with time step ", dt, " s (the smallest, "
                        "time_step / 2^max_halvings) after ", iterations, " iterations; residual ", residual,
                        " N (tolerance ", s_.residual_tolerance * force_scale_, " N)"));
                throw ConvergenceError(detail::concat(
                    method_name(s_), " under tolerance = ", s_.tolerance, ": the error estimate is ", error_,
                    " times the tolerance at t = ", s.t, " s with the smallest step time_step / 2^max_halvings = ", dt,
                    " s; raise max_halvings (at most ", NewmarkSettings::max_levels - 1, ") or the tolerance"));
            }
            if (newton_failed) {
                ++stats.halvings;
                ++level;
            } else {
                ++stats.rejected_steps;
                const int more = std::max(1, int(std::ceil(std::log2(2.0 * error_) / 3.0)));
                level = std::min(finest, level + more);
            }
        }
        if (level > coarsest_level_ && largest_error <= coarsen_below) --level;
        level_ = level;
    }

    // Zienkiewicz & Xie's local error estimate of the step from s to (q_, v_, a_), dt long, in units
    // of the tolerance (ErrorScales: the mixed norm and the force-weighted one). With the step's
    // acceleration difference da = a1 - a0 ~ dt a':
    //   e_q = (beta - 1/6) dt^2 da                         (the displacement's dt^3 term)
    //   e_v = (gamma - 1/2) dt da - dt^3 / 12 a''            (a'' from this and the last step's da)
    // both ~dt^3, so one level coarser multiplies the error by 8.
    bool within_tolerance(const StateType& s, double dt) {
        da_ = a_ - s.a;
        eq_ = ((s_.beta - 1.0 / 6.0) * dt * dt) * da_;
        ev_ = ((s_.gamma - 0.5) * dt) * da_;
        if (has_old_difference_) {  // a'' ~ (da / dt - da_old / dt_old) / ((dt + dt_old) / 2)
            const double w = -dt * dt * dt / 12.0 * 2.0 / (dt + dt_old_);
            ev_ += (w / dt) * da_;
            ev_ -= (w / dt_old_) * da_old_;
        }
        tangent(system_, s.workspace, q_, v_, 1.0, 0.0, uvq_);
        tangent(system_, s.workspace, q_, v_, 0.0, 1.0, uvv_);
        const double force = force_error(system_, uvq_, uvv_, eq_, ev_, ef_) / (s_.tolerance * force_scale_);
        error_ = std::max(scales_.mixed(s_.tolerance, eq_, ev_, s.q, s.v, q_, v_), force);
        if (!(error_ <= 1.0)) {
            if (!std::isfinite(error_)) error_ = 1e10;  // refused for its error, not as Newton's failure
            return false;
        }
        std::swap(da_, da_old_);
        dt_old_ = dt, has_old_difference_ = true;
        scales_.update(q_, v_);
        return true;
    }
    static constexpr double coarsen_below = 0.1;

    const System& system_;
    NewmarkSettings s_;
    int n_;
    Linear linear_;
    const bool control_error_;
    int coarsest_level_ = 0, level_ = 0;
    double error_ = 0.0;  // the last attempt's error in units of the tolerance (+inf: Newton failed)
    double dt_old_ = 0.0;
    bool has_old_difference_ = false;
    ErrorScales scales_;
    Vector eq_, ev_, da_, da_old_, ef_;
    LowRank<Vector> uvq_, uvv_;
    InterruptPoll interrupt_;
    double force_scale_ = 1.0;
    double norm_M_ = 0.0, norm_C_ = 0.0, norm_K_ = 0.0;  // infinity norms, for the rounding floor
    // Scratch, sized once: nothing is allocated inside the time loop.
    Vector q_pred_, v_pred_, b_, a_, q_, v_, r_, dq_;
    EventWatch<System> events_{system_};
};

}  // namespace camfollower
