// SPDX-License-Identifier: BSD-3-Clause
// Newmark and Fox-Goodwin under a tolerance: the level the controller holds
// against the closed-form leading term of the local error, the error against closed-form responses,
// adaptivity, and the settings it refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "camfollower/constants.hpp"
#include "camfollower/solver/newmark.hpp"
#include "driven_sdof.hpp"
#include "linear_system_instances.hpp"
#include "run.hpp"

using namespace camfollower;

namespace {

SolverSettings under_tolerance(const char* method, double output_interval, double tolerance, int max_halvings = 10) {
    SolverSettings s;
    s.method = method_from_name(method);
    s.time_step = output_interval;
    s.tolerance = tolerance;
    s.max_halvings = max_halvings;
    return s;
}

// An undamped oscillator q'' = -w^2 q released from q = 1 at rest.
LinearSystem<1> oscillator(double w) {
    LinearSystem<1> s;
    s.K(0, 0) = w * w;
    s.q0[0] = 1.0;
    return s;
}

}  // namespace

TEST_CASE("newmark under a tolerance holds the level that the local error's leading term asks for") {
    // Newmark (beta = 1/4): one step from the exact state leaves e_q = (1/6 - beta) h^3 q''' + O(h^4)
    // (Taylor), and on q = cos(w t) |q'''| peaks at w^3: against the force scale k |q|max = w^2 it is
    // (w h)^3 / 12, 8 x per doubling of h.
    // Fox-Goodwin (processed, fourth order): Numerov's phase lag (w h)^5 / 480 per step, per radian of
    // the reference rate (here the oscillator's own w: it has no cam period) (w h)^4 / 480, 16 x per
    // doubling. With steps h_k = D / 2^k, the level k holds when the estimate is <= tol there and the
    // level coarser exceeds it. Chosen: D = T / 8 and tol such that level 4 makes 0.4 tol (level 3:
    // 3.2 resp. 6.4 tol, refused; level 5: 0.05 resp. 0.025 tol, low enough to coarsen).
    const double w = 2.0 * pi * 50.0, D = (2.0 * pi / w) / 8.0;
    const int expected_level = 4;
    struct Case {
        const char* method;
        double leading, growth;  // the estimate at level 0 (x tol), its growth per doubling of the step
    };
    for (const Case& c :
         {Case{"newmark", std::pow(w * D, 3) / 12.0, 8.0}, Case{"fox_goodwin", std::pow(w * D, 4) / 480.0, 16.0}}) {
        INFO(c.method);
        const double tol = c.leading / std::pow(c.growth, expected_level) / 0.4;
        const LinearSystem<1> system = oscillator(w);
        Newmark<LinearSystem<1>> stepper(system, under_tolerance(c.method, D, tol));
        auto state = stepper.start(0.0, system.q0, LinearSystem<1>::Vector::Zero());
        SolverStatistics stats;
        for (int i = 0; i < 8 * 20; ++i) stepper.step(state, stats);  // 20 periods
        CHECK(stepper.level() == expected_level);
        const std::uint64_t before = stats.steps;
        for (int i = 0; i < 8 * 5; ++i) stepper.step(state, stats);
        CHECK(stats.steps - before == std::uint64_t(8 * 5) << expected_level);  // 16 steps per interval
        CHECK(std::abs(state.t - 25.0 * 8.0 * D) < 1e-12);
    }
}

TEST_CASE("newmark under a tolerance: a loose tolerance runs fixed steps of the output interval, value for value") {
    const DrivenSdof sdof;
    const double D = sdof.period() / 32.0, duration = 3.0 * sdof.period();
    for (const char* method : {"newmark", "fox_goodwin"}) {
        INFO(method);
        SolverSettings fixed;
        fixed.method = method_from_name(method);
        fixed.time_step = D;
        const auto a = run(sdof.system(), fixed, duration);
        const auto b = run(sdof.system(), under_tolerance(method, D, 0.1), duration);
        REQUIRE(a.rows == b.rows);
        for (std::size_t i = 0; i < a.rows; ++i) {
            CHECK(a.q[i] == b.q[i]);
            CHECK(a.a[i] == b.a[i]);
        }
        CHECK(b.stats.rejected_steps == 0);
        CHECK(b.stats.steps == a.stats.steps);
    }
}

