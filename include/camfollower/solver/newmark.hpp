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
// gamma = 1/2 with beta < 1/4 (Fox-Goodwin) post-processes the velocity to fourth order
// (NewmarkParameters::processed): the stepper keeps the jerk at the last state and the acceleration
// before it, and starts them from a central difference of the acceleration in time.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "camfollower/core/system.hpp"
#include "camfollower/detail/force_inline.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/dense_newton.hpp"
#include "camfollower/solver/error_scales.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/interrupt.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"
#include "camfollower/solver/step_limit.hpp"
#include "camfollower/solver/step_sensitivity.hpp"

namespace camfollower {

// to = from; a fixed-size vector as an inline copy (in the stepper's large functions GCC calls Eigen's
// assignment loop out of line for each 7-vector copy: 67 of ~2950 instructions per preset step).
namespace detail {
template <class V>
CAMFOLLOWER_FORCE_INLINE void copy_vector(const V& from, V& to) {
    if constexpr (V::SizeAtCompileTime != Eigen::Dynamic)
        std::memcpy(to.data(), from.data(), sizeof(typename V::Scalar) * std::size_t(V::SizeAtCompileTime));
    else to = from;
}
}  // namespace detail

// The stepper, on a linear backend (DenseNewtonSolve by default; SparseNewtonSolve in
// solver/sparse_newton.hpp for large models).
template <class System, class Linear = DenseNewtonSolve<System>>
class Newmark {
    static_assert(check_system<System>());

public:
    using Vector = typename System::Vector;
    using SystemType = System;
    using StateType = State<System>;

    Newmark(const System& system, const SolverSettings& settings)
        : system_(system),
          s_(validated(settings)),
          p_(newmark_parameters(s_)),
          n_(system.size()),
          linear_(system, s_),
          control_error_(s_.tolerance.has_value()),
          numerov_(p_.processed && p_.beta == 1.0 / 12.0) {
        norm_M_ = row_sum_norm(linear_.mass());
        norm_C_ = row_sum_norm(linear_.damping());
        norm_K_ = row_sum_norm(linear_.stiffness());
        for (Vector* v : {&q_pred_, &v_pred_, &b_, &a_, &q_, &v_, &r_, &dq_}) v->resize(n_);
        if (p_.processed)
            for (Vector* v : {&jerk_, &a_prev_, &jerk_next_}) v->resize(n_);
        if (control_error_) {
            for (Vector* v : {&eq_, &ev_, &da_, &da_old_, &ef_}) v->resize(n_);
            if (numerov_)
                for (Vector* v : {&a_prev2_, &a3_, &a3_old_}) v->resize(n_);
            uvq_ = uvv_ = LowRank<Vector>(n_, std::max(1, max_rank(system)));
        }
    }

    // The stepper keeps a reference to the system: a temporary would dangle.
    Newmark(System&&, const SolverSettings&) = delete;

    const SolverSettings& settings() const { return s_; }
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
        if (p_.processed) start_history(s);
        if constexpr (provides_sensitivity) {
            if (sensitivity_) start_sensitivity(s);
        }
        accepted(system_, s.workspace, s.q, s.v);  // path memory starts from the initial state
        events_.start(s.workspace, s.q, s.v);
        return s;
    }

