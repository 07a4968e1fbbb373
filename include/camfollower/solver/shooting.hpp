// SPDX-License-Identifier: BSD-3-Clause
// The periodic steady state of a periodically forced system (a camshaft at constant speed) found
// directly by shooting: Newton's method on the state z = (q, v) at the start of a revolution for the
// fixed point of the one-revolution map Phi of the time-stepping scheme,
//     R(z) = Phi(z) - z = 0,   (dPhi/dz - I) dz = -R(z),
// instead of simulating revolutions until the transient has died out (solver/settle.hpp). The
// monodromy matrix dPhi/dz comes from the scheme's variational equations carried through one
// revolution (solver/step_sensitivity.hpp: the Newmark family on the dense backend), else from
// forward differences (one revolution per state component, 2n in all). It is reused while the
// iterations converge quickly (chord iterations: one revolution each) and rebuilt when they do not;
// four Newton steps in a row that do not halve the best mismatch end the search (not periodic, or a
// tolerance below the rounding floor). Its eigenvalues are the Floquet multipliers of the orbit: all
// inside the unit circle for a stable orbit; one leaving through -1 flags period doubling, through +1
// a fold (the onset of a jump), a complex pair a quasi-periodic response (the start of chatter).
//
// The orbit found is the fixed point of the discrete scheme with this time step: the state a long
// transient run with the same settings converges to, without waiting for lightly damped modes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/error.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"
#include "camfollower/solver/step_sensitivity.hpp"

namespace camfollower {

// How shooting builds the monodromy: "variational" (one revolution carrying the step sensitivities),
// "differences" (2n perturbed revolutions), "auto" (variational where the stepper provides it).
enum class MonodromyMethod { automatic, variational, differences };
inline constexpr std::array<const char*, 3> monodromy_method_names{"auto", "variational", "differences"};
inline const char* monodromy_method_name(MonodromyMethod m) { return monodromy_method_names[std::size_t(m)]; }
inline MonodromyMethod monodromy_method_from_name(const std::string& name) {
    for (std::size_t k = 0; k < monodromy_method_names.size(); ++k)
        if (name == monodromy_method_names[k]) return MonodromyMethod(k);
    detail::fail("monodromy must be 'auto', 'variational' or 'differences', got '", name, "'");
}

struct ShootingOptions {
    double period = 0.0;      // s, one revolution; the time step must divide it
    double start_time = 0.0;  // s, where the orbit's revolution starts (its phase)
    // Converged when max |Phi(z) - z| <= tolerance, displacements relative to the largest |q| on the
    // revolution, velocities to the largest |v| (each with a floor: 1e-9 and 1e-9 * 2 pi / period).
    double tolerance = 1e-9;
    int max_iterations = 30;     // Newton and chord iterations
    int warmup_revolutions = 1;  // transient revolutions from the initial state before shooting
    double perturbation = 1e-6;  // forward-difference step, relative to those scales
    // Rebuild the monodromy at the converged orbit when the last one was built elsewhere, so that the
    // Floquet multipliers are the orbit's own (2n more revolutions).
    bool multipliers = true;
    // A 2n x 2n monodromy to start the chord iterations with (a nearby orbit's, e.g. the nominal case
    // of a tolerance study); empty: built at the first iterate.
    Eigen::MatrixXd monodromy;
    MonodromyMethod monodromy_method = MonodromyMethod::automatic;
    static constexpr int max_state_size = 400;  // 2n: the monodromy is a dense 2n x 2n matrix