TEST_CASE("fox_goodwin under a tolerance: steps ~ tol^(-1/4), error held at the tolerance against the closed form") {
    // Driven, damped SDOF (closed form), output every T / 8. The controlled error is the phase lag per
    // radian, ~h^4, so a 100 x tighter tolerance takes 100^(1/4) = 3.16 x the steps, and the processed
    // Fox-Goodwin is fourth order: the error shrinks ~100 x (at least 30 x asked here). The lag adds up
    // over the run's 10 periods (63 radians of the reference rate); the error stays below 10 x tol.
    const DrivenSdof sdof;
    const double duration = 10.0 * sdof.period();
    double peak = 0.0;
    for (int i = 0; i <= 1000; ++i) peak = std::max(peak, std::abs(sdof.exact(duration * i / 1000.0)));
    double last = INFINITY;
    std::uint64_t last_steps = 0;
    for (double tol : {1e-4, 1e-6, 1e-8}) {
        INFO("tolerance " << tol);
        const SolverSettings s = under_tolerance("fox_goodwin", sdof.period() / 8.0, tol, 14);
        const auto r = run(sdof.system(), s, duration);
        double err = 0.0;
        for (std::size_t i = 0; i < r.rows; ++i) err = std::max(err, std::abs(r.q[i] - sdof.exact(r.t[i])));
        err /= peak;
        CHECK(err <= 10.0 * tol);
        if (last_steps > 0) {
            CHECK(err < last / 30.0);
            const double ratio = double(r.stats.steps) / double(last_steps);
            CHECK(ratio >= 0.75 * std::sqrt(10.0));
            CHECK(ratio <= 1.3 * std::sqrt(10.0));
        }
        last = err, last_steps = r.stats.steps;
    }
}

TEST_CASE("fox_goodwin under a tolerance steps over a kink of the load that no event marks") {
    // q'' + w^2 q = R (t - t_kink) after t_kink, 0 before: the acceleration's slope jumps by R there
    // (a cam program's segment boundary does the same to a contact force); after it the response is
    // R / w^2 (u - sin(w u) / w), u = t - t_kink. Across the kink the fourth-order estimate per
    // radian falls only 4 x per halving (16 x where smooth): the stepper takes the kink's error as a
    // one-off, per step, instead of bisecting towards it. Checked: few refusals, about the steps of
    // the same ramp started at t = 0 (no kink inside the run), the error against the closed form
    // within 20 x tol (measured 5.6 x).
    const double w = 2.0 * pi * 50.0, R = 100.0, t_kink = 0.0123;
    const double T = 2.0 * pi / w, duration = 5.0 * T, tol = 1e-6;
    const auto ramp = [=](double start) {
        LinearSystem<1> system;
        system.K(0, 0) = w * w;
        system.external = [=](double t) { return LinearSystem<1>::Vector(t >= start ? R * (t - start) : 0.0); };
        return system;
    };
    const auto exact = [=](double t) {
        const double u = t - t_kink;
        return u < 0.0 ? 0.0 : R / (w * w) * (u - std::sin(w * u) / w);
    };
    const SolverSettings s = under_tolerance("fox_goodwin", T / 16.0, tol, 14);
    const auto r = run(ramp(t_kink), s, duration);
    double err = 0.0;
    for (std::size_t i = 0; i < r.rows; ++i) err = std::max(err, std::abs(r.q[i] - exact(r.t[i])));
    const double peak = exact(duration);
    INFO("steps " << r.stats.steps << ", refused " << r.stats.rejected_steps << ", error / tol " << err / peak / tol);
    CHECK(err / peak <= 20.0 * tol);
    CHECK(r.stats.rejected_steps <= 10);
    const auto smooth = run(ramp(0.0), s, duration);
    CHECK(r.stats.steps <= smooth.stats.steps + 200);
}

