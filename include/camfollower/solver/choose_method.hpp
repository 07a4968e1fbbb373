// SPDX-License-Identifier: BSD-3-Clause
// Method "auto" made concrete at the start of a run, with the reason in words:
//   at a fixed time_step (no tolerance): Fox-Goodwin within its stability limit, else
//   average-acceleration Newmark;
//   under a tolerance: radau when the model's fastest modes are damped,
//   or when the fastest rings alone (a stiff contact) at tolerances of 1e-7 and looser; else
//   Fox-Goodwin at tolerances of 1e-5 and looser, dop853 below.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include <Eigen/Eigenvalues>

#include "camfollower/error.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"
#include "camfollower/solver/step_limit.hpp"

namespace camfollower {

// A mode of the linearized first-order system x' = J x, x = (q, v), J = [0 I; -M^-1 K_t  -M^-1 C_t]:
// rate |lambda| (rad/s) and damping ratio -Re(lambda) / |lambda| (1 for a real, decaying root).
struct ModeRate {
    double rate = 0.0, damping_ratio = 0.0;
};
// Above this damping ratio a mode decays within about a period instead of ringing.
inline constexpr double ringing_damping_ratio = 0.3;
// A fastest ringing mode this many times faster than the next is a stiff spring the motion loads
// quasi-statically (a stiff contact); at tolerances down to isolated_mode_tolerance its oscillation
// need not be resolved (measured: docs/solvers.md).
inline constexpr double isolated_mode_ratio = 3.0;
inline constexpr double isolated_mode_tolerance = 1e-7;
// Above this tolerance radau, when chosen, has its steps bounded by the output interval (max_step).
inline constexpr double radau_long_step_tolerance = 1e-5;
// Where the fastest modes ring, Fox-Goodwin (fourth order, one Newton solve per step) at tolerances
// down to this, dop853 (eighth order, 12 evaluations per step) below (measured: docs/benchmarks.md).
inline constexpr double fox_goodwin_tolerance = 1e-5;
// Fox-Goodwin so chosen steps down to time_step / 2^this at least (its levels cost one factorization
// each, at construction): the output interval alone does not bound how fine a ringing mode needs.
inline constexpr int fox_goodwin_halvings = 12;
// The two fastest ringing modes (damping ratio below ringing_damping_ratio) and the fastest damped
// one (at or above it) of `system` with its contacts' tangent (stiffness and damping) at state s,
// each complex pair counted once; a rate of 0 where there is none. Allocates (a 2n x 2n eigenvalue
// problem); call once per run.
struct FastestModes {
    ModeRate ringing, next_ringing, damped;
};
template <class System>
FastestModes fastest_modes(const System& system, const State<System>& s) {
    const int n = system.size();
    LowRank<typename System::Vector> uvq(n, std::max(1, max_rank(system))), uvv(n, std::max(1, max_rank(system)));
    uvq.clear(), uvv.clear();
    tangent(system, s.workspace, s.q, s.v, 1.0, 0.0, uvq);
    tangent(system, s.workspace, s.q, s.v, 0.0, 1.0, uvv);
    Eigen::MatrixXd Kt = system.stiffness(), Ct = system.damping();
    for (int r = 0; r < uvq.rank; ++r) Kt += uvq.U.col(r) * uvq.V.col(r).transpose();
    for (int r = 0; r < uvv.rank; ++r) Ct += uvv.U.col(r) * uvv.V.col(r).transpose();
    const Eigen::PartialPivLU<Eigen::MatrixXd> mass(Eigen::MatrixXd(system.mass()));
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    J.topRightCorner(n, n).setIdentity();
    J.bottomLeftCorner(n, n) = -mass.solve(Kt);
    J.bottomRightCorner(n, n) = -mass.solve(Ct);
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(J, false);
    FastestModes out;
    if (eig.info() != Eigen::Success) return out;
    for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
        const std::complex<double> lambda = eig.eigenvalues()[k];
        const double rate = std::abs(lambda);
        if (!(rate > 0.0) || lambda.imag() < 0.0) continue;
        const ModeRate mode{rate, -lambda.real() / rate};
        if (mode.damping_ratio >= ringing_damping_ratio) {
            if (rate > out.damped.rate) out.damped = mode;
        } else if (rate > out.ringing.rate) {
            out.next_ringing = out.ringing, out.ringing = mode;
        } else if (rate > out.next_ringing.rate) {
            out.next_ringing = mode;
        }
    }
    return out;
}

// The method a run with `s` uses, and why, in words (RunResult::method_choice).
struct MethodChoice {
    SolverSettings settings;
    std::string reason;    // empty when the method was named
    std::string velocity;  // choose_velocity's reason: empty unless it kept the trapezoidal velocity
};

