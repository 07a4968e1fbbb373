// SPDX-License-Identifier: BSD-3-Clause
// The largest stable step of a conditionally stable Newmark scheme (beta < gamma / 2) on a system,
// damping included. Plain Newmark with gamma = 1/2 is stable below omega_max dt = 1 / sqrt(1/4 - beta)
// whatever the damping. Its processed velocity (NewmarkParameters::processed: Fox-Goodwin and the
// studies' period-matched scheme) is not: the jerk it subtracts comes from the last three
// accelerations, explicitly, and through a damper it feeds back. A lightly damped mode loses a little
// of the limit (damping ratio 0.1: omega dt < 2.26 instead of 2.45 for Fox-Goodwin), a heavily damped
// one most of it (c dt < about 3, c = 2 zeta omega its damping rate): a stiffness-proportional
// damping on a finely meshed shaft puts c at 10^7 / s, and Fox-Goodwin grew without bound on the
// valve-train preset at steps well within the undamped limit (docs/solvers.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

// Spectral radius of one constant step dt of processed Newmark (gamma = 1/2, beta) on a mode
// a + c v + omega^2 q = 0 (mass-normalized; c = 2 zeta omega, 1/s), in the step's own units (dt = 1:
// it depends on omega dt and c dt alone, and the matrix stays well scaled). The step's state is (q, vN,
// a, a_prev), vN the trapezoidal velocity; the damping sees v = vN - dt^2 / 12 a', a' = (3 a - 4 a_prev
// + a_prev2) / (2 dt) (docs/solvers.md, "Fourth order with damping").
inline double processed_mode_amplification(double beta, double omega_dt, double c_dt) {
    const double w2 = omega_dt * omega_dt, c = c_dt;
    Eigen::Matrix4d A;
    for (int j = 0; j < 4; ++j) {
        const Eigen::Vector4d e = Eigen::Vector4d::Unit(j);
        const double q = e[0], vN = e[1], a = e[2], a_prev = e[3];
        // v1 = vN + (a + a1) / 2 - (3 a1 - 4 a + a_prev) / 24: 3/8 of the new acceleration.
        const double rest = c * (vN + (0.5 + 1.0 / 6.0) * a - a_prev / 24.0) + w2 * (q + vN + (0.5 - beta) * a);
        const double a1 = -rest / (1.0 + processed_damping_gamma * c + w2 * beta);
        A.col(j) << q + vN + (0.5 - beta) * a + beta * a1, vN + 0.5 * (a + a1), a1, a;
    }
    return Eigen::EigenSolver<Eigen::Matrix4d>(A, false).eigenvalues().cwiseAbs().maxCoeff();
}

// A spectral radius above 1 + this is growth (above the rounding of a unit-circle root).
inline constexpr double processed_growth = 1e-9;

// The largest dt (s) at which processed Newmark (gamma = 1/2, beta < 1/4) is stable on that mode, no
// margin; +inf for a mode without stiffness or damping. The stable steps are [0, limit]: the limit is
// found by bisection to 1e-6 relative between a stable step and an unstable one.
inline double processed_mode_step_limit(double beta, double omega, double c) {
    const auto stable = [&](double dt) {
        return processed_mode_amplification(beta, omega * dt, c * dt) <= 1.0 + processed_growth;
    };
    if (!(omega > 0.0) && !(c > 0.0)) return std::numeric_limits<double>::infinity();
    // Undamped, the limit is plain Newmark's, 1 / (omega sqrt(1/4 - beta)); damping only lowers it. A
    // mode of damping alone is stable up to c dt of about 3.
    double hi = omega > 0.0 ? 1.0 / (omega * std::sqrt(0.25 - beta)) : 8.0 / c;
    if (stable(hi)) return hi;
    double lo = 0.0;
    while (hi - lo > 1e-6 * hi) {
        const double mid = 0.5 * (lo + hi);
        (stable(mid) ? lo : hi) = mid;
    }
    return lo;
}

// The step limit of a run and the mode that sets it.
struct StepLimit {
    double step = std::numeric_limits<double>::infinity();  // s, with step_limit_margin
    double omega = 0.0;                                     // rad/s, the mode's undamped angular frequency
    double damping_ratio = 0.0;                             // the mode's c / (2 omega)
};

namespace detail {
// A figure for a reason in words: 4 significant digits.
inline std::string figure(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return text;
}
}  // namespace detail

// The mode that sets `limit`, in words (error messages, method auto's reason).
inline std::string step_limit_reason(const StepLimit& limit, const NewmarkParameters& p) {
    const std::string hz = detail::figure(limit.omega / (2.0 * pi));
    if (!p.processed) return "highest mode " + hz + " Hz";
    return "velocity processed to fourth order: the mode at " + hz + " Hz with damping ratio " +
           detail::figure(limit.damping_ratio) + " sets it";
}