    void validate(int n, double dt) const {
        detail::require_positive(period, "shooting period", "(s)");
        detail::require_finite(start_time, "shooting start_time");
        if (!(tolerance > 0.0 && tolerance < 1.0))
            detail::fail("shooting tolerance must be in (0, 1), got ", tolerance);
        if (max_iterations < 1 || max_iterations > 1000)
            detail::fail("shooting max_iterations must be in [1, 1000], got ", max_iterations);
        if (warmup_revolutions < 0 || warmup_revolutions > 10000)
            detail::fail("shooting warmup_revolutions must be in [0, 10000], got ", warmup_revolutions);
        if (!(perturbation >= 1e-12 && perturbation <= 1e-2))
            detail::fail("shooting perturbation must be in [1e-12, 1e-2], got ", perturbation);
        if (2 * n > max_state_size)
            detail::fail("shooting builds a dense monodromy by 2n = ", 2 * n, " revolutions: at most ", max_state_size,
                         " (", max_state_size / 2, " DOFs); use the transient route (settle) for larger models");
        if (monodromy.size() != 0 && (monodromy.rows() != 2 * n || monodromy.cols() != 2 * n || !monodromy.allFinite()))
            detail::fail("shooting monodromy guess must be a finite ", 2 * n, " x ", 2 * n, " matrix, got ",
                         monodromy.rows(), " x ", monodromy.cols());
        const double steps = std::round(period / dt);
        if (!(steps >= 1.0 && std::abs(steps * dt - period) <= 1e-9 * period))
            detail::fail("shooting needs a time step that divides the period: period / time_step = ", period / dt,
                         " is not a whole number");
    }
};

struct PeriodicOrbit {
    bool converged = false;
    bool cancelled = false;
    int iterations = 0;   // Newton / chord iterations
    int monodromies = 0;  // monodromy matrices built (2n revolutions each, or one variational revolution)
    MonodromyMethod monodromy_method = MonodromyMethod::differences;  // how they were built
    double mismatch = std::numeric_limits<double>::quiet_NaN();       // relative, at the returned state
    std::vector<double> history;           // mismatch per iterate, the first after the warm-up
    Eigen::VectorXd q, v;                  // the orbit's state at start_time (when converged; else the last iterate)
    double q_scale = 0.0, v_scale = 0.0;   // largest |q| (m or rad), |v| on the revolution
    Eigen::MatrixXd monodromy;             // d(q, v)(start + T) / d(q, v)(start), 2n x 2n
    bool monodromy_at_orbit = false;       // built at the returned state (else at an earlier iterate)
    Eigen::VectorXcd multipliers;          // eigenvalues of the monodromy, largest magnitude first
    double revolutions = 0.0;              // cost: revolutions simulated in all
    double variational_revolutions = 0.0;  // of them, those carrying the step sensitivities (~3x the cost)
    SolverStatistics stats;

