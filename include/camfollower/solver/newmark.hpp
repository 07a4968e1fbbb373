// Implicit Newmark-beta / HHT-alpha time integration with Newton-Raphson on the effective residual.
//
// System concept (see CamFollowerModel): dofs, Vector/Matrix (fixed size), mass_matrix(),
// damping_matrix(), stiffness_matrix(), initial_state(), at_time(t) -> TimeContext (members theta,
// g: the contact direction; pressure_angle()), nonlinear(ctx, q, v) -> {force, delta, contact}, and
// tangent_row(ctx, nl, velocity_factor) -> w such that d force / dq = g w^T.
//
// Residual (HHT-alpha, alpha in [-1/3, 0]; alpha = 0 is plain Newmark):
//   r = M a1 + (1 + alpha) (C v1 + K q1 + f1) - alpha (C v0 + K q0 + f0)
// with a1 = (q1 - q_pred) / (beta dt^2), v1 = v_pred + gamma dt a1. The Newton matrix is
// A0 + (1 + alpha) g w^T with A0 = M / (beta dt^2) + (1 + alpha)(gamma / (beta dt) C + K) constant
// for a given dt: it is factored once per step size, and the rank-one contact term is handled by
// the Sherman-Morrison formula (default) or by a dense LU of the full matrix every iteration.
// Convergence: residual below tolerance (or its rounding floor) and Newton increment below
// tolerance. When the Newton matrix is A0 plus a symmetric positive semi-definite contact term (no
// contact damping), the next increment is bounded by |r|_2 / lambda_min(A0) and the confirming
// solve is skipped: a step whose contact state does not change converges in one solve.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/error.hpp"

namespace camfollower {

enum class LinearSolver { sherman_morrison, dense_lu };

struct NewmarkSettings {
    double time_step = 3e-6;            // s
    double gamma = 0.5;
    double beta = 0.25;
    double hht_alpha = 0.0;             // in [-1/3, 0]
    double residual_tolerance = 1e-10;  // relative to the system's force scale
    double increment_tolerance = 1e-10; // relative to max |q| (+ 1 nm floor)
    int max_iterations = 25;
    int max_halvings = 6;
    LinearSolver linear_solver = LinearSolver::sherman_morrison;

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
        detail::require_positive(time_step, "time_step", "(s)");
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
    }
    static constexpr int max_levels = 16;
};

struct SolverStatistics {
    std::uint64_t steps = 0;              // accepted steps, substeps included
    std::uint64_t newton_iterations = 0;  // linear solves
    std::uint64_t halvings = 0;
    int max_iterations_in_a_step = 0;
    double mean_iterations() const { return steps ? double(newton_iterations) / double(steps) : 0.0; }
};

// Time histories, row-major per channel; one row every `decimation` steps (first row: t = 0).
template <int N>
struct SimulationResult {
    std::size_t rows = 0;
    std::vector<double> t, theta;
    std::vector<double> q, v, a;  // rows x N
    std::vector<double> contact_force, contact_stiffness, pressure_angle, penetration;
    std::vector<std::uint8_t> in_contact;
    std::vector<std::pair<double, double>> contact_loss;  // [start, end) times, every step checked
    SolverStatistics stats;
    double time_step = 0.0;
    std::size_t decimation = 1;
};

template <class System>
class NewmarkSolver {
public:
    static constexpr int N = System::dofs;
    using Vector = typename System::Vector;
    using Matrix = typename System::Matrix;

    using Nonlinear = decltype(std::declval<const System&>().nonlinear(
        std::declval<const System&>().at_time(0.0), std::declval<Vector>(), std::declval<Vector>()));

    struct State {
        double t = 0.0;
        Vector q, v, a;
        Nonlinear nl;                // nonlinear terms at (t, q, v); nl.force is f for HHT
        double theta = 0.0;          // cam angle, rad
        double pressure_angle = 0.0; // rad
    };

