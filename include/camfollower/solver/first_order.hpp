// SPDX-License-Identifier: BSD-3-Clause
// What the steppers on the first-order form share (the explicit Runge-Kutta methods and Radau IIA):
// the system written as y = (q, v), y' = (v, a) with M a = -(C v + K q + f(t, q, v) - p(t)); an
// integration state kept ahead of the reported one, which step() moves by exactly one output interval
// and fills by the method's dense output (the output grid never shortens the integration steps); the
// start (consistent acceleration, force scale, error scales, event watch); the checks of the system
// and settings; events, interrupt polls and statistics.
//
// A stepper derives from FirstOrderStepper<Derived, System> (CRTP, no virtual calls) and provides
//   void restart(const State<System>& s)                  its own start after the shared one (first step size, ...)
//   void advance(double target, SolverStatistics&)        one accepted integration step towards the output time
//   void dense_output(double t, Vector& q, Vector& v)     the state at t within the last accepted step
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/error_scales.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/interrupt.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

template <class Derived, class System>
class FirstOrderStepper {
    static_assert(check_system<System>());

public:
    using SystemType = System;
    using Vector = typename System::Vector;
    using Matrix = typename System::Matrix;
    using StateType = State<System>;

    const SolverSettings& settings() const { return s_; }
    const System& system() const { return system_; }
    double time_step() const { return s_.time_step; }  // the output interval (steps are adaptive)
    double force_scale() const { return force_scale_; }

    // A state at (t, q, v) with its consistent acceleration; the integration state starts there.
    StateType start(double t, const Vector& q, const Vector& v) {
        StateType s = state_at(system_, t, q, v);
        acceleration(s.q, s.v, s.f, s.a);
        const Vector Kq = system_.stiffness() * s.q;
        force_scale_ = std::max({1.0, Kq.cwiseAbs().maxCoeff(), s.f.cwiseAbs().maxCoeff()});
        accepted(system_, s.workspace, s.q, s.v);
        ws_ = s.workspace;
        t_ = t, q_ = q, v_ = v;
        events_.start(ws_, q_, v_);  // before the first step size's trial moves the workspace elsewhere
        t_start_ = t, fixed_steps_ = 0;
        scales_.start(reference_rate(system_, s, s_.time_step), q_, v_);
        derived().restart(s);
        return s;
    }

    // Moves the reported state one output interval on (dense output between integration steps).
    void step(StateType& s, SolverStatistics& stats) {
        const double target = s.t + s_.time_step;
        while (!reaches(t_, target)) {
            interrupt_();
            derived().advance(target, stats);
        }
        derived().dense_output(target, s.q, s.v);
        s.t = target;
        // The reported state carries the integration's path memory (e.g. contact losses so far).
        s.workspace = ws_;
        prepare(system_, target, s.workspace);
        nonlinear_force(system_, s.workspace, s.q, s.v, s.f);
        acceleration(s.q, s.v, s.f, s.a);
        ++stats.evaluations;
    }

    // Polled every few integration steps within an output interval (solver/interrupt.hpp).
    void set_interrupt(std::function<bool()> keep_going) { interrupt_.set(std::move(keep_going)); }

    // Contact losses and re-contacts since start(); each ended an integration step (solver/events.hpp).
    const std::vector<Event>& events() const { return events_.events(); }
    std::vector<Event> take_events() { return events_.take_events(); }

    // Highest natural angular frequency at a state (rad/s), contacts linearized.
    double highest_angular_frequency(const StateType& s) const {
        return camfollower::highest_angular_frequency(system_, s);
    }

protected:
    // `method`: the one this stepper runs (another is refused); `name` for messages.
    FirstOrderStepper(const System& system, const SolverSettings& settings, Method method, const char* name)
        : system_(system),
          s_(validated(settings, method, name)),
          adaptive_(settings.tolerance.has_value()),
          tolerance_(settings.tolerance.value_or(runge_kutta_default_tolerance)),
          n_(system.size()),
          uvq_(n_, std::max(1, max_rank(system))),
          uvv_(n_, std::max(1, max_rank(system))) {
        const Matrix& M = system.mass();
        if (M.rows() != n_ || M.cols() != n_ || system.damping().rows() != n_ || system.stiffness().rows() != n_)
            detail::fail("system: mass, damping and stiffness must be ", n_, " x ", n_, " (size())");
        for (int k = 0; k < n_; ++k)
            if (!(M(k, k) > 0.0))
                detail::fail("system: mass matrix diagonal must be > 0, got M(", k, ", ", k, ") = ", M(k, k));
        M_inv_ = M.partialPivLu().inverse();
        for (Vector* x : {&q_, &v_, &f_, &rhs_}) x->resize(n_);
    }

    // Whether a step ending at t_end reaches the output time `target` (a step ending within rounding
    // of it does: no sliver of a step).
    bool reaches(double t_end, double target) const { return target - t_end <= 1e-9 * s_.time_step; }

    // a = M^-1 (-(C v + K q + f)).
    void acceleration(const Vector& q, const Vector& v, const Vector& f, Vector& out) {
        rhs_.noalias() = system_.damping() * v;
        rhs_.noalias() += system_.stiffness() * q;
        rhs_ += f;
        out.noalias() = M_inv_ * rhs_;  // then negated in place: -(M^-1 r) would be a temporary for dynamic sizes
        out = -out;
    }

    const System& system_;
    SolverSettings s_;
    bool adaptive_;     // a tolerance set: adaptive steps; else fixed steps of max_step (or time_step)
    double tolerance_;  // the step's error tolerance (fixed steps: runge_kutta_default_tolerance, for Radau's Newton)
    int n_;
    Matrix M_inv_;
    double force_scale_ = 1.0;
    // The integration state (ahead of the reported one), its workspace and error scales.
    double t_ = 0.0, t_start_ = 0.0;
    std::uint64_t fixed_steps_ = 0;  // fixed steps: the time is t_start_ + n h
    workspace_t<System> ws_;
    ErrorScales scales_;
    // Scratch, sized once: nothing is allocated inside the time loop.
    Vector q_, v_, f_, rhs_;
    LowRank<Vector> uvq_, uvv_;
    InterruptPoll interrupt_;
    EventWatch<System> events_{system_};

private:
    Derived& derived() { return static_cast<Derived&>(*this); }
    static SolverSettings validated(const SolverSettings& s, Method method, const char* name) {
        s.validate();
        if (s.method != method)
            detail::fail("the ", name, " stepper runs method '", method_name(method), "', got '", method_name(s.method),
                         "' (simulate() and periodic_orbit() run every method)");
        if (!s.tolerance && s.max_step == 0.0)
            detail::fail("method '", method_name(method),
                         "' adapts its steps under a tolerance: set tolerance (Python and the "
                         "config default to ",
                         runge_kutta_default_tolerance, "), or max_step for fixed steps of max_step");
        return s;
    }
};

}  // namespace camfollower
