// SPDX-License-Identifier: BSD-3-Clause
// One call for the common case: start a system in its initial state (or a given state), integrate
// with settings.method (solver/settings.hpp; "auto" chosen at the start) for a duration, record named
// channels, report progress and honour cancellation.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "camfollower/solver/choose_method.hpp"
#include "camfollower/solver/dispatch.hpp"
#include "camfollower/solver/integrate.hpp"
#include "camfollower/solver/observers.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/settle.hpp"
#include "camfollower/solver/shooting.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

// The periodic steady state and settling need forcing that repeats every period.
template <class System>
void require_periodic(const System& system, const char* what) {
    if constexpr (detail::has_periodic<System>::value)
        if (!system.periodic())
            detail::fail(what,
                         " needs a camshaft whose motion repeats every revolution; this one's speed program ramps "
                         "(run-up, run-down): simulate it over a duration instead");
}

struct RunOptions {
    double duration = 0.0;  // s
    RecordOptions record;
    // Called every `progress_every` steps with (steps done, steps planned), and by the adaptive methods
    // every few hundred integration steps within an output interval (solver/interrupt.hpp); return
    // false to cancel.
    std::function<bool(std::uint64_t, std::uint64_t)> progress;
    std::uint64_t progress_every = 100000;
    // First settle on the periodic response (solver/settle.hpp); `duration` and record.from_time then
    // count from the settled state (recorded times stay absolute).
    SettleOptions settle;
};

template <class System>
struct RunResult {
    Recording recording;
    IntegrationReport report;
    State<System> final_state;
    double time_step = 0.0;
    std::size_t decimation = 1;
    SettleReport settle;
    // Contact losses and re-contacts of the recorded run, in time order; Event::index names the
    // switching function in event_names(system) (solver/events.hpp).
    std::vector<Event> events;
    const char* backend = "dense";                              // the Newton algebra used: "dense" or "sparse"
    const char* method = method_name(SolverSettings{}.method);  // the method that ran
    const char* requested_method = method;                      // as asked: "auto" when choose_method picked `method`
    std::string method_choice;  // with "auto": what choose_method picked and why, in words; else empty
    // A Fox-Goodwin-type run that kept the trapezoidal velocity (choose_velocity): why; else empty.
    std::string velocity_choice;
    // Highest natural frequency at the start (Hz, contacts linearized), for reading the step against
    // the shortest period: dense backend up to 200 DOFs only, else NaN (an eigen solve too costly).
    double highest_mode_hz = std::numeric_limits<double>::quiet_NaN();
};

namespace detail {

template <class S, class = void>
struct has_set_interrupt : std::false_type {};
template <class S>
struct has_set_interrupt<S, void_t<decltype(std::declval<S&>().set_interrupt(std::function<bool()>()))>>
    : std::true_type {};

template <class Stepper, class System>
RunResult<System> run(const System& system, const SolverSettings& settings, const RunOptions& options,
                      const std::optional<typename System::Vector>& q0,
                      const std::optional<typename System::Vector>& v0) {
    using Vector = typename System::Vector;
    Stepper stepper(system, settings);
    const std::uint64_t steps = steps_for(options.duration, settings.time_step);
    const Vector q = q0 ? *q0 : initial_displacement(system);
    const Vector v = v0 ? *v0 : initial_velocity(system);
    RunResult<System> result;
    result.method = result.requested_method = method_name(settings.method);
    result.final_state = stepper.start(0.0, q, v);
    if constexpr (!std::is_same_v<Stepper, SparseNewmark<System>>)
        if (system.size() <= 200)
            result.highest_mode_hz = highest_angular_frequency(system, result.final_state) / (2.0 * pi);
    RecordOptions record = options.record;
    if (options.settle.enabled) {
        require_periodic(system, "settling on the periodic response");
        const std::uint64_t planned =
            std::uint64_t(options.settle.max_revolutions) * steps_for(options.settle.period, settings.time_step);
        result.settle =
            settle(stepper, result.final_state, options.settle, result.report.stats,
                   [&](std::uint64_t done) { return !options.progress || options.progress(done, planned); });
        if (!result.settle.settled && result.settle.revolutions < options.settle.max_revolutions) {  // cancelled
            result.report.cancelled = true;
            result.recording =
                Recorder<System>(system, options.record, 0, result.final_state.t, settings.time_step).take();
            return result;
        }
        // Restart at the settled state: path memory (contact losses) covers the recorded run only.
        const State<System> settled = result.final_state;
        result.final_state = stepper.start(settled.t, settled.q, settled.v);
        record.from_time += settled.t;
    }
    const double t0 = result.final_state.t;
    Recorder<System> recorder(system, record, steps, t0, settings.time_step);
    const std::uint64_t every = options.progress ? options.progress_every : 0;
    const SolverStatistics settling = result.report.stats;
    std::uint64_t done = 0;  // output steps, for the polls within an interval
    if constexpr (has_set_interrupt<Stepper>::value)
        if (options.progress) stepper.set_interrupt([&] { return options.progress(done, steps); });
    result.report =
        integrate(stepper, result.final_state, options.duration, [&](const State<System>& s, std::uint64_t n) {
            recorder(s, n);
            done = n;
            if (every && n % every == 0 && n > 0) return options.progress(n, steps);
            return true;
        });
    result.report.stats.add(settling);
    result.recording = recorder.take();
    result.events = stepper.take_events();
    result.time_step = settings.time_step;
    result.decimation = options.record.decimation;
    result.backend = std::is_same_v<Stepper, SparseNewmark<System>> ? "sparse" : "dense";
    return result;
}

}  // namespace detail