    NewmarkSolver(const System& system, const NewmarkSettings& settings) : system_(system), s_(settings) {
        s_.validate();
        const Matrix& M = system.mass_matrix();
        for (int k = 0; k < N; ++k)
            if (!(M(k, k) > 0.0)) detail::fail("mass matrix diagonal must be > 0");
        for (int level = 0; level <= s_.max_halvings; ++level) {
            const double dt = s_.time_step / double(1 << level);
            A0_[level] = effective_matrix(dt);
            Aa_[level] = (s_.beta * dt * dt) * A0_[level];
            lu_[level].compute(A0_[level]);
            // A 7x7 well-conditioned inverse applied as one matrix-vector product beats two
            // triangular solves; the factorization stays for the dense-LU option.
            A0_inv_[level] = lu_[level].inverse();
            // 1 / lambda_min(A0) when A0 is symmetric positive definite (0 disables the bound).
            inverse_bound_[level] = 0.0;
            if ((A0_[level] - A0_[level].transpose()).cwiseAbs().maxCoeff() <= 1e-14 * A0_[level].cwiseAbs().maxCoeff()) {
                const Eigen::SelfAdjointEigenSolver<Matrix> eig(A0_[level], Eigen::EigenvaluesOnly);
                if (eig.info() == Eigen::Success && eig.eigenvalues()[0] > 0.0)
                    inverse_bound_[level] = 1.0 / eig.eigenvalues()[0];
            }
        }
        norm_M_ = M.cwiseAbs().rowwise().sum().maxCoeff();
        norm_C_ = system.damping_matrix().cwiseAbs().rowwise().sum().maxCoeff();
        norm_K_ = system.stiffness_matrix().cwiseAbs().rowwise().sum().maxCoeff();
        const State s0 = initial_state();
        check_stability_limit(s0);
        force_scale_ = std::max({1.0, (system.stiffness_matrix() * s0.q).cwiseAbs().maxCoeff(),
                                 s0.nl.force.cwiseAbs().maxCoeff()});
    }

