// SPDX-License-Identifier: BSD-3-Clause
// Explicit embedded Runge-Kutta methods with adaptive steps and dense output, for any system of the
// contract in core/system.hpp, written as the first-order system y = (q, v), y' = (v, a(t, q, v)) with
// M a = -(C v + K q + f(t, q, v) - p(t)). One stepper, EmbeddedRungeKutta<System, Scheme>, runs two
// schemes (Hairer, Norsett & Wanner, Solving ODE I, II.4-II.6 and II.10, and Hairer's codes DOPRI5 and
// DOP853):
//   DormandPrince<System>  Dormand-Prince 5(4): 6 force evaluations a step, 4th-order dense output;
//   Dop853<System>         Dormand-Prince 8(5,3): 12 a step, 7th-order dense output from 3 more,
//                          evaluated only for the steps that are interpolated (an output time or a
//                          located event inside them).
//
// Why beside Newmark: at the accuracy users read contact forces and accelerations (1e-4 ... 1e-8) a
// lumped cam-follower model is not stiff (the explicit stability limit allows larger steps than the
// accuracy does), and a fifth- or eighth-order method needs far fewer steps than a second-order one.
//
// Error control: a step is accepted when both the mixed displacement/velocity norm <= 1 and the
// force-weighted error |K_t e_q + C_t e_v|_inf <= tol * force_scale, K_t, C_t with the contacts'
// tangent at the new state (solver/error_scales.hpp).
// e is the scheme's error estimate: DOP853 has two (5th- and 3rd-order) and combines their norms
// (Scheme::combine), the force-weighted ones the same way.
// Step size by Hairer's PI controller (the scheme's exponent, beta and step-ratio limits), stiffness
// detection by the same codes' test (h |lambda| beyond the stability boundary for 15 steps).
//
// The stepper keeps its own integration state ahead of the reported one: step() moves the reported
// state by exactly one output interval (time_step) and fills it by the dense output, so the output
// grid never shortens the integration steps.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>

#include <Eigen/Core>
#include <Eigen/LU>

#include "camfollower/core/system.hpp"
#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/dop853_tableau.hpp"
#include "camfollower/solver/error_scales.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/first_order.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

// The Dormand-Prince 5(4) tableau (FSAL: the seventh stage is the next step's first) and Hairer's
// dense-output coefficients.
namespace dopri5 {
inline constexpr std::array<double, 7> c{0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0};
inline constexpr double a[7][6] = {
    {0, 0, 0, 0, 0, 0},
    {1.0 / 5.0, 0, 0, 0, 0, 0},
    {3.0 / 40.0, 9.0 / 40.0, 0, 0, 0, 0},
    {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0, 0, 0},
    {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0, 0},
    {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0},
    {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}};
// Fifth-order weights are the last row of a; e = b5 - b4 gives the embedded error estimate.
inline constexpr std::array<double, 7> e{71.0 / 57600.0,      0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                                         -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};
inline constexpr std::array<double, 7> d{-12715105075.0 / 11282082432.0,  0.0,
                                         87487479700.0 / 32700410799.0,   -10690763975.0 / 1880347072.0,
                                         701980252875.0 / 199316789632.0, -1453857185.0 / 822651844.0,
                                         69997945.0 / 29380423.0};

// What EmbeddedRungeKutta needs of a scheme. The stages are numbered from 0; the last of a step's
// `stages` is f at the solution (its input row of `a` holds the weights b), the next step's first
// (FSAL), and the one before it also ends at c = 1 (the stiffness test compares the two).
struct Scheme {
    static constexpr const char* name = "Dormand-Prince";  // in error messages
    static constexpr Method method = Method::dormand_prince;
    static constexpr int order = 5;         // of the solution
    static constexpr int stages = 7;        // evaluated each step (the first reused)
    static constexpr int dense_stages = 0;  // more, for the dense output
    static constexpr auto& c = dopri5::c;
    static constexpr auto& a = dopri5::a;
    // The error estimates, h sum_i e[k][i] k_i, and their norms' combination.
    static constexpr std::array<std::array<double, 7>, 1> e{{dopri5::e}};
    static double combine(const std::array<double, 1>& norm) { return norm[0]; }
    // Dense output: y0 + th (y1 - y0 + (1 - th) (... )) with rows d (Hairer's CONTD5, below).
    static constexpr std::array<std::array<double, 7>, 1> d{{dopri5::d}};
    // PI controller: h_new = h / clamp(err^exponent / err_old^beta / 0.9, 1 / grow_max, shrink_max).
    static constexpr double exponent = 0.17, beta = 0.04, grow_max = 10.0, shrink_max = 5.0;
    // The stability boundary on the negative real axis is ~3.3.
    static constexpr double stiffness_bound = 3.25;
};
}  // namespace dopri5