// Refuses a time step the run cannot use: longer than the run itself, or (for a cam mechanism) longer
// than a twelfth of a camshaft revolution, which cannot resolve the cam's motion.
template <class System>
void check_time_step(const System& system, const SolverSettings& settings, double duration) {
    settings.validate();
    detail::require_positive(duration, "duration", "(s)");
    if (settings.time_step > duration)
        detail::fail("time_step = ", settings.time_step, " s is longer than the duration ", duration, " s");
    // A run whose steps are bounded by max_step is bounded like a fixed-step run (1e10 steps).
    if ((settings.tolerance || is_runge_kutta(settings.method)) && settings.max_step > 0.0 &&
        !(duration / settings.max_step <= 1e10))
        detail::fail("duration / max_step = ", duration / settings.max_step,
                     " steps is too many (limit 1e10); raise "
                     "max_step or shorten the run");
    if constexpr (detail::has_period<System>::value) {
        const double limit = system.period() / 12.0;
        if (settings.time_step > limit)
            detail::fail("time_step = ", settings.time_step,
                         " s cannot resolve the cam's motion: it must be <= ", limit,
                         " s (a twelfth of the camshaft period ", system.period(), " s)");
    }
}

// The settings made concrete for a run starting at (q0, v0), and why: method "auto" (choose_method),
// a processed velocity where it is stable (choose_velocity).
template <class System>
MethodChoice concrete_settings(const System& system, const SolverSettings& settings,
                               const std::optional<typename System::Vector>& q0,
                               const std::optional<typename System::Vector>& v0) {
    const bool automatic = is_automatic(settings.method);
    if (!automatic && !newmark_parameters(settings).processed) return {settings, "", ""};
    const typename System::Vector q = q0 ? *q0 : initial_displacement(system);
    const typename System::Vector v = v0 ? *v0 : initial_velocity(system);
    const State<System> start = state_at(system, 0.0, q, v);
    MethodChoice choice = automatic ? choose_method(system, settings, start) : MethodChoice{settings, "", ""};
    if (traits(choice.settings.method).stepper == StepperKind::newmark)
        choice.velocity = choose_velocity(system, choice.settings, start, uses_sparse_backend(system, choice.settings));
    return choice;
}

template <class System>
RunResult<System> simulate(const System& system, const SolverSettings& requested, const RunOptions& options,
                           const std::optional<typename System::Vector>& q0 = std::nullopt,
                           const std::optional<typename System::Vector>& v0 = std::nullopt) {
    if (options.progress && options.progress_every < 1) detail::fail("progress_every must be >= 1");
    check_initial(system, q0, "initial q", true);
    check_initial(system, v0, "initial v", false);
    check_time_step(system, requested, options.duration);
    const MethodChoice choice = concrete_settings(system, requested, q0, v0);
    RunResult<System> r = with_stepper(system, choice.settings, [&](auto stepper) {
        return detail::run<typename decltype(stepper)::type>(system, choice.settings, options, q0, v0);
    });
    r.requested_method = method_name(requested.method);
    r.method_choice = choice.reason;
    r.velocity_choice = choice.velocity;
    return r;
}

namespace detail {
template <class Stepper, class System>
PeriodicOrbit shoot_with(const System& system, const SolverSettings& settings, const ShootingOptions& options,
                         const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                         const std::function<bool()>& keep_going) {
    Stepper stepper(system, settings);
    return shoot(stepper, q0, v0, options, [&] { return !keep_going || keep_going(); });
}
}  // namespace detail

// The periodic steady state by shooting (solver/shooting.hpp) from (q0, v0) at options.start_time
// (default: the system's initial state), on the backend simulate() would use. options.period
// defaults to the system's period(). Check orbit.converged (or call require_converged).
template <class System>
PeriodicOrbit periodic_orbit(const System& system, const SolverSettings& requested, ShootingOptions options,
                             const std::optional<typename System::Vector>& q0 = std::nullopt,
                             const std::optional<typename System::Vector>& v0 = std::nullopt,
                             const std::function<bool()>& keep_going = {}) {
    if constexpr (detail::has_period<System>::value) {
        if (options.period == 0.0) options.period = system.period();
    }
    require_periodic(system, "the periodic steady state");
    check_initial(system, q0, "initial q", true);
    check_initial(system, v0, "initial v", false);
    check_time_step(system, requested, options.period);
    const SolverSettings settings = concrete_settings(system, requested, q0, v0).settings;
    const Eigen::VectorXd q = q0 ? Eigen::VectorXd(*q0) : Eigen::VectorXd(initial_displacement(system));
    const Eigen::VectorXd v = v0 ? Eigen::VectorXd(*v0) : Eigen::VectorXd(initial_velocity(system));
    return with_stepper(system, settings, [&](auto stepper) {
        return detail::shoot_with<typename decltype(stepper)::type>(system, settings, options, q, v, keep_going);
    });
}

}  // namespace camfollower