TEST_CASE("newmark under a tolerance refines for a fast transient and coarsens after it") {
    // A lightly damped fast mode (1 kHz, zeta = 0.02) released from a displacement, beside a slow one
    // (5 Hz) driven at its own pace: the ringing needs short steps; once it has decayed (e^-8 after
    // 64 ms) the slow response does not.
    LinearSystem<2> system;
    const double fast = 2.0 * pi * 1000.0, slow = 2.0 * pi * 5.0;
    system.K(0, 0) = fast * fast, system.C(0, 0) = 2.0 * 0.02 * fast;
    system.K(1, 1) = slow * slow;
    system.q0 << 1e-3, 0.0;
    system.external = [slow](double t) {
        return LinearSystem<2>::Vector(0.0, slow * slow * 1e-2 * std::sin(slow * t));
    };
    Newmark<LinearSystem<2>> stepper(system, under_tolerance("fox_goodwin", 1e-3, 1e-6, 12));
    auto state = stepper.start(0.0, system.q0, LinearSystem<2>::Vector::Zero());
    SolverStatistics stats;
    for (int i = 0; i < 5; ++i) stepper.step(state, stats);
    const int early = stepper.level();
    for (int i = 0; i < 195; ++i) stepper.step(state, stats);
    const int late = stepper.level();
    CHECK(early >= late + 3);
    CHECK(stats.rejected_steps > 0);
}

TEST_CASE("fox_goodwin under a tolerance keeps its steps within the stability limit") {
    // A slow mode released from a displacement beside a fast one at rest (w_fast = 100 w_slow): the
    // error is the slow mode's, tiny; the output interval 4 / w_fast is beyond Fox-Goodwin's limit
    // (0.9 sqrt(6) / w_fast = 2.2 / w_fast), so the steps stay at half of it and the fast mode at rest.
    const double slow = 2.0 * pi * 5.0, fast = 100.0 * slow;
    LinearSystem<2> system;
    system.K(0, 0) = slow * slow, system.K(1, 1) = fast * fast;
    system.q0 << 1.0, 0.0;
    Newmark<LinearSystem<2>> stepper(system, under_tolerance("fox_goodwin", 4.0 / fast, 0.1));
    auto state = stepper.start(0.0, system.q0, LinearSystem<2>::Vector::Zero());
    SolverStatistics stats;
    for (int i = 0; i < 2000; ++i) stepper.step(state, stats);
    CHECK(stepper.level() == 1);
    CHECK(stats.steps == 2 * 2000);
    CHECK(std::abs(state.q[1]) <= 1e-12);
}

TEST_CASE("newmark under a tolerance refuses what it cannot do, naming the setting") {
    const DrivenSdof sdof;
    const double D = sdof.period() / 8.0;
    SolverSettings hht = SolverSettings::hht(-0.1, D);
    hht.tolerance = 1e-6;
    CHECK_THROWS_WITH(hht.validate(), Catch::Contains("method 'hht' takes no tolerance"));
    SolverSettings fixed = under_tolerance("fox_goodwin", D, 1e-6);
    fixed.tolerance.reset();
    fixed.max_step = D / 4.0;
    CHECK_THROWS_WITH(fixed.validate(), Catch::Contains("max_step applies with a tolerance"));
    SolverSettings small = under_tolerance("newmark", D, 1e-6, 2);
    small.max_step = D / 16.0;
    CHECK_THROWS_WITH(run(sdof.system(), small, 2.0 * sdof.period()), Catch::Contains("max_halvings"));
    // A tolerance the smallest step cannot meet: a ConvergenceError naming the tolerance.
    const SolverSettings tight = under_tolerance("fox_goodwin", D, 1e-12, 1);
    CHECK_THROWS_WITH(run(sdof.system(), tight, sdof.period()),
                      Catch::Contains("tolerance = 1e-12") && Catch::Contains("max_halvings"));
    // max_step bounds the steps: the coarsest level is the first at or below it.
    SolverSettings bounded = under_tolerance("newmark", D, 0.1);
    bounded.max_step = D / 3.0;
    const auto r = run(sdof.system(), bounded, sdof.period());
    CHECK(r.stats.steps == 8 * 4);
}