// Dormand-Prince 8(5,3) (solver/dop853_tableau.hpp), as in Hairer's DOP853.
namespace dop853 {
struct Scheme {
    static constexpr const char* name = "DOP853";
    static constexpr Method method = Method::dop853;
    static constexpr int order = 8;
    static constexpr int stages = step_stages;  // 12 and f at the solution (FSAL)
    static constexpr int dense_stages = all_stages - step_stages;
    static constexpr auto& c = dop853::c;
    static constexpr auto& a = dop853::a;
    static constexpr std::array<std::array<double, step_stages>, 2> e{{e5, e3}};
    // Hairer's estimate err5^2 / sqrt(err5^2 + 0.01 err3^2): ~h^8 as h -> 0 like the method's own
    // error (err5 alone is ~h^6, err3 ~h^4), yet never above err5.
    static double combine(const std::array<double, 2>& norm) {
        const double den = norm[0] * norm[0] + 0.01 * norm[1] * norm[1];
        return den == 0.0 ? 0.0 : norm[0] * norm[0] / std::sqrt(den);  // (NaN stays NaN: a blow-up)
    }
    static constexpr auto& d = dop853::d;
    static constexpr double exponent = 1.0 / 8.0, beta = 0.0, grow_max = 6.0, shrink_max = 1.0 / 0.333;
    // The stability boundary on the negative real axis is ~6.4; 6.1 is Hairer's threshold.
    static constexpr double stiffness_bound = 6.1;
};
}  // namespace dop853

template <class System, class Scheme>
class EmbeddedRungeKutta : public FirstOrderStepper<EmbeddedRungeKutta<System, Scheme>, System> {
    using Base = FirstOrderStepper<EmbeddedRungeKutta<System, Scheme>, System>;
    friend Base;
    static constexpr std::size_t S = std::size_t(Scheme::stages);            // a step's stages
    static constexpr std::size_t K = S + std::size_t(Scheme::dense_stages);  // with the dense output's
    static constexpr std::size_t E = std::size(Scheme::e);                   // error estimates
    static constexpr std::size_t R = 4 + std::size(Scheme::d);               // dense-output coefficients

public:
    using typename Base::Matrix;
    using typename Base::StateType;
    using typename Base::Vector;
    // h |lambda| beyond this (the scheme's stability boundary on the negative real axis) on
    // `stiff_run` successive steps: the step is bounded by stability, not by accuracy.
    static constexpr double stiffness_bound = Scheme::stiffness_bound;
    static constexpr int stiff_run = 15;

    EmbeddedRungeKutta(const System& system, const SolverSettings& settings)
        : Base(system, settings, Scheme::method, Scheme::name) {
        for (Vector* x : {&qs_, &vs_, &ql_, &vl_, &qd_, &vd_, &ef_, &dq_, &dv_, &cq_, &cv_, &cq_trial_, &cv_trial_})
            x->resize(n_);
        auto resize = [this](auto&... sets) {
            (..., [this](auto& set) {
                for (Vector& x : set) x.resize(n_);
            }(sets));
        };
        resize(eq_, ev_, kq_, kv_, rq_, rv_);
    }
    EmbeddedRungeKutta(System&&, const SolverSettings&) = delete;

private:
    using Base::acceleration, Base::reaches;
    using Base::system_, Base::s_, Base::adaptive_, Base::tolerance_, Base::n_, Base::force_scale_, Base::t_,
        Base::t_start_, Base::fixed_steps_, Base::ws_, Base::scales_, Base::q_, Base::v_, Base::f_, Base::uvq_,
        Base::uvv_, Base::events_;

