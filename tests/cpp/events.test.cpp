// SPDX-License-Identifier: BSD-3-Clause
// Events (solver/events.hpp; every method locates them at the closed-form times of a bouncing mass:
// steppers.test.cpp): Dormand-Prince 5(4) and 8(5,3) ending their steps there keep
// their accuracy across the kinks (against the same system without switching functions); events on
// the paper preset above its jump speed agree between methods and with the recorded penetration.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"
#include "bouncer.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

using namespace camfollower;

namespace {

SolverSettings adaptive_run(double tolerance, double output, const char* method = "dormand_prince") {
    SolverSettings s;
    s.method = method_from_name(method);
    s.tolerance = tolerance;
    s.time_step = output;
    return s;
}

RunOptions for_duration(double duration) {
    RunOptions o;
    o.duration = duration;
    o.record.decimation = 1;
    return o;
}

}  // namespace

constexpr const char* explicit_methods[] = {"dormand_prince", "dop853"};

TEST_CASE("events: ending steps at the kinks keeps both explicit methods accurate and cheaper") {
    const Bouncer with;
    Bouncer without;
    without.with_events = false;
    const double duration = 3.2 * (with.flight() + with.contact_time());
    for (const auto& [method, tol] : {std::pair{"dormand_prince", 1e-6}, std::pair{"dormand_prince", 1e-9},
                                      std::pair{"dop853", 1e-6}, std::pair{"dop853", 1e-9}}) {
        CAPTURE(method, tol);
        const auto a = simulate(with, adaptive_run(tol, 1e-4, method), for_duration(duration));
        const auto b = simulate(without, adaptive_run(tol, 1e-4, method), for_duration(duration));
        double err_a = 0.0, err_b = 0.0;
        const Recording& ra = a.recording;
        const Recording& rb = b.recording;
        REQUIRE(ra.rows == rb.rows);
        for (std::size_t i = 0; i < ra.rows; ++i) {
            const double exact = with.height(ra.at("t", i));
            err_a = std::max(err_a, std::abs(ra.at("q.0", i) - exact));
            err_b = std::max(err_b, std::abs(rb.at("q.0", i) - exact));
        }
        CAPTURE(err_a, err_b, a.report.stats.steps + a.report.stats.rejected_steps,
                b.report.stats.steps + b.report.stats.rejected_steps);
        // Relative to the drop height: within the tolerance with events, and better than without.
        CHECK(err_a < 20.0 * tol * with.h0);
        CHECK(err_a < err_b);
        // (at about the same number of attempted steps: the retakes replace rejections at the kinks)
        CHECK(double(a.report.stats.steps + a.report.stats.rejected_steps) <
              1.2 * double(b.report.stats.steps + b.report.stats.rejected_steps));
        CHECK(b.events.empty());
    }
}

TEST_CASE("events: Newmark reports the crossings within its fixed steps, to its order") {
    const Bouncer b;
    const double duration = 3.2 * (b.flight() + b.contact_time());
    const std::vector<double> exact = b.event_times(duration);
    double previous = 0.0;
    for (const double dt : {2e-5, 5e-6}) {
        SolverSettings s;
        s.time_step = dt;
        const auto r = simulate(b, s, for_duration(duration));
        REQUIRE(r.events.size() == exact.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < exact.size(); ++i) {
            CHECK(r.events[i].direction == (i % 2 == 0 ? 1 : -1));
            worst = std::max(worst, std::abs(r.events[i].time - exact[i]));
        }
        CAPTURE(dt, worst);
        // The times follow the scheme's own (second-order) error of the motion: / 16 when dt / 4.
        CHECK(worst < 0.5 * dt);
        if (previous > 0.0) CHECK(worst < previous / 8.0);
        previous = worst;
    }
}

TEST_CASE("events: the paper preset above its jump speed loses and regains contact, alike in every method") {
    CamFollowerParameters p;
    p.camshaft_speed_rpm = 2000.0;  // jump speed 1329 rpm (docs/studies.md)
    const Mechanism<presets::paper_dofs> m = presets::paper(p);
    REQUIRE(event_names(m) == std::vector<std::string>{"cam.contact"});
    RunOptions run;
    run.duration = m.period();
    run.record.decimation = 1;
    SolverSettings fg;
    fg.beta = 1.0 / 12.0;
    fg.time_step = m.period() / 8192;
    const auto a = simulate(m, fg, run);
    const auto b = simulate(m, adaptive_run(1e-9, m.period() / 8192), run);
    const auto c = simulate(m, adaptive_run(1e-9, m.period() / 8192, "dop853"), run);
    REQUIRE(a.events.size() >= 2);
    REQUIRE(a.events.size() == b.events.size());
    REQUIRE(c.events.size() == b.events.size());
    for (std::size_t i = 0; i < a.events.size(); ++i) {
        CAPTURE(i, a.events[i].time, b.events[i].time, c.events[i].time);
        CHECK(a.events[i].direction == b.events[i].direction);
        CHECK(c.events[i].direction == b.events[i].direction);
        CHECK(std::abs(a.events[i].time - b.events[i].time) < 0.05 * fg.time_step);
        // The explicit methods locate them on their own interpolants, each error-controlled (measured:
        // 2e-6 dt apart, Dormand-Prince's error; at 1e-12 it moves to within 1e-8 dt of DOP853's).
        CHECK(std::abs(c.events[i].time - b.events[i].time) < 1e-4 * fg.time_step);
    }
    // Every sign change of the recorded penetration lies next to a reported event.
    const double* t = b.recording.channel("t");
    const double* d = b.recording.channel("cam.penetration");
    std::size_t changes = 0;
    for (std::size_t i = 1; i < b.recording.rows; ++i) {
        if ((d[i] > 0.0) == (d[i - 1] > 0.0)) continue;
        ++changes;
        bool near = false;
        for (const Event& e : b.events) near = near || (e.time > t[i - 1] - 1e-12 && e.time <= t[i] + 1e-12);
        CHECK(near);
    }
    CHECK(changes == b.events.size());
}