    double spectral_radius() const {
        return multipliers.size() ? std::abs(multipliers[0]) : std::numeric_limits<double>::quiet_NaN();
    }
};

namespace detail {

template <class S, class = void>
struct provides_sensitivity : std::false_type {};
template <class S>
struct provides_sensitivity<S, void_t<decltype(S::provides_sensitivity)>>
    : std::bool_constant<S::provides_sensitivity> {};

template <class Stepper>
bool variational_monodromy(MonodromyMethod requested) {
    if (requested == MonodromyMethod::differences) return false;
    if (requested == MonodromyMethod::variational && !provides_sensitivity<Stepper>::value)
        fail(
            "monodromy 'variational' needs the Newmark family ('newmark', 'fox_goodwin', 'hht') on the dense "
            "backend (fewer than ",
            sparse_backend_threshold, " DOFs, or linear_solver 'dense'); use 'auto' or 'differences'");
    return provides_sensitivity<Stepper>::value;
}

// The one-revolution map of a stepper, with the scales of the revolution it ran.
template <class Stepper>
class RevolutionMap {
public:
    using Vector = typename Stepper::Vector;
    RevolutionMap(Stepper& stepper, const ShootingOptions& o, int n)
        : stepper_(stepper),
          t0_(o.start_time),
          n_(n),
          steps_(static_cast<std::uint64_t>(std::round(o.period / stepper.time_step()))),
          v_floor_(1e-9 * 2.0 * pi / o.period) {
        q_.resize(n), v_.resize(n);
    }
    // out = Phi(z); scales of the run in q_max, v_max.
    void operator()(const Eigen::VectorXd& z, Eigen::VectorXd& out, SolverStatistics& stats, double& q_max,
                    double& v_max) {
        q_ = z.head(n_);
        v_ = z.tail(n_);
        auto s = stepper_.start(t0_, q_, v_);
        q_max = s.q.cwiseAbs().maxCoeff(), v_max = s.v.cwiseAbs().maxCoeff();
        for (std::uint64_t i = 0; i < steps_; ++i) {
            stepper_.step(s, stats);
            s.t = t0_ + double(i + 1) * stepper_.time_step();  // as integrate() does
            q_max = std::max(q_max, s.q.cwiseAbs().maxCoeff());
            v_max = std::max(v_max, s.v.cwiseAbs().maxCoeff());
        }
        out.resize(2 * n_);
        out.head(n_) = s.q;
        out.tail(n_) = s.v;
        if (!out.allFinite()) fail("shooting: the revolution from the current iterate ended in a non-finite state");
        q_max = std::max(q_max, 1e-9), v_max = std::max(v_max, v_floor_);
        ++revolutions;
    }
    // The same, and J = dPhi/dz from the variational equations of the revolution.
    void operator()(const Eigen::VectorXd& z, Eigen::VectorXd& out, Eigen::MatrixXd& J, SolverStatistics& stats,
                    double& q_max, double& v_max) {
        if constexpr (provides_sensitivity<Stepper>::value) {
            struct Untrack {
                Stepper& s;
                ~Untrack() { s.track_sensitivity(nullptr); }
            } untrack{stepper_};
            stepper_.track_sensitivity(&sensitivity_);
            (*this)(z, out, stats, q_max, v_max);
            J = sensitivity_.state_jacobian();
            ++variational_revolutions;
        } else {
            (void)z, (void)out, (void)J, (void)stats, (void)q_max, (void)v_max;
            fail("shooting: this stepper has no variational equations");  // unreachable: variational_monodromy()
        }
    }
    double revolutions = 0.0, variational_revolutions = 0.0;

private:
    Stepper& stepper_;
    double t0_;
    int n_;
    std::uint64_t steps_;
    double v_floor_;
    Vector q_, v_;
    StepSensitivity<Vector> sensitivity_;
};

inline double scaled_mismatch(const Eigen::VectorXd& r, int n, double q_scale, double v_scale) {
    return std::max(r.head(n).cwiseAbs().maxCoeff() / q_scale, r.tail(n).cwiseAbs().maxCoeff() / v_scale);
}

}  // namespace detail

// Throws ConvergenceError unless the orbit converged, with the mismatch history.
inline void require_converged(const PeriodicOrbit& orbit, const ShootingOptions& options) {
    if (orbit.converged) return;
    std::string history;
    for (double h : orbit.history) history += (history.empty() ? "" : ", ") + detail::concat(h);
    if (orbit.cancelled) throw ConvergenceError("shooting was cancelled");
    throw ConvergenceError(
        detail::concat("shooting did not converge to the periodic steady state in ", orbit.iterations, " iterations (",
                       orbit.revolutions, " revolutions): mismatch ", orbit.mismatch, " > tolerance ",
                       options.tolerance, "; history [", history,
                       "]. The response may not be periodic (contact loss, chatter, period doubling: "
                       "multipliers outside the unit circle) -- use the transient route (settle) instead"));
}

// Shooting from (q0, v0) at options.start_time. keep_going() is polled every revolution (false
// cancels: the orbit comes back with cancelled set). Stepper errors (Newton failure within a step)
// propagate; non-convergence of the shooting itself is reported in the result (see periodic_orbit()).
template <class Stepper, class KeepGoing>
PeriodicOrbit shoot(Stepper& stepper, const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                    const ShootingOptions& options, KeepGoing&& keep_going) {
    const int n = int(q0.size());
    options.validate(n, stepper.time_step());
    if (v0.size() != n) detail::fail("shooting: initial q and v must have the same size, got ", n, " and ", v0.size());
    const int m = 2 * n;
    detail::RevolutionMap<Stepper> phi(stepper, options, n);
    // automatic: the variational equations while their Newton steps converge (below), then differences.
    bool variational = detail::variational_monodromy<Stepper>(options.monodromy_method);
    PeriodicOrbit orbit;
    Eigen::VectorXd z(m), fz(m), r(m), zp(m), fp(m);
    z << q0, v0;
    double qs = 0, vs = 0;
    auto stop = [&] {
        if (keep_going()) return false;
        orbit.cancelled = true;
        return true;
    };
    for (int k = 0; k < options.warmup_revolutions; ++k) {
        phi(z, fz, orbit.stats, qs, vs);
        z = fz;
        if (stop()) break;
    }
    Eigen::MatrixXd J = options.monodromy;  // dPhi/dz
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    bool J_fresh = false;  // built at the current iterate
    auto factor = [&] {
        ++orbit.monodromies;
        orbit.monodromy_method = variational ? MonodromyMethod::variational : MonodromyMethod::differences;
        lu.compute(J - Eigen::MatrixXd::Identity(m, m));
        J_fresh = true;
    };
    auto build = [&](const Eigen::VectorXd& at, const Eigen::VectorXd& f_at) {
        J.resize(m, m);
        double qs2 = 0, vs2 = 0;
        if (variational) {
            phi(at, fp, J, orbit.stats, qs2, vs2);
            if (stop()) return false;
            factor();
            return true;
        }
        for (int j = 0; j < m; ++j) {
            const double h = options.perturbation * (j < n ? qs : vs);
            zp = at;
            zp[j] += h;
            phi(zp, fp, orbit.stats, qs2, vs2);
            J.col(j) = (fp - f_at) / h;
            if (stop()) return false;
        }
        factor();
        return true;
    };
    auto finish = [&] {
        orbit.q = z.head(n), orbit.v = z.tail(n);
        orbit.q_scale = qs, orbit.v_scale = vs;
        orbit.revolutions = phi.revolutions;
        orbit.variational_revolutions = phi.variational_revolutions;
        if (!orbit.history.empty()) orbit.mismatch = orbit.history.back();
        return orbit;
    };
    if (orbit.cancelled) return finish();
    if (variational && J.size() == 0) {  // no monodromy to start from: the first revolution builds it
        J.resize(m, m);
        phi(z, fz, J, orbit.stats, qs, vs);
        factor();
    } else {
        phi(z, fz, orbit.stats, qs, vs);
        if (J.size()) lu.compute(J - Eigen::MatrixXd::Identity(m, m));
    }
    r = fz - z;
    double mis = detail::scaled_mismatch(r, n, qs, vs);
    orbit.history.push_back(mis);
    double best = mis;
    const Eigen::VectorXd z_first = z, fz_first = fz;  // where a switch to differences restarts
    const double qs_first = qs, vs_first = vs, mis_first = mis;
    int stalls = 0;
    constexpr int max_stalls = 4;
    while (!(mis <= options.tolerance) && orbit.iterations < options.max_iterations) {
        if (stop()) return finish();
        if (J.size() == 0 && !build(z, fz)) return finish();
        Eigen::VectorXd dz = lu.solve(-r);
        const bool was_fresh = J_fresh;
        // Backtrack (halve the update) while a fresh Newton step makes the mismatch grow.
        double next = 0, qs2 = 0, vs2 = 0;
        for (int halving = 0;; ++halving) {
            zp = z + dz;
            phi(zp, fp, orbit.stats, qs2, vs2);
            next = detail::scaled_mismatch(fp - zp, n, qs2, vs2);
            if (!(next > mis) || !was_fresh || halving == 4 || !std::isfinite(mis)) break;
            dz *= 0.5;
        }
        ++orbit.iterations;
        // A chord step (monodromy from elsewhere) that does not reduce the mismatch is rejected: the
        // monodromy is rebuilt here and the next step is Newton's.
        if (!was_fresh && !(next < mis)) {
            if (!build(z, fz)) return finish();
            continue;
        }
        z = zp, fz = fp, r = fz - z, J_fresh = false, qs = qs2, vs = vs2;
        const double ratio = next / mis;
        mis = next;
        orbit.history.push_back(mis);
        if (mis <= options.tolerance) break;
        // Newton steps that keep failing to improve on the best iterate: the response is not periodic
        // (or the tolerance is below the rounding floor): stop rather than spend 2n revolutions a time.
        if (was_fresh) {
            const bool improved = mis < 0.5 * best;
            if (!improved && variational && options.monodromy_method == MonodromyMethod::automatic) {
                // A fresh variational Newton step that did not halve the mismatch: the variational
                // equations miss what the model does between steps (impacts, path memory; grooved
                // cams chattering between flanks). The search restarts from its first iterate by
                // differences, as if asked for them (the steps taken may have left the smooth part).
                variational = false;
                z = z_first, fz = fz_first, r = fz - z, qs = qs_first, vs = vs_first, mis = best = mis_first;
                orbit.history.push_back(mis);
                stalls = 0;
                if (!build(z, fz)) return finish();
                continue;
            }
            stalls = improved ? 0 : stalls + 1;
        }
        if (stalls >= max_stalls) break;
        best = std::min(best, mis);
        // Chord iterations that do not at least quarter the mismatch: rebuild the monodromy here.
        if (!(ratio <= 0.25) && !build(z, fz)) return finish();
    }
    orbit.converged = mis <= options.tolerance;
    if (orbit.converged && options.multipliers && !J_fresh && !build(z, fz)) return finish();
    if (J.size()) {
        orbit.monodromy = J;
        orbit.monodromy_at_orbit = J_fresh;
        const Eigen::EigenSolver<Eigen::MatrixXd> eig(J, false);
        if (eig.info() == Eigen::Success) {
            orbit.multipliers = eig.eigenvalues();
            std::sort(
                orbit.multipliers.data(), orbit.multipliers.data() + m,
                [](const std::complex<double>& a, const std::complex<double>& b) { return std::abs(a) > std::abs(b); });
        }
    }
    return finish();
}

}  // namespace camfollower