    // FirstOrderStepper's hooks: the start after the shared one, a step, the dense output.
    void restart(const StateType& s) {
        cq_.setZero(), cv_.setZero(), ct_ = 0.0;
        kq_[0] = v_, kv_[0] = s.a;
        h_ = initial_step(s.a);
        t_old_ = t_, h_last_ = 0.0, err_old_ = 1e-4;
        stiff_count_ = 0, non_stiff_count_ = 0;
        event_retake_ = false, dense_ready_ = false;
        if constexpr (K > S) dense_ws_ = ws_;  // (its copies in the loop then reuse this one's storage)
    }
    void advance(double target, SolverStatistics& stats) { take_step(target, stats); }
    void dense_output(double t, Vector& q, Vector& v) const { interpolate(t, q, v); }

    // Stage derivative at (t, q, v): kq = v, kv = a.
    void derivative(double t, const Vector& q, const Vector& v, Vector& kq, Vector& kv, workspace_t<System>& ws,
                    SolverStatistics& stats) {
        prepare(system_, t, ws);
        nonlinear_force(system_, ws, q, v, f_);
        kq = v;
        acceleration(q, v, f_, kv);
        ++stats.evaluations;
    }

    // Stage i of the step [t_, t_ + h]: its input (q, v) = y + h sum_j a_ij k_j, then k_i. The last
    // step stage's input is the solution, summed with compensation (solution_with_compensation).
    void stage(std::size_t i, double h, Vector& q, Vector& v, workspace_t<System>& ws, SolverStatistics& stats) {
        if (i + 1 == S) {
            solution_with_compensation(h, q, v);
            derivative(t_ + Scheme::c[i] * h, q, v, kq_[i], kv_[i], ws, stats);
            return;
        }
        q = q_;
        v = v_;
        for (std::size_t j = 0; j < i; ++j) {
            const double w = h * Scheme::a[i][j];
            if (w == 0.0) continue;
            q.noalias() += w * kq_[j];
            v.noalias() += w * kv_[j];
        }
        derivative(t_ + Scheme::c[i] * h, q, v, kq_[i], kv_[i], ws, stats);
    }

    // y1 = y0 + (h sum_j b_j k_j + c0) by compensated summation (Kahan; Hairer, Lubich & Wanner,
    // Geometric Numerical Integration, VIII.5): c1 = the part of the sum rounding dropped, carried
    // into the next step. Plain y0 + increment loses ~eps |y0| per step, and over 10^5 steps that walk
    // drives a stiff, barely damped contact mode far above the tolerance (docs/benchmarks.md): the
    // rounding of a 1e-2 m coordinate is ~1e-10 of the peak force through a 1.9e10 N/m contact.
    // TwoSum (any magnitudes), so it holds while a coordinate passes through zero.
    void solution_with_compensation(double h, Vector& q, Vector& v) {
        dq_ = cq_;
        dv_ = cv_;
        for (std::size_t j = 0; j + 1 < S; ++j) {
            const double w = h * Scheme::a[S - 1][j];
            if (w == 0.0) continue;
            dq_.noalias() += w * kq_[j];
            dv_.noalias() += w * kv_[j];
        }
        two_sum(q_, dq_, q, cq_trial_);
        two_sum(v_, dv_, v, cv_trial_);
    }
    // rounded(x + y), error = x + y - rounded(x + y) exactly (Knuth's TwoSum, six operations).
    static double two_sum(double x, double y, double& error) {
        const double sum = x + y;
        const double y_part = sum - x;
        error = (x - (sum - y_part)) + (y - y_part);
        return sum;
    }
    static void two_sum(const Vector& x, const Vector& y, Vector& sum, Vector& error) {
        for (int k = 0; k < x.size(); ++k) sum[k] = two_sum(x[k], y[k], error[k]);
    }