    // The variational equations (solver/step_sensitivity.hpp) on the dense backend; the sparse one
    // would refactor its matrix for every column (shooting's finite differences serve it).
    static constexpr bool provides_sensitivity = std::is_same_v<Linear, DenseNewtonSolve<System>>;
    // While set (non-null), start() and every accepted step carry d(q, v, a) / d(q0, v0) in
    // *sensitivity, (q0, v0) being the state given to start(); null stops it. Sizes once per call.
    using Sensitivity = StepSensitivity<Vector>;
    void track_sensitivity(Sensitivity* sensitivity) {
        static_assert(provides_sensitivity, "the variational equations need the dense backend");
        sensitivity_ = sensitivity;
        if (!sensitivity) return;
        const int capacity = std::max(1, max_rank(system_));
        sensitivity->resize(n_, capacity);
        sens_uvq_ = sens_uvv_ = LowRank<Vector>(n_, capacity);
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
                    " halvings): the integration is unstable",
                    p_.beta < 0.25
                        ? " (beta < 1/4 is only conditionally "
                          "stable: reduce time_step below 2 / (omega_max sqrt(1 - 4 beta)) or use beta = 1/4)"
                        : ""));
            throw ConvergenceError(detail::concat("Newton-Raphson did not converge at t = ", state.t,
                                                  " s with time step ", dt, " s (", level, " halvings) after ",
                                                  iterations, " iterations; residual ", residual, " N (tolerance ",
                                                  s_.residual_tolerance * force_scale_, " N)"));
        }
        stats.halvings += 1;
        step_at_level(state, stats, level + 1);
        step_at_level(state, stats, level + 1);
    }

    static SolverSettings validated(const SolverSettings& s) {
        s.validate();
        if (!is_newmark_family(s.method))
            detail::fail("the Newmark stepper runs methods 'newmark', 'fox_goodwin' and 'hht', got '",
                         method_name(s.method), "' (simulate() and periodic_orbit() run every method)");
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
        const double alpha = p_.alpha, one_alpha = 1.0 + alpha;
        const auto& C = linear_.damping();
        const auto& K = linear_.stiffness();
        const double t1 = s.t + dt;
        // The velocity the forces see moves by v_step per unit of the new acceleration; the Newton
        // matrix was formed with damping_gamma dt, the rest (a processed step of another length than
        // the last) is added to the residual.
        double v_step = p_.gamma * dt, v_step_excess = 0.0;
        if (p_.processed && !history_is_of(s)) start_history(s);
        prepare(system_, t1, s.workspace);
        if (p_.processed) {
            v_step = predict_processed(s, dt);
            v_step_excess = v_step - p_.damping_gamma * dt;
        } else {
            q_pred_ = s.q + dt * s.v + (dt * dt * (0.5 - p_.beta)) * s.a;
            v_pred_ = s.v + (dt * (1.0 - p_.gamma)) * s.a;
        }
        v_step_ = v_step, v_step_excess_ = v_step_excess;
        // r(a) = Aa a + b + (1 + alpha) f(q, v)
        b_.noalias() = C * v_pred_;
        b_.noalias() += K * q_pred_;
        if (alpha != 0.0) {
            b_ *= one_alpha;
            b_.noalias() -= alpha * (C * s.v);
            b_.noalias() -= alpha * (K * s.q);
            b_ -= alpha * s.f;
        }
        const double v_factor = v_step / (p_.beta * dt * dt);
        const double r_tol = s_.residual_tolerance * force_scale_;
        linear_.new_step();
        error_ = std::numeric_limits<double>::infinity();  // until Newton converges

        // The unknown is the new acceleration (q and v follow from it): unlike q, no rounding error
        // gets amplified by 1/(beta dt^2) in the residual.
        detail::copy_vector(s.a, a_);
        const double q_step = p_.beta * dt * dt;
        for (iterations = 0; iterations < s_.max_iterations;) {
            q_ = q_pred_ + q_step * a_;
            v_ = v_pred_ + v_step * a_;
            nonlinear_force(system_, s.workspace, q_, v_, s.f);
            r_.noalias() = linear_.residual_matrix(level) * a_;
            if (v_step_excess != 0.0) r_.noalias() += v_step_excess * (C * a_);
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
                return finish(s, t1, dt, level, false);  // s.f is already the force at (q_, v_)
            linear_.solve(level, one_alpha, r_, dq_);
            a_ += dq_ / q_step;
            ++iterations;
            if (residual_ok && dq_.cwiseAbs().maxCoeff() <= q_tol) {
                q_ = q_pred_ + q_step * a_;
                v_ = v_pred_ + v_step * a_;
                return finish(s, t1, dt, level, true);
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
    CAMFOLLOWER_FORCE_INLINE bool finish(StateType& s, double t1, double dt, int level, bool evaluate_force) {
        if (evaluate_force) nonlinear_force(system_, s.workspace, q_, v_, s.f);
        bool crossed = false;  // a switching function changed sign: the step has a kink or jump inside
        if constexpr (has_events_v<System>) crossed = events_.changed(s.workspace, q_, v_);
        if (control_error_ && !within_tolerance(s, dt, crossed)) return fail_step(s);
        if constexpr (provides_sensitivity) {
            if (sensitivity_) propagate_sensitivity(s.workspace, dt, level);
        }
        if (p_.processed) advance_history(s, t1, dt);
        accept(s, t1, crossed);
        return true;
    }

    CAMFOLLOWER_FORCE_INLINE void accept(StateType& s, double t1, bool crossed) {
        if (crossed) record_crossings(s, t1);
        s.t = t1;
        detail::copy_vector(q_, s.q);
        detail::copy_vector(v_, s.v);
        detail::copy_vector(a_, s.a);
        accepted(system_, s.workspace, s.q, s.v);
    }

    // The crossings in the step from s to (t1, q_, v_), in time order, located on the cubic through
    // both ends (rare: out of line).
    CAMFOLLOWER_NOINLINE void record_crossings(StateType& s, double t1) {
        auto path = [&](double t, Vector& q, Vector& v) {
            EventWatch<System>::hermite(t, s.t, t1, s.q, s.v, q_, v_, q, v);
        };
        while (const Crossing c = events_.earliest(s.t, t1, path)) events_.record(c, s.workspace);
    }

    // The processed velocity (NewmarkParameters::processed). With a' the jerk, the trapezoidal velocity
    // of steps dt is vN = v + dt^2 / 12 a' (its quadrature error, by Euler-Maclaurin), so a step from s
    // starts from vN0 = v0 + dt^2 / 12 a'0, moves the displacement as Fox-Goodwin does, and ends at
    // v1 = vN0 + dt / 2 (a0 + a1) - dt^2 / 12 a'1, a'1 the three-point derivative through a_prev, a0,
    // a1 (spacings h_prev_, dt). Sets q_pred_, v_pred_ (v1 less its a1 part) and the weights; returns
    // v1's coefficient of a1. The first step after start_history (h_prev_ = 0, a_prev_ holding the
    // jerk a'0) takes a'1 = 2 (a1 - a0) / dt - a'0 instead, the trapezoidal rule's, also O(dt^2).
    double predict_processed(const StateType& s, double dt) {
        const double w = dt * dt / 12.0, h1 = h_prev_;
        if (h1 == dt) {
            jerk_weights_ = {1.5 / dt, -2.0 / dt, 0.5 / dt};
        } else if (h1 == 0.0) {
            jerk_weights_ = {2.0 / dt, -2.0 / dt, -1.0};
        } else {
            jerk_weights_ = {(2.0 * dt + h1) / (dt * (h1 + dt)), -(h1 + dt) / (h1 * dt), dt / (h1 * (h1 + dt))};
        }
        const auto [c1, c0, cm] = jerk_weights_;
        q_pred_ = s.q + dt * s.v + (dt * w) * jerk_ + (dt * dt * (0.5 - p_.beta)) * s.a;
        v_pred_ = s.v + w * jerk_ + (0.5 * dt - w * c0) * s.a - (w * cm) * a_prev_;
        return h1 == dt ? p_.damping_gamma * dt : 0.5 * dt - w * c1;
    }
    // After the step to t1 is accepted (s still the state before it, a_ the new acceleration).
    void advance_history(const StateType& s, double t1, double dt) {
        const auto [c1, c0, cm] = jerk_weights_;
        jerk_next_ = c1 * a_ + c0 * s.a + cm * a_prev_;
        if (numerov_ && control_error_) {  // the fourth-order error estimate's third acceleration back
            std::swap(a_prev_, a_prev2_);
            h_prev2_ = h_prev_;
        }
        detail::copy_vector(s.a, a_prev_);
        detail::copy_vector(jerk_next_, jerk_);
        h_prev_ = dt, history_t_ = t1, history_q0_ = q_[0];
    }
    // Whether the history is of state s (a state stepped from elsewhere restarts it).
    bool history_is_of(const StateType& s) const {
        return std::abs(s.t - history_t_) <= 1e-9 * s_.time_step && s.q[0] == history_q0_;
    }
    // The jerk at s by a central difference of the consistent acceleration along the state's Taylor
    // line (t +- d, q +- d v, v +- d a); no acceleration before it yet (h_prev_ = 0: a_prev_ holds the
    // jerk for the first step's two-point rule, predict_processed).
    CAMFOLLOWER_NOINLINE void start_history(const StateType& s) {
        const double d = 1e-3 * s_.time_step;
        acceleration_along(s, d, jerk_next_);
        acceleration_along(s, -d, a_prev_);
        jerk_ = (jerk_next_ - a_prev_) / (2.0 * d);
        a_prev_ = jerk_;
        h_prev_ = 0.0, history_t_ = s.t, history_q0_ = s.q[0];
        h_prev2_ = 0.0, has_a3_old_ = false, smooth_steps_ = 0;
    }
    // The state's Taylor line at s.t + d: (q_, v_) = (s.q + d s.v, s.v + d s.a), the returned workspace
    // prepared there and the force in r_ (s untouched). start_history and start_sensitivity difference
    // along it.
    workspace_t<System> along_taylor_line(const StateType& s, double d) {
        workspace_t<System> ws = s.workspace;
        prepare(system_, s.t + d, ws);
        q_ = s.q + d * s.v;
        v_ = s.v + d * s.a;
        nonlinear_force(system_, ws, q_, v_, r_);
        return ws;
    }
    // The consistent acceleration on the Taylor line at s.t + d, into out (q_, v_, r_, b_ as scratch).
    void acceleration_along(const StateType& s, double d, Vector& out) {
        (void)along_taylor_line(s, d);
        b_.noalias() = linear_.damping() * v_;
        b_.noalias() += linear_.stiffness() * q_;
        b_ += r_;
        out = linear_.solve_mass(-b_);
    }

    // A failed attempt leaves the state as it was, but for the force at the old state (HHT needs it)
    // and the workspace's time terms, both restored here.
    bool fail_step(StateType& s) {
        prepare(system_, s.t, s.workspace);
        nonlinear_force(system_, s.workspace, s.q, s.v, s.f);
        return false;
    }

    // The variational equations (solver/step_sensitivity.hpp): the start's and one accepted step's.
    CAMFOLLOWER_NOINLINE void start_sensitivity(const StateType& s) {
        Sensitivity& d = *sensitivity_;
        d.dq.setZero(), d.dv.setZero();
        d.dq.leftCols(n_).setIdentity();
        d.dv.rightCols(n_).setIdentity();
        tangent_products(s.workspace, s.q, s.v, d.dq, d.dv, d.g);
        d.da = linear_.mass().partialPivLu().solve(d.g);
        d.da = -d.da;
        if (p_.processed) {  // the start's jerk differentiated as start_history computes it
            const double h = s_.time_step, delta = 1e-3 * h;
            for (const double sign : {1.0, -1.0}) {
                // (the tangent is of the force along_taylor_line evaluated last)
                const workspace_t<System> ws = along_taylor_line(s, sign * delta);
                d.p = d.dq + (sign * delta) * d.dv;
                d.w = d.dv + (sign * delta) * d.da;
                tangent_products(ws, q_, v_, d.p, d.w, sign > 0.0 ? d.dj : d.da_prev);
            }
            d.r = (d.dj - d.da_prev) / (2.0 * delta);
            d.dj = linear_.mass().partialPivLu().solve(d.r);
            d.dj = -d.dj;
            d.da_prev = d.dj;  // as start_history's a_prev_
        }
    }
    CAMFOLLOWER_NOINLINE void propagate_sensitivity(const workspace_t<System>& ws, double dt, int level) {
        Sensitivity& d = *sensitivity_;
        const double alpha = p_.alpha, one_alpha = 1.0 + alpha;
        const double q_step = p_.beta * dt * dt, v_step = v_step_;
        if (p_.processed) {  // predict_processed's predictors, differentiated
            const double w = dt * dt / 12.0;
            const auto [c1, c0, cm] = jerk_weights_;
            (void)c1;
            d.p = d.dq + dt * d.dv + (dt * w) * d.dj + (dt * dt * (0.5 - p_.beta)) * d.da;
            d.w = d.dv + w * d.dj + (0.5 * dt - w * c0) * d.da - (w * cm) * d.da_prev;
            d.dj = c0 * d.da + cm * d.da_prev;  // the new jerk's, but for the new acceleration's term
            d.da_prev = d.da;
        } else {
            d.p = d.dq + dt * d.dv + (dt * dt * (0.5 - p_.beta)) * d.da;
            d.w = d.dv + (dt * (1.0 - p_.gamma)) * d.da;
        }
        tangent_products(ws, q_, v_, d.p, d.w, d.r);
        d.r *= one_alpha;
        if (alpha != 0.0) d.r -= alpha * d.g;
        linear_.fill_tangent(ws, q_, v_, 1.0, v_step / q_step);  // the Newton matrix at the step's end
        linear_.solve_columns(level, one_alpha, d.r, d.da);
        if (v_step_excess_ != 0.0) {
            // A processed step of another length than the last (the first after a start, a halving):
            // the level's matrix has damping_gamma dt C where the step has v_step C. Corrected by
            // defect iterations, each contracting by about v_step_excess |C| / |M| (alpha = 0: g is
            // free scratch until it is rebuilt below).
            for (int k = 0; k < 3; ++k) {
                d.g.noalias() = linear_.damping() * d.da;
                d.g *= v_step_excess_ / q_step;
                d.g += d.r;
                linear_.solve_columns(level, one_alpha, d.g, d.da);
            }
        }
        d.da /= q_step;
        d.dq = d.p + q_step * d.da;
        d.dv = d.w + v_step * d.da;
        if (p_.processed) d.dj += std::get<0>(jerk_weights_) * d.da;
        d.g *= alpha;
        d.g.noalias() -= linear_.mass() * d.da;
        d.g /= one_alpha;
    }
    // out = (K + F_q) xq + (C + F_v) xv, the tangent F at (q, v).
    using Block = typename Sensitivity::Block;
    void tangent_products(const workspace_t<System>& ws, const Vector& q, const Vector& v, const Block& xq,
                          const Block& xv, Block& out) {
        out.noalias() = linear_.stiffness() * xq;
        out.noalias() += linear_.damping() * xv;
        camfollower::tangent(system_, ws, q, v, 1.0, 0.0, sens_uvq_);
        camfollower::tangent(system_, ws, q, v, 0.0, 1.0, sens_uvv_);
        for (const auto* uv : {&sens_uvq_, &sens_uvv_}) {
            const int k = uv->rank;
            if (k == 0) continue;
            auto vx = sensitivity_->low_rank.topRows(k);
            vx.noalias() = uv->V.leftCols(k).transpose() * (uv == &sens_uvq_ ? xq : xv);
            out.noalias() += uv->U.leftCols(k) * vx;
        }
    }

    // Error control (a tolerance set). The steps are time_step / 2^level, level in [coarsest_level_,
    // max_halvings]: each level's Newton matrix is factored once at construction, as for the halvings,
    // and the steps land on the output grid (no interpolation). Levels change by the error estimate
    // (within_tolerance): finer after a refused step (Newton's failure: one level; error e: enough
    // levels for e 2^(-order m) <= 1/2). Coarser: with the per-step estimate one level at the end of an
    // output interval whose every step predicts <= 0.8 at twice the step (rare on purpose: at a
    // constant step the unprocessed rules' local errors largely cancel from step to step, and each
    // change leaves one uncancelled); with Fox-Goodwin's fourth-order one, coarser_level().
    void start_error_control(const StateType& s) {
        scales_.start(reference_rate(system_, s, s_.time_step), s.q, s.v);
        // A run from rest at zero has no size to measure displacements against; the explicit methods
        // then shrink their first steps without bound, the levels cannot. The static deflection under
        // the force scale stands in.
        if (norm_K_ > 0.0) scales_.floor_displacement(force_scale_ / norm_K_);
        double largest = s_.time_step;
        if (s_.max_step > 0.0) largest = std::min(largest, s_.max_step);
        const char* bound = s_.max_step > 0.0 && s_.max_step < s_.time_step ? "max_step" : "time_step";
        coarsest_level_ = 0;
        while (coarsest_level_ <= s_.max_halvings &&
               s_.time_step / double(1 << coarsest_level_) > largest * (1.0 + 1e-12))
            ++coarsest_level_;
        if (p_.beta < 0.5 * p_.gamma) {  // and within the stability limit (one test per level)
            const StepLimitTest stability(system_, s, p_);
            const int within = coarsest_level_;
            while (coarsest_level_ <= s_.max_halvings && !stability.allows(s_.time_step / double(1 << coarsest_level_)))
                ++coarsest_level_;
            if (coarsest_level_ != within) largest = stability.limit().step, bound = "the stability limit";
        }
        if (coarsest_level_ > s_.max_halvings)
            detail::fail("Newmark under a tolerance: the largest step allowed by ", bound, " (", largest,
                         " s) is below the smallest step time_step / 2^max_halvings = ",
                         s_.time_step / double(1 << s_.max_halvings), " s; raise max_halvings (at most ",
                         SolverSettings::max_levels - 1, ") or shorten time_step");
        level_ = coarsest_level_;
        has_old_difference_ = false;
        window_peak_ = window_peak_before_ = 0.0, window_steps_ = 0;
        refused_t_ = std::numeric_limits<double>::quiet_NaN(), one_off_ = false;
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
                if (error_order_ == 4) {
                    if (window_steps_ > 0 && window_steps_ % coarsen_window == 0)
                        window_peak_before_ = window_peak_, window_peak_ = 0.0;
                    window_peak_ = std::max(window_peak_, error_);
                    ++window_steps_;
                    level = coarser_level(level, done, finest);
                } else {
                    window_peak_ = window_peak_before_ = 0.0, window_steps_ = 0;
                }
                continue;
            }
            const bool newton_failed = !std::isfinite(error_);
            if (!newton_failed && kink_suspected(s.t, level)) continue;  // retried at this level, per step
            if (level >= finest) {
                const double dt = s_.time_step / double(1 << level);
                if (newton_failed)
                    throw ConvergenceError(
                        detail::concat("Newton-Raphson did not converge at t = ", s.t, " s with time step ", dt,
                                       " s (the smallest, "
                                       "time_step / 2^max_halvings) after ",
                                       iterations, " iterations; residual ", residual, " N (tolerance ",
                                       s_.residual_tolerance * force_scale_, " N)"));
                throw ConvergenceError(detail::concat(
                    method_name(s_.method), " under tolerance = ", *s_.tolerance, ": the error estimate is ", error_,
                    " times the tolerance at t = ", s.t, " s with the smallest step time_step / 2^max_halvings = ", dt,
                    " s; raise max_halvings (at most ", SolverSettings::max_levels - 1, ") or the tolerance"));
            }
            if (newton_failed) {
                ++stats.halvings;
                ++level;
            } else {
                ++stats.rejected_steps;
                refused_t_ = s.t, refused_level_ = level, refused_error_ = error_;
                refused_end_ = s.t + s_.time_step / double(1 << level);
                const int more = std::max(1, int(std::ceil(std::log2(2.0 * error_) / double(error_order_))));
                level = std::min(finest, level + more);
            }
            window_peak_ = window_peak_before_ = 0.0, window_steps_ = 0;
        }
        if (window_steps_ == 0 && level > coarsest_level_ && largest_error <= coarsen_below) --level;
        level_ = level;
    }

    // Fox-Goodwin's fourth-order estimate, after an accepted step (`done` finest steps into the
    // output interval): the level to go on at. Its estimate follows a ringing mode's phase (it passes
    // through zero twice a period), so the peak over the last coarsen_window to 2 coarsen_window steps
    // at this level stands for the mode's amplitude: as many levels coarser as that peak predicts
    // <= 0.8 at (16 x per level), as far as the steps stay on their own grid (each coarser step
    // starts at a multiple of its length, so the output points are still hit exactly).
    int coarser_level(int level, std::uint32_t done, int finest) {
        if (window_steps_ < coarsen_window) return level;
        int target = level;
        for (double e = std::max(window_peak_, window_peak_before_) * 16.0; target > coarsest_level_ && e <= 0.8;
             e *= 16.0)
            --target;
        while (target < level && done % (std::uint32_t(1) << (finest - target)) != 0) ++target;
        if (target != level) window_peak_ = window_peak_before_ = 0.0, window_steps_ = 0;
        return target;
    }

    // Whether the step from t just refused at `level`, within the span of a step refused at a coarser
    // level, holds a kink or jump of the acceleration that no switching function marks (a cam
    // program's segment boundary, a jump of the load): the fourth-order estimate then fell by less
    // than 8 x per halving (16 x where smooth).
    // Such an error is a one-off, not a phase that adds up over the run: the step is retried at this
    // level with the estimate per step (one_off_), and the next two steps, whose divided differences
    // span the kink, take the per-step one.
    bool kink_suspected(double t, int level) {
        if (error_order_ != 4 || one_off_ || !(t >= refused_t_ && t < refused_end_) || level <= refused_level_)
            return false;
        if (error_ * std::pow(8.0, level - refused_level_) <= refused_error_) return false;
        one_off_ = true;
        return true;
    }

    // The local error estimate of the step from s to (q_, v_, a_), dt long, in units of the tolerance
    // (ErrorScales: the mixed norm and the force-weighted one); error_order_ says how it grows per
    // doubling of the step (2^error_order_).
    //  - Newmark, HHT and Fox-Goodwin's first two steps after a start (Zienkiewicz & Xie), with the
    //    step's acceleration difference da = a1 - a0 ~ dt a', per step (order 3):
    //      e_q = (beta - 1/6) dt^2 da                       (the displacement's dt^3 term)
    //      e_v = (gamma - 1/2) dt da - dt^3 / 12 a''          (a'' from this and the last step's da)
    //  - processed Fox-Goodwin (beta = 1/12 exactly: fourth order), per radian of the reference rate
    //    (order 4): processed_error(). Other processed beta (the studies' period-matched scheme) are
    //    second order in the displacement: the per-step estimate. Not across a switching function's sign change
    //    (`crossed`: a contact made or lost) nor in the two steps after it, whose divided differences would span the
    //    kink: there the error is a one-off, not a phase that adds up, and the per-step estimate applies.
    bool within_tolerance(const StateType& s, double dt, bool crossed) {
        const bool fourth = numerov_ && !crossed && processed_error(s, dt);
        if (!fourth) {
            da_ = a_ - s.a;
            eq_ = ((p_.beta - 1.0 / 6.0) * dt * dt) * da_;
            ev_ = ((p_.gamma - 0.5) * dt) * da_;
            if (has_old_difference_) {  // a'' ~ (da / dt - da_old / dt_old) / ((dt + dt_old) / 2)
                const double w = -dt * dt * dt / 12.0 * 2.0 / (dt + dt_old_);
                ev_ += (w / dt) * da_;
                ev_ -= (w / dt_old_) * da_old_;
            }
        }
        error_order_ = fourth ? 4 : 3;
        tangent(system_, s.workspace, q_, v_, 1.0, 0.0, uvq_);
        tangent(system_, s.workspace, q_, v_, 0.0, 1.0, uvv_);
        const double force = force_error(system_, uvq_, uvv_, eq_, ev_, ef_) / (*s_.tolerance * force_scale_);
        error_ = std::max(scales_.mixed(*s_.tolerance, eq_, ev_, s.q, s.v, q_, v_), force);
        if (fourth && !one_off_) error_ /= dt * scales_.omega_ref;
        if (!(error_ <= 1.0)) {
            if (!std::isfinite(error_)) error_ = 1e10;  // refused for its error, not as Newton's failure
            return false;
        }
        const bool one_off = std::exchange(one_off_, false);
        if (fourth && one_off) {
            has_a3_old_ = false, smooth_steps_ = 0;
        } else if (fourth) {
            std::swap(a3_, a3_old_);
            h_a3_old_ = dt, has_a3_old_ = true;
            has_old_difference_ = false;
            ++smooth_steps_;
        } else {
            std::swap(da_, da_old_);
            dt_old_ = dt, has_old_difference_ = true;
            has_a3_old_ = false;
            smooth_steps_ = crossed ? 0 : smooth_steps_ + 1;
        }
        scales_.update(q_, v_);
        return true;
    }
    // The processed Fox-Goodwin's error: its displacements are Numerov's, whose error on a ringing
    // mode of amplitude A is a phase lag of (w dt)^5 / 480 A per step ((w dt)^4 / 480 A per radian of
    // the mode), i.e. dt^5 / 480 |q'''''| = dt^5 / 480 |a'''|; its velocities lag by the same
    // phase: dt^5 / 480 a''''. a''' from the third divided difference of the accelerations at t1,
    // t0 and the two accepted states before (a_prev_, a_prev2_), a'''' from its change since the last
    // step. Per radian of the reference rate (ErrorScales::omega_ref: the cam's for a camshaft-driven
    // system), because the phase errors add up over the run instead of cancelling: a run of one
    // revolution then ends within about 2 pi tolerances. False (no estimate: the caller falls back on
    // the per-step one) until two steps have been accepted since the history started or a crossing.
    bool processed_error(const StateType& s, double dt) {
        if (smooth_steps_ < 2) return false;
        const double at[4] = {dt, 0.0, -h_prev_, -h_prev_ - h_prev2_};
        double w[4];
        for (int i = 0; i < 4; ++i) {
            double product = 1.0;
            for (int j = 0; j < 4; ++j)
                if (j != i) product *= at[i] - at[j];
            w[i] = 6.0 / product;  // a''' = 3! times the third divided difference
        }
        a3_ = w[0] * a_ + w[1] * s.a + w[2] * a_prev_ + w[3] * a_prev2_;
        const double lag = std::pow(dt, 5) / 480.0;
        eq_ = lag * a3_;
        if (has_a3_old_) {  // the two estimates are centred about half a step apart on average
            ev_ = (lag / (0.5 * (dt + h_a3_old_))) * (a3_ - a3_old_);
        } else {
            ev_.setZero();
        }
        return true;
    }
    static constexpr double coarsen_below = 0.1;
    static constexpr int coarsen_window = 32;

    const System& system_;
    SolverSettings s_;
    NewmarkParameters p_;  // gamma, beta, alpha of the method
    int n_;
    Linear linear_;
    const bool control_error_;
    const bool numerov_;  // Fox-Goodwin processed: Numerov's displacements, the fourth-order estimate
    int coarsest_level_ = 0, level_ = 0;
    double error_ = 0.0;  // the last attempt's error in units of the tolerance (+inf: Newton failed)
    double dt_old_ = 0.0;
    bool has_old_difference_ = false;
    ErrorScales scales_;
    Vector eq_, ev_, da_, da_old_, ef_;
    LowRank<Vector> uvq_, uvv_;
    InterruptPoll interrupt_;
    Sensitivity* sensitivity_ = nullptr;   // variational equations while shooting builds a monodromy
    LowRank<Vector> sens_uvq_, sens_uvv_;  // their tangent, dF/dq and dF/dv apart
    double force_scale_ = 1.0;
    double norm_M_ = 0.0, norm_C_ = 0.0, norm_K_ = 0.0;  // infinity norms, for the rounding floor
    // The processed velocity's history: the jerk at the last accepted state, the acceleration one step
    // before it and that step's length; of the state at (history_t_, q[0] = history_q0_).
    Vector jerk_, a_prev_, jerk_next_;
    double h_prev_ = 0.0, history_t_ = std::numeric_limits<double>::quiet_NaN(), history_q0_ = 0.0;
    std::tuple<double, double, double> jerk_weights_{0.0, 0.0, 0.0};  // of a1, a0, a_prev in the new jerk
    // Under a tolerance, processed_error's: the acceleration two steps before the last state and that
    // step's length, the last accepted step's a''' estimate and that step's length, and the steps
    // accepted since the history started or the last crossing.
    Vector a_prev2_, a3_, a3_old_;
    double h_prev2_ = 0.0, h_a3_old_ = 0.0;
    bool has_a3_old_ = false;
    int smooth_steps_ = 0;
    // The largest fourth-order estimates of the steps at this level, in blocks of coarsen_window steps
    // (this block's and the last's), and the number of steps (step_under_tolerance).
    double window_peak_ = 0.0, window_peak_before_ = 0.0;
    int window_steps_ = 0;
    // The last refused attempt's span [refused_t_, refused_end_), level and error, and whether the next
    // attempt is estimated per step (kink_suspected).
    double refused_t_ = std::numeric_limits<double>::quiet_NaN(), refused_end_ = 0.0, refused_error_ = 0.0;
    int refused_level_ = 0;
    bool one_off_ = false;
    int error_order_ = 3;         // the last estimate's growth per doubling of the step: 2^error_order_
    double v_step_ = 0.0;         // the last attempt's velocity coefficient of the new acceleration
    double v_step_excess_ = 0.0;  // its part beyond the Newton matrix's damping_gamma dt
    // Scratch, sized once: nothing is allocated inside the time loop.
    Vector q_pred_, v_pred_, b_, a_, q_, v_, r_, dq_;
    EventWatch<System> events_{system_};
};

}  // namespace camfollower
