// SPDX-License-Identifier: BSD-3-Clause
// The stepper conformance suite: every method of method_table (solver/settings.hpp) through the same
// checks, so that a new integrator joins them by its row in the table: its order on a closed form,
// its error following the tolerance, its statistics, a restart at a state, and events located at the
// closed-form times of a bouncing mass. (No allocation per step: no_allocation.test.cpp, over the
// same table.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bouncer.hpp"
#include "camfollower/solver/dispatch.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/simulate.hpp"
#include "driven_sdof.hpp"

using namespace camfollower;

namespace {

// The concrete methods ("auto" runs one of them: choose_method.test.cpp).
std::vector<MethodTraits> concrete_methods() {
    std::vector<MethodTraits> out;
    for (const MethodTraits& t : method_table)
        if (t.stepper != StepperKind::automatic) out.push_back(t);
    return out;
}

// Fixed steps of time_step (a Runge-Kutta method takes them as max_step).
SolverSettings fixed_steps(Method method, double time_step) {
    SolverSettings s = SolverSettings::named(method, time_step);
    if (is_runge_kutta(method)) s.max_step = time_step;
    return s;
}

bool implicit(Method m) { return is_newmark_family(m) || m == Method::radau; }

}  // namespace

TEST_CASE("Every method with fixed steps converges at its order on the driven damped oscillator") {
    const DrivenSdof sdof;
    const double T = sdof.period();
    for (const MethodTraits& t : concrete_methods()) {
        // The coarsest step keeps the finest error well above rounding (DOP853's is 7e-16 m at T/40).
        const double coarsest = t.order >= 8 ? T / 5 : t.order >= 5 ? T / 20 : T / 40;
        double errors[3];
        for (int i = 0; i < 3; ++i)
            errors[i] = max_error(sdof, fixed_steps(t.method, coarsest / double(1 << i)), 3 * T);
        for (int i = 0; i < 2; ++i) {
            const double observed = std::log2(errors[i] / errors[i + 1]);
            INFO(t.name << ", h = T/" << T / coarsest * double(1 << i) << ": error " << errors[i] << ", observed order "
                        << observed << " (table: " << t.order << ")");
            CHECK(observed == Approx(double(t.order)).margin(0.2));
        }
        CHECK(errors[2] > 1e-13);  // above rounding: the orders measure the method
    }
}

TEST_CASE("Every method that takes a tolerance holds its error near it, tighter for a tighter tolerance") {
    const DrivenSdof sdof;
    const double T = sdof.period(), peak = sdof.F / sdof.k * 10.0;  // a generous bound of |x|
    for (const MethodTraits& t : concrete_methods()) {
        if (t.method == Method::hht) {  // its error estimate is not Newmark's: refused (newmark_adaptive.test.cpp)
            CHECK_THROWS_WITH(SolverSettings::named(Method::hht, T / 64, 1e-6).validate(),
                              Catch::Contains("method 'hht' takes no tolerance"));
            continue;
        }
        double errors[2];
        const double tolerances[2] = {1e-5, 1e-8};
        for (int i = 0; i < 2; ++i) {
            SolverSettings s = SolverSettings::named(t.method, T / 64, tolerances[i]);
            s.max_halvings = 15;  // the Newmark family's smallest step, T / 64 / 2^15
            errors[i] = max_error(sdof, s, 3 * T);
            INFO(t.name << " at tolerance " << tolerances[i] << ": error " << errors[i] / peak << " of the peak");
            CHECK(errors[i] / peak < 300.0 * tolerances[i]);
        }
        CHECK(errors[1] < errors[0] / 30.0);
    }
}

TEST_CASE("A Runge-Kutta method without a tolerance needs max_step for its fixed steps") {
    const DrivenSdof sdof;
    for (const MethodTraits& t : concrete_methods()) {
        if (!is_runge_kutta(t.method)) continue;
        CAPTURE(t.name);
        CHECK_THROWS_WITH(run(sdof.system(), SolverSettings::named(t.method, 1e-3), 0.1),
                          Catch::Contains("adapts its steps under a tolerance: set tolerance") &&
                              Catch::Contains("or max_step for fixed steps of max_step"));
    }
}