    // beta < gamma / 2 is only conditionally stable: omega_max dt < 1 / sqrt(gamma / 2 - beta)
    // (undamped). omega_max from the tangent stiffness at the initial state, with a 10 % margin for
    // its variation along the motion (the contact direction turns with the pressure angle).
    void check_stability_limit(const State& s0) const {
        if (s_.beta >= 0.5 * s_.gamma) return;
        const auto ctx = system_.at_time(0.0);
        const Vector w = system_.tangent_row(ctx, s0.nl, 0.0);
        const Matrix gw = ctx.g * w.transpose();
        const Matrix Kt = system_.stiffness_matrix() + 0.5 * (gw + gw.transpose());
        const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Kt, system_.mass_matrix(), Eigen::EigenvaluesOnly);
        if (eig.info() != Eigen::Success) return;
        const double omega_max = std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
        const double limit = 0.9 / (omega_max * std::sqrt(0.5 * s_.gamma - s_.beta));
        if (s_.time_step > limit)
            detail::fail("time_step = ", s_.time_step, " s exceeds the stability limit ", limit, " s of Newmark with beta = ",
                         s_.beta, " < gamma / 2 (highest mode ", omega_max / (2.0 * 3.14159265358979323846),
                         " Hz); reduce time_step or use beta = 1/4");
    }

    // The solver keeps a reference to the system: a temporary would dangle.
    NewmarkSolver(System&&, const NewmarkSettings&) = delete;

    const NewmarkSettings& settings() const { return s_; }
    double force_scale() const { return force_scale_; }

    // System at rest in its initial (static) state, with the consistent acceleration.
    State initial_state() const {
        State s;
        s.t = 0.0;
        s.q = system_.initial_state();
        s.v.setZero();
        finish(s, system_.at_time(0.0));
        s.a = system_.mass_matrix().partialPivLu().solve(
            -(system_.damping_matrix() * s.v + system_.stiffness_matrix() * s.q + s.nl.force));
        return s;
    }

    // One step of the nominal size, halving (recursively, bounded) when Newton fails.
    void advance(State& state, SolverStatistics& stats, int level = 0) const {
        State next;
        int iterations = 0;
        double residual = 0.0;
        if (try_step(state, next, level, iterations, residual)) {
            state = next;
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
        advance(state, stats, level + 1);
        advance(state, stats, level + 1);
    }

    // Integrate from the initial state for `duration` seconds (ceil(duration / time_step) steps),
    // recording every `decimation`-th step.
    SimulationResult<N> run(double duration, std::size_t decimation = 1,
                            double max_output_bytes = 4.0 * 1024 * 1024 * 1024) const {
        detail::require_positive(duration, "duration", "(s)");
        if (decimation < 1) detail::fail("decimation must be >= 1, got ", decimation);
        detail::require_positive(max_output_bytes, "max_output_bytes");
        const double steps_real = std::ceil(duration / s_.time_step - 1e-9);
        if (!(steps_real < 1e13))
            detail::fail("duration / time_step = ", steps_real, " steps is too many (limit 1e13)");
        const auto steps = static_cast<std::uint64_t>(steps_real);
        const std::uint64_t rows = steps / decimation + 1;
        const double bytes = double(rows) * (8.0 * (6 + 3 * N) + 1.0);
        if (bytes > max_output_bytes)
            detail::fail("duration ", duration, " s at time_step ", s_.time_step, " s and decimation ", decimation,
                         " would store ", rows, " rows (", bytes / 1073741824.0,
                         " GiB) > max_output_bytes = ", max_output_bytes / 1073741824.0,
                         " GiB; increase decimation or shorten the duration");

        SimulationResult<N> out;
        out.time_step = s_.time_step;
        out.decimation = decimation;
        reserve(out, std::size_t(rows));
        State state = initial_state();
        record(out, state);
        bool contact = state.nl.contact.in_contact;
        double loss_start = 0.0;
        for (std::uint64_t n = 1; n <= steps; ++n) {
            advance(state, out.stats);
            if (state.nl.contact.in_contact != contact) {
                if (contact) loss_start = state.t;
                else out.contact_loss.emplace_back(loss_start, state.t);
                contact = state.nl.contact.in_contact;
            }
            if (n % decimation == 0) record(out, state);
        }
        if (!contact) out.contact_loss.emplace_back(loss_start, state.t);
        return out;
    }

private:
    Matrix effective_matrix(double dt) const {
        const double one_alpha = 1.0 + s_.hht_alpha;
        return system_.mass_matrix() / (s_.beta * dt * dt) +
               one_alpha * (s_.gamma / (s_.beta * dt) * system_.damping_matrix() + system_.stiffness_matrix());
    }

    // Fill the state's time-dependent outputs and nonlinear terms (given, or evaluated here).
    template <class Context>
    void finish(State& s, const Context& ctx, const Nonlinear& nl) const {
        s.nl = nl;
        s.theta = ctx.theta;
        s.pressure_angle = ctx.pressure_angle();
    }
    template <class Context>
    void finish(State& s, const Context& ctx) const {
        finish(s, ctx, system_.nonlinear(ctx, s.q, s.v));
    }

    bool try_step(const State& s, State& out, int level, int& iterations, double& residual) const {
        const double dt = s_.time_step / double(1 << level);
        const double alpha = s_.hht_alpha, one_alpha = 1.0 + alpha;
        const Matrix& C = system_.damping_matrix();
        const Matrix& K = system_.stiffness_matrix();
        const double t1 = s.t + dt;
        const auto ctx = system_.at_time(t1);
        const Vector q_pred = s.q + dt * s.v + (dt * dt * (0.5 - s_.beta)) * s.a;
        const Vector v_pred = s.v + (dt * (1.0 - s_.gamma)) * s.a;
        // The residual is affine in the new acceleration but for the nonlinear force:
        // r(a) = Aa a + b + (1 + alpha) f(q, v), Aa = M + (1 + alpha)(gamma dt C + beta dt^2 K).
        Vector b = one_alpha * (C * v_pred + K * q_pred);
        if (alpha != 0.0) b -= alpha * (C * s.v + K * s.q + s.nl.force);
        const double v_factor = s_.gamma / (s_.beta * dt);
        // A0^-1 u with u = (1 + alpha) g: the Sherman-Morrison vector, fixed for the step.
        const Vector u = one_alpha * ctx.g;
        const Vector A0_inv_u = A0_inv_[level] * u;
        const double r_tol = s_.residual_tolerance * force_scale_;

        // The unknown is the new acceleration (q and v follow from it): unlike a/q, no rounding error
        // of q gets amplified by 1/(beta dt^2) in the residual.
        Vector a = s.a;
        const double q_step = s_.beta * dt * dt, v_step = s_.gamma * dt;
        for (iterations = 0; iterations < s_.max_iterations;) {
            const Vector q = q_pred + q_step * a;
            const Vector v = v_pred + v_step * a;
            const auto nl = system_.nonlinear(ctx, q, v);
            const Vector r = Aa_[level] * a + b + one_alpha * nl.force;
            residual = r.cwiseAbs().maxCoeff();
            if (!std::isfinite(residual)) return false;
            // Rounding floor of the residual: a few ulps of its largest terms.
            const double floor = 64.0 * std::numeric_limits<double>::epsilon() *
                                 (norm_M_ * a.cwiseAbs().maxCoeff() + norm_C_ * v.cwiseAbs().maxCoeff() +
                                  norm_K_ * q.cwiseAbs().maxCoeff());
            const bool residual_ok = residual <= std::max(r_tol, floor);
            const double q_tol = s_.increment_tolerance * (q.cwiseAbs().maxCoeff() + 1e-9);
            const Vector w = system_.tangent_row(ctx, nl, v_factor);
            // The next Newton increment is bounded without solving when the Newton matrix is A0 plus
            // a symmetric positive semi-definite term (w = s u, s >= 0): |dq|_2 <= |r|_2 / lambda_min(A0).
            if (iterations > 0 && residual_ok && inverse_bound_[level] > 0.0) {
                const double s = w.dot(u) / u.squaredNorm();
                if (s >= 0.0 && (w - s * u).squaredNorm() <= 1e-24 * w.squaredNorm() &&
                    r.norm() * inverse_bound_[level] <= q_tol) {
                    out.a = a, out.q = q, out.v = v, out.t = t1;
                    finish(out, ctx, nl);  // q and v are those nl was evaluated at
                    return true;
                }
            }
            // Newton: (beta dt^2) (A0 + u w^T) da = -r; dq = beta dt^2 da.
            Vector dq;
            if (s_.linear_solver == LinearSolver::sherman_morrison) {
                const Vector x = A0_inv_[level] * r;
                dq = -(x - A0_inv_u * (w.dot(x) / (1.0 + w.dot(A0_inv_u))));
            } else {
                const Matrix A = A0_[level] + u * w.transpose();
                dq = -A.partialPivLu().solve(r);
            }
            a += dq / q_step;
            ++iterations;
            if (residual_ok && dq.cwiseAbs().maxCoeff() <= q_tol) {
                accept(out, a, q_pred, v_pred, q_step, v_step, t1, ctx);
                return true;
            }
        }
        return false;
    }

    template <class Context>
    void accept(State& out, const Vector& a, const Vector& q_pred, const Vector& v_pred, double q_step,
                double v_step, double t1, const Context& ctx) const {
        out.a = a;
        out.q = q_pred + q_step * a;
        out.v = v_pred + v_step * a;
        out.t = t1;
        finish(out, ctx);
    }

    static void reserve(SimulationResult<N>& out, std::size_t rows) {
        for (auto* v : {&out.t, &out.theta, &out.contact_force, &out.contact_stiffness, &out.pressure_angle,
                        &out.penetration})
            v->reserve(rows);
        for (auto* v : {&out.q, &out.v, &out.a}) v->reserve(rows * N);
        out.in_contact.reserve(rows);
        out.contact_loss.reserve(64);
    }

    static void record(SimulationResult<N>& out, const State& s) {
        out.t.push_back(s.t);
        out.theta.push_back(s.theta);
        for (int k = 0; k < N; ++k) {
            out.q.push_back(s.q[k]);
            out.v.push_back(s.v[k]);
            out.a.push_back(s.a[k]);
        }
        out.contact_force.push_back(s.nl.contact.force);
        out.contact_stiffness.push_back(s.nl.contact.stiffness);
        out.pressure_angle.push_back(s.pressure_angle);
        out.penetration.push_back(s.nl.delta);
        out.in_contact.push_back(s.nl.contact.in_contact ? 1 : 0);
        ++out.rows;
    }

    const System& system_;
    NewmarkSettings s_;
    std::array<Matrix, NewmarkSettings::max_levels> A0_, Aa_, A0_inv_;
    std::array<Eigen::PartialPivLU<Matrix>, NewmarkSettings::max_levels> lu_;
    std::array<double, NewmarkSettings::max_levels> inverse_bound_{};
    double force_scale_ = 1.0;
    double norm_M_ = 0.0, norm_C_ = 0.0, norm_K_ = 0.0;  // infinity norms, for the rounding floor
};

}  // namespace camfollower