    double error_norm_qv(const Vector& eq, const Vector& ev, const Vector& q0, const Vector& v0, const Vector& q1,
                         const Vector& v1) const {
        return scales_.mixed(tolerance_, eq, ev, q0, v0, q1, v1);
    }

    // Hairer's starting step: from the sizes of y, y' and an estimate of y''.
    double initial_step(const Vector& a0) {
        SolverStatistics scratch;
        Vector zero = Vector::Zero(n_);
        const double d0 = error_norm_qv(q_, v_, zero, zero, zero, zero);
        const double d1 = error_norm_qv(v_, a0, zero, zero, zero, zero);
        double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
        h0 = std::min(h0, s_.time_step * 100.0);
        qs_ = q_ + h0 * v_;
        vs_ = v_ + h0 * a0;
        derivative(t_ + h0, qs_, vs_, kq_[1], kv_[1], ws_, scratch);
        eq_[0] = (kq_[1] - v_) / h0;
        ev_[0] = (kv_[1] - a0) / h0;
        const double d2 = error_norm_qv(eq_[0], ev_[0], zero, zero, zero, zero);
        const double dm = std::max(d1, d2);
        const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 1.0 / Scheme::order);
        prepare(system_, t_, ws_);  // the workspace back at the integration time
        return std::min(100.0 * h0, h1);
    }

    // One accepted step of the integration state (rejected attempts retried with a smaller step);
    // `target`: the next output time (the step reaching it prepares the dense output).
    void take_step(double target, SolverStatistics& stats) {
        const double min_step = 1e-14 * std::max(1.0, std::abs(t_));
        for (;;) {
            double h = h_;
            if (s_.max_step > 0.0) h = std::min(h, s_.max_step);
            if (!adaptive_) h = s_.max_step;  // fixed steps (FirstOrderStepper requires max_step without a tolerance)
            if (!(h >= min_step))
                throw ConvergenceError(detail::concat(
                    Scheme::name, ": the step fell to ", h, " s at t = ", t_, " s without meeting tolerance = ",
                    tolerance_, " (the response is not smooth there, or the tolerance is below rounding)"));
            dense_ready_ = false;
            // Stages 1 ... S - 1 (stage 0 is the previous step's last: FSAL); the one before the last
            // is kept for the stiffness test, the last's input is the solution.
            for (std::size_t i = 1; i < S; ++i) {
                stage(i, h, qs_, vs_, ws_, stats);
                if (i == S - 2) ql_ = qs_, vl_ = vs_;
            }
            // Embedded errors, in the mixed norm and weighted by the forces.
            std::array<double, E> mixed{}, force{};
            for (std::size_t k = 0; k < E; ++k) {
                eq_[k].setZero();
                ev_[k].setZero();
                for (std::size_t i = 0; i < S; ++i) {
                    const double w = h * Scheme::e[k][i];
                    if (w == 0.0) continue;
                    eq_[k].noalias() += w * kq_[i];
                    ev_[k].noalias() += w * kv_[i];
                }
                mixed[k] = error_norm_qv(eq_[k], ev_[k], q_, v_, qs_, vs_);
            }
            force_errors(qs_, vs_, force);
            double err = std::max(Scheme::combine(mixed), Scheme::combine(force) / (tolerance_ * force_scale_));
            if (!std::isfinite(err)) err = 1e10;
            if (!adaptive_) {
                if (err == 1e10)
                    throw ConvergenceError(detail::concat(Scheme::name, ": the state became non-finite at t = ", t_,
                                                          " s with the fixed step ", h,
                                                          " s: the step is beyond the stability limit"));
                err = 0.5;
            }
            // Hairer's PI step-size controller.
            const double fac11 = std::pow(err, Scheme::exponent);
            if (err <= 1.0) {
                double fac = fac11 / std::pow(err_old_, Scheme::beta) / 0.9;
                fac = std::clamp(fac, 1.0 / Scheme::grow_max, Scheme::shrink_max);
                double h_new = h / fac;
                if constexpr (has_events_v<System>) {
                    if (end_at_crossing(h, h_new, stats)) continue;
                }
                err_old_ = std::max(err, 1e-4);
                stiffness_test(h, stats);
                accept(h, target, stats);
                h_ = rejected_last_ ? std::min(h_new, h) : h_new;
                rejected_last_ = false;
                return;
            }
            h_ = h / std::min(Scheme::shrink_max, fac11 / 0.9);
            rejected_last_ = true;
            event_retake_ = false;
            ++stats.rejected_steps;  // the next attempt's stages prepare the workspace again
        }
    }

    // Events of the trial step [t_, t_ + h] (error accepted): when a switching function changed sign
    // inside it, sets up the retake ending just past the earliest crossing and returns true; else
    // records the crossings found (a retake's own, at its end) and returns false. The step after a
    // crossing starts from the size the controller had before it (the retake may be a sliver).
    bool end_at_crossing(double h, double& h_new, SolverStatistics& stats) {
        if (events_.changed(ws_, qs_, vs_)) {
            dense_coefficients(h, stats);
            auto path = [&](double t, Vector& q, Vector& v) { interpolate_on(t, t_, h, q, v); };
            const Crossing first = events_.earliest(t_, t_ + h, path);
            // A crossing within a millionth of the step from its start is left inside: its error,
            // ~ (1e-6 h)^2 times the force's kink, is below any tolerance.
            if (adaptive_ && !event_retake_ && first.beyond < t_ + h && first.beyond - t_ > 1e-6 * h) {
                event_retake_ = true;
                h_before_event_ = h_new;
                h_ = first.beyond - t_;
                return true;
            }
            events_.record(first, ws_);
            while (const Crossing c = events_.earliest(t_, t_ + h, path)) events_.record(c, ws_);
        }
        if (event_retake_) h_new = std::max(h_new, h_before_event_), rejected_last_ = false;
        event_retake_ = false;
        return false;
    }

    // |K_t e_q + C_t e_v|_inf of each error estimate, with the contacts' tangent at the new state (the
    // last stage evaluated it). DOP853 weighs both its estimates and combines them like their mixed
    // norms: the force test then also scales like the method's error (~h^8), as the controller's
    // exponent 1/8 assumes; its 5th-order estimate alone (~h^6) would hold the steps far below what
    // the tolerance asks wherever the force test decides.
    void force_errors(const Vector& q1, const Vector& v1, std::array<double, E>& out) {
        tangent(system_, ws_, q1, v1, 1.0, 0.0, uvq_);
        tangent(system_, ws_, q1, v1, 0.0, 1.0, uvv_);
        for (std::size_t k = 0; k < E; ++k) out[k] = force_error(system_, uvq_, uvv_, eq_[k], ev_[k], ef_);
    }

    // Hairer's test: h |lambda| ~ h |k_S-1 - k_S-2| / |y_S-1 - y_S-2| (both stages at c = 1) beyond
    // the stability boundary.
    void stiffness_test(double h, SolverStatistics& stats) {
        const double num = (kq_[S - 1] - kq_[S - 2]).squaredNorm() + (kv_[S - 1] - kv_[S - 2]).squaredNorm();
        const double den = (qs_ - ql_).squaredNorm() + (vs_ - vl_).squaredNorm();
        if (den > 0.0 && h * std::sqrt(num / den) > stiffness_bound) {
            non_stiff_count_ = 0;
            if (++stiff_count_ >= stiff_run) ++stats.stiff_steps;
        } else if (++non_stiff_count_ >= 6) {
            stiff_count_ = 0;
        }
    }

    // Dense output coefficients (Hairer's CONTD5 / CONTD8) of the step [t_, t_ + h] just computed,
    // once per step. DOP853's three extra stages run on a copy of the workspace: the step's own keeps
    // the force at the new state, which accepted() and the event watch read.
    void dense_coefficients(double h, SolverStatistics& stats) {
        if (dense_ready_) return;
        if constexpr (K > S) {
            dense_ws_ = ws_;
            for (std::size_t i = S; i < K; ++i) stage(i, h, qd_, vd_, dense_ws_, stats);
        }
        rq_[0] = q_, rv_[0] = v_;
        rq_[1] = qs_ - q_, rv_[1] = vs_ - v_;
        rq_[2] = h * kq_[0] - rq_[1], rv_[2] = h * kv_[0] - rv_[1];
        rq_[3] = rq_[1] - h * kq_[S - 1] - rq_[2], rv_[3] = rv_[1] - h * kv_[S - 1] - rv_[2];
        for (std::size_t r = 4; r < R; ++r) {
            rq_[r].setZero(), rv_[r].setZero();
            for (std::size_t i = 0; i < K; ++i) {
                const double w = h * Scheme::d[r - 4][i];
                if (w == 0.0) continue;
                rq_[r].noalias() += w * kq_[i];
                rv_[r].noalias() += w * kv_[i];
            }
        }
        dense_ready_ = true;
    }

    void accept(double h, double target, SolverStatistics& stats) {
        // Fixed steps: time as t0 + n h (a sum drifts by ulps, off the output grid); adaptive ones
        // compensated like the state (the cam's motion turns a drifting time into a drifting input).
        double t_new = t_start_ + double(fixed_steps_ + 1) * h;
        if (adaptive_) t_new = two_sum(t_, h + ct_, ct_);
        if (reaches(t_new, target)) dense_coefficients(h, stats);  // step() interpolates in this step
        t_old_ = t_, h_last_ = h, t_ = t_new;
        if (!adaptive_) ++fixed_steps_;
        q_ = qs_, v_ = vs_;
        cq_ = cq_trial_, cv_ = cv_trial_;
        kq_[0] = kq_[S - 1], kv_[0] = kv_[S - 1];  // FSAL; the workspace holds the force at the new state
        scales_.update(q_, v_);
        accepted(system_, ws_, q_, v_);
        ++stats.steps;
    }

    // The dense output at time t in [t_old_, t_] (the last accepted step).
    void interpolate(double t, Vector& q, Vector& v) const { interpolate_on(t, t_old_, h_last_, q, v); }
    // y0 + th (r1 + (1 - th) (r2 + th (r3 + (1 - th) (r4 + ...)))), th = (t - t0) / h.
    void interpolate_on(double t, double t0, double h, Vector& q, Vector& v) const {
        const double th = h > 0.0 ? (t - t0) / h : 1.0, th1 = 1.0 - th;
        q = rq_[R - 1], v = rv_[R - 1];
        for (std::size_t j = R - 1; j-- > 0;) {
            const double w = j % 2 == 0 ? th : th1;
            q *= w, v *= w;
            q += rq_[j], v += rv_[j];
        }
    }

    // The integration state (ahead of the reported one) beyond the shared part.
    double t_old_ = 0.0, h_ = 0.0, h_last_ = 0.0, err_old_ = 1e-4;
    double ct_ = 0.0;  // the time's compensation (adaptive steps)
    bool rejected_last_ = false;
    bool event_retake_ = false;  // the step being taken ends at a located crossing
    bool dense_ready_ = false;   // rq_, rv_ hold the dense output of the step last computed
    double h_before_event_ = 0.0;
    int stiff_count_ = 0, non_stiff_count_ = 0;
    workspace_t<System> dense_ws_;
    // Scratch, sized once: nothing is allocated inside the time loop.
    Vector qs_, vs_, ql_, vl_, qd_, vd_, ef_;
    Vector dq_, dv_, cq_, cv_, cq_trial_, cv_trial_;  // the solution's increment and compensation
    std::array<Vector, E> eq_, ev_;
    std::array<Vector, K> kq_, kv_;
    std::array<Vector, R> rq_, rv_;
};

template <class System>
using DormandPrince = EmbeddedRungeKutta<System, dopri5::Scheme>;
template <class System>
using Dop853 = EmbeddedRungeKutta<System, dop853::Scheme>;

}  // namespace camfollower