TEST_CASE("Every method counts its work: steps, evaluations, Newton iterations, no rejections at fixed steps") {
    const DrivenSdof sdof;
    const double T = sdof.period();
    for (const MethodTraits& t : concrete_methods()) {
        CAPTURE(t.name);
        const auto r = run(sdof.system(), fixed_steps(t.method, T / 200), T);
        CHECK(r.rows == 201u);
        CHECK(r.stats.steps == 200u);  // one integration step per output step
        CHECK(r.stats.rejected_steps == 0u);
        CHECK(r.stats.halvings == 0u);
        CHECK((r.stats.newton_iterations > 0u) == implicit(t.method));
        if (is_runge_kutta(t.method)) CHECK(r.stats.evaluations >= r.stats.steps);
    }
}

TEST_CASE("Every method restarts at a state: the run continues as if never stopped, events and history reset") {
    const DrivenSdof sdof;
    const LinearSystem<1> system = sdof.system();
    const double T = sdof.period();
    for (const MethodTraits& t : concrete_methods()) {
        CAPTURE(t.name);
        const SolverSettings s = fixed_steps(t.method, T / 400);
        with_stepper(system, s, [&](auto tag) {
            using Stepper = typename decltype(tag)::type;
            Stepper straight(system, s), stopped(system, s);
            SolverStatistics stats;
            auto a = straight.start(0.0, system.initial_displacement(), LinearSystem<1>::Vector::Zero());
            auto b = stopped.start(0.0, system.initial_displacement(), LinearSystem<1>::Vector::Zero());
            for (int i = 0; i < 400; ++i) straight.step(a, stats);
            for (int i = 0; i < 200; ++i) stopped.step(b, stats);
            b = stopped.start(b.t, b.q, b.v);  // the acceleration recomputed from the equations
            for (int i = 0; i < 200; ++i) stopped.step(b, stats);
            CHECK(b.t == Approx(a.t).epsilon(1e-14));
            // The restart costs far less than the method's own error: nothing (to the Newton tolerance)
            // where the stepped acceleration meets the equations of motion; for HHT, whose acceleration
            // meets them at the alpha-weighted time, O(alpha h^2) of it.
            const double error = std::abs(a.q[0] - sdof.exact(a.t));
            INFO("restarted - straight " << b.q[0] - a.q[0] << " m, straight - exact " << error << " m");
            CHECK(std::abs(b.q[0] - a.q[0]) <= std::max(1e-8 * sdof.F / sdof.k, 0.01 * error));
            CHECK(error < 1e-3 * sdof.F / sdof.k);
        });
    }
}

TEST_CASE("Every method locates contact made and lost at the closed-form times of a bouncing mass") {
    const Bouncer b;
    const double duration = 3.2 * (b.flight() + b.contact_time());
    const std::vector<double> exact = b.event_times(duration);
    REQUIRE(exact.size() == 6);
    for (const MethodTraits& t : concrete_methods()) {
        CAPTURE(t.name);
        // Fixed steps locate a crossing within their step, to the scheme's order; the methods under a
        // tolerance end a step at it.
        const bool fixed = is_newmark_family(t.method);
        SolverSettings s = fixed ? fixed_steps(t.method, 5e-6) : SolverSettings::named(t.method, 1e-3, 1e-10);
        s.max_halvings = 15;
        RunOptions o;
        o.duration = duration;
        const RunResult<Bouncer> r = simulate(b, s, o);
        REQUIRE(r.events.size() == exact.size());
        for (std::size_t i = 0; i < exact.size(); ++i) {
            CAPTURE(i, r.events[i].time, exact[i]);
            CHECK(r.events[i].index == 0);
            CHECK(r.events[i].direction == (i % 2 == 0 ? 1 : -1));
            CHECK(std::abs(r.events[i].time - exact[i]) < (fixed ? 0.5 * s.time_step : 1e-7 * duration));
        }
    }
}