// The stability of Newmark with parameters p on `system` linearized at state s (contacts' stiffness
// and damping tangents). Processed: each mode of the undamped problem (K_t, M) with its modal damping
// phi' C_t phi (the coupling of modes through damping left out). Allocates (an n x n eigen problem,
// with vectors when processed); build once per run.
class StepLimitTest {
public:
    template <class System>
    StepLimitTest(const System& system, const State<System>& s, const NewmarkParameters& p) : p_(p) {
        if (p.beta >= 0.5 * p.gamma) return;
        if (!p.processed) {
            omega_max_ = highest_angular_frequency(system, s);
            return;
        }
        using Matrix = typename System::Matrix;
        const int n = system.size();
        LowRank<typename System::Vector> uvq(n, std::max(1, max_rank(system))), uvv(n, std::max(1, max_rank(system)));
        uvq.clear(), uvv.clear();
        tangent(system, s.workspace, s.q, s.v, 1.0, 0.0, uvq);
        tangent(system, s.workspace, s.q, s.v, 0.0, 1.0, uvv);
        const Matrix tq = uvq.U.leftCols(uvq.rank) * uvq.V.leftCols(uvq.rank).transpose();
        const Matrix tv = uvv.U.leftCols(uvv.rank) * uvv.V.leftCols(uvv.rank).transpose();
        const Matrix Kt = system.stiffness() + 0.5 * (tq + tq.transpose());
        const Matrix Ct = system.damping() + 0.5 * (tv + tv.transpose());
        const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Kt, system.mass());
        if (eig.info() != Eigen::Success) return;
        omega_.resize(eig.eigenvalues().size()), c_.resize(eig.eigenvalues().size());
        for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
            const auto phi = eig.eigenvectors().col(k);  // mass-normalized
            omega_[k] = std::sqrt(std::max(eig.eigenvalues()[k], 0.0));
            c_[k] = std::max(phi.dot(Ct * phi), 0.0);
        }
    }

    // dt is within the limit (with step_limit_margin): one spectral radius per mode when processed.
    bool allows(double dt) const {
        if (p_.beta >= 0.5 * p_.gamma) return true;
        if (!p_.processed) return !std::isfinite(omega_max_) || dt <= newmark_step_limit(p_.gamma, p_.beta, omega_max_);
        for (Eigen::Index k = 0; k < omega_.size(); ++k)
            if (!(processed_mode_amplification(p_.beta, omega_[k] * dt / step_limit_margin,
                                               c_[k] * dt / step_limit_margin) <= 1.0 + processed_growth))
                return false;
        return true;
    }

    // The largest stable step, with step_limit_margin, and the mode that sets it (+inf when p is
    // unconditionally stable); processed: a bisection per mode (processed_mode_step_limit).
    StepLimit limit() const {
        StepLimit out;
        if (p_.beta >= 0.5 * p_.gamma) return out;
        if (!p_.processed) {
            out.omega = omega_max_;
            if (std::isfinite(omega_max_)) out.step = newmark_step_limit(p_.gamma, p_.beta, omega_max_);
            return out;
        }
        double smallest = std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 0; k < omega_.size(); ++k) {
            const double mode_limit = processed_mode_step_limit(p_.beta, omega_[k], c_[k]);
            if (mode_limit < smallest) {
                smallest = mode_limit;
                out.omega = omega_[k];
                out.damping_ratio = omega_[k] > 0.0 ? 0.5 * c_[k] / omega_[k] : std::numeric_limits<double>::infinity();
            }
        }
        out.step = step_limit_margin * smallest;
        return out;
    }

private:
    NewmarkParameters p_;
    double omega_max_ = std::numeric_limits<double>::quiet_NaN();  // unprocessed: the highest mode
    Eigen::VectorXd omega_, c_;                                    // processed: the modes, their damping
};

// The largest stable step of Newmark with parameters p on `system` linearized at state s, with
// step_limit_margin, and the mode that sets it (StepLimitTest::limit).
template <class System>
StepLimit step_limit(const System& system, const State<System>& s, const NewmarkParameters& p) {
    return StepLimitTest(system, s, p).limit();
}

// Refuses a fixed time_step beyond the step limit of p at s0 (the Newmark backends, at the start).
template <class System>
void check_step_limit(const System& system, const State<System>& s0, const NewmarkParameters& p, double time_step) {
    const StepLimitTest test(system, s0, p);
    if (test.allows(time_step)) return;
    const StepLimit limit = test.limit();
    detail::fail("time_step = ", time_step, " s exceeds the stability limit ", limit.step,
                 " s of Newmark with beta = ", p.beta, " < gamma / 2 (", step_limit_reason(limit, p),
                 "); reduce time_step, use beta = 1/4 or method 'auto'");
}

// A Fox-Goodwin-type run (a processed velocity, NewmarkParameters::processed) made stable where it can:
// on the sparse backend, and at a fixed step beyond the processed velocity's limit but within the
// trapezoidal velocity's (the undamped limit), sets s.process_velocity = false (second order through
// the dampers, Fox-Goodwin's fourth-order period error kept) and returns why; else returns "" and
// leaves s (beyond both limits the stepper refuses the step). Under a tolerance the steps stay within
// the processed velocity's limit instead. Allocates (step_limit); call once per run.
template <class System>
std::string choose_velocity(const System& system, SolverSettings& s, const State<System>& start, bool sparse) {
    const NewmarkParameters p = newmark_parameters(s);
    if (!p.processed) return "";
    if (sparse) {
        s.process_velocity = false;
        return "trapezoidal velocity: the sparse backend does not process it (second order through the dampers)";
    }
    if (s.tolerance) return "";
    const StepLimitTest processed_test(system, start, p);
    if (processed_test.allows(s.time_step)) return "";
    SolverSettings plain = s;
    plain.process_velocity = false;
    const NewmarkParameters q = newmark_parameters(plain);
    const StepLimit trapezoidal = step_limit(system, start, q);
    if (s.time_step > trapezoidal.step) return "";
    const StepLimit processed = processed_test.limit();
    s = plain;
    return "trapezoidal velocity (second order through the dampers): time_step " + detail::figure(s.time_step) +
           " s is beyond the processed velocity's stability limit " + detail::figure(processed.step) + " s (" +
           step_limit_reason(processed, p) + ") and within the trapezoidal one's " + detail::figure(trapezoidal.step) +
           " s (" + step_limit_reason(trapezoidal, q) + ")";
}

}  // namespace camfollower