// Method "auto" made concrete for a run starting at `start`; other methods are returned as they are.
//  - no tolerance: Fox-Goodwin when time_step is within its stability limit there (at equal cost per
//    step it is 50x to 1000x more accurate in contact force than average acceleration on the paper
//    preset, docs/benchmarks.md), else average-acceleration Newmark (unconditionally stable). Above
//    200 DOFs the highest mode is not computed: average acceleration.
//  - under a tolerance: radau (L-stable: it steps over what it need not resolve) when a damped mode
//    (damping ratio >= 0.3) is at least half as fast as the fastest ringing one, or when the fastest
//    ringing mode is isolated_mode_ratio times faster than the next at tolerances of
//    isolated_mode_tolerance and looser; else fox_goodwin at tolerances of fox_goodwin_tolerance and
//    looser (its error per radian is held across output intervals, docs/solvers.md; on the paper
//    preset at 1e-4 and 1e-5 it is twice as fast as dop853 and 40 to 80 times as accurate), dop853
//    (order 8, no linear solves) below. Above 200 DOFs the spectrum is not computed: dop853. Radau
//    chosen at a tolerance above 1e-5 gets max_step = time_step (the output interval) unless
//    max_step is set; fox_goodwin gets max_halvings >= fox_goodwin_halvings.
template <class System>
MethodChoice choose_method(const System& system, SolverSettings s, const State<System>& start) {
    if (s.method != Method::automatic) return {s, "", ""};
    // The reason starts with the method's own name (method_table), then `why`.
    const auto take = [&s](Method method, const std::string& why) {
        s.method = method;
        return MethodChoice{s, method_name(method) + why, ""};
    };
    if (!s.tolerance) {
        const std::string average = " (average acceleration): ";
        if (system.size() > 200)
            return take(Method::newmark,
                        detail::concat(average, system.size(), " DOFs, above 200 the highest mode is not computed"));
        // The trapezoidal velocity's limit (the undamped one): choose_velocity then keeps the processed
        // velocity where that is stable too.
        SolverSettings fox_goodwin = s;
        fox_goodwin.method = Method::fox_goodwin, fox_goodwin.process_velocity = false;
        const NewmarkParameters p = newmark_parameters(fox_goodwin);
        const StepLimit limit = step_limit(system, start, p);
        const std::string where = "time_step " + detail::figure(s.time_step) +
                                  " s against Fox-Goodwin's stability limit " + detail::figure(limit.step) + " s (" +
                                  step_limit_reason(limit, p) + ")";
        if (limit.omega >= 0.0 && s.time_step <= limit.step) return take(Method::fox_goodwin, ": " + where);
        return take(Method::newmark, average + where);
    }
    if (system.size() > 200)
        return take(Method::dop853,
                    detail::concat(": ", system.size(), " DOFs, above 200 the spectrum is not computed"));
    const FastestModes modes = fastest_modes(system, start);
    using detail::figure;
    const auto mode = [](const ModeRate& m) {
        return figure(m.rate / (2.0 * pi)) + " Hz at damping ratio " + figure(m.damping_ratio);
    };
    const std::string units = " (rates |lambda| / 2 pi)";
    // Radau's error estimate misjudges a long step across the start of a rise after a dwell at
    // tolerances above 1e-5 (100x the tolerance in force, docs/solvers.md): there its steps are
    // bounded by the output interval unless max_step says otherwise.
    const auto take_radau = [&s, &take](const std::string& why) {
        MethodChoice choice = take(Method::radau, why);
        if (*s.tolerance <= radau_long_step_tolerance || s.max_step > 0.0) return choice;
        choice.settings.max_step = s.time_step;
        choice.reason += "; max_step = the output interval " + figure(s.time_step) + " s (tolerance above " +
                         figure(radau_long_step_tolerance) + ")";
        return choice;
    };
    if (modes.damped.rate > 0.0 && modes.damped.rate >= 0.5 * modes.ringing.rate)
        return take_radau(": the fastest modes are damped: " + mode(modes.damped) + " (>= " +
                          figure(ringing_damping_ratio) + "), the fastest ringing mode " + mode(modes.ringing) + units);
    const double isolation = modes.next_ringing.rate > 0.0 ? modes.ringing.rate / modes.next_ringing.rate : 0.0;
    const std::string ringing = mode(modes.ringing) + ", " + figure(isolation) + " times the next ringing mode (" +
                                figure(modes.next_ringing.rate / (2.0 * pi)) + " Hz)";
    const bool isolated = isolation >= isolated_mode_ratio;
    if (isolated && *s.tolerance >= isolated_mode_tolerance)
        return take_radau(": the fastest mode rings alone, a stiff spring loaded quasi-statically: " + ringing +
                          " (>= " + figure(isolated_mode_ratio) + ", tolerance >= " + figure(isolated_mode_tolerance) +
                          ")" + units);
    const bool loose = *s.tolerance >= fox_goodwin_tolerance;
    if (loose) s.max_halvings = std::max(s.max_halvings, fox_goodwin_halvings);
    return take(loose ? Method::fox_goodwin : Method::dop853,
                ": the fastest modes ring: " + ringing +
                    (modes.damped.rate > 0.0 ? ", the fastest damped mode (>= " + figure(ringing_damping_ratio) + ") " +
                                                   mode(modes.damped) + ", below half that rate"
                                             : ", no mode damped at " + figure(ringing_damping_ratio) + " or more") +
                    units + (isolated ? "; tolerance < " + figure(isolated_mode_tolerance) : "") + "; tolerance " +
                    (loose ? ">= " : "< ") + figure(fox_goodwin_tolerance));
}

}  // namespace camfollower
