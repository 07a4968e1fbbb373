// SPDX-License-Identifier: BSD-3-Clause
// Fox-Goodwin until the first contact event, DOP853 from there (solver/handover.hpp): without an event
// the run is Fox-Goodwin's under the same tolerance, value for value; with contact loss (the paper
// preset above its jump speed) the events are located where a tight DOP853 run locates them, the rows
// before the handover are Fox-Goodwin's, the run is as accurate as Fox-Goodwin alone at a quarter of
// its steps and converges with the tolerance; where Fox-Goodwin cannot meet the tolerance DOP853 takes
// over.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/handover.hpp"
#include "camfollower/solver/simulate.hpp"

using namespace camfollower;

namespace {

using Paper = Mechanism<presets::paper_dofs>;

NewmarkSettings pair_settings(double output_interval, double tolerance) {
    NewmarkSettings s;
    s.method = Method::fox_goodwin_then_dop853;
    s.beta = 1.0 / 12.0;
    s.time_step = output_interval;
    s.tolerance = tolerance;
    s.max_halvings = 12;
    return s;
}

NewmarkSettings named(NewmarkSettings s, const char* method) {
    set_method(s, method);
    set_tolerance(s, s.tolerance);
    return s;
}

Paper paper_at(double rpm) {
    CamFollowerParameters p;
    p.camshaft_speed_rpm = rpm;
    return presets::paper(p);
}

RunResult<Paper> run(const Paper& m, const NewmarkSettings& s) {
    RunOptions o;
    o.duration = m.period();
    return simulate(m, s, o);
}

// max |a_i - b_i| over the rows of channel `name`, relative to max |b_i|.
double relative_error(const RunResult<Paper>& a, const RunResult<Paper>& b, const std::string& name) {
    REQUIRE(a.recording.rows == b.recording.rows);
    double error = 0.0, peak = 0.0;
    for (std::size_t i = 0; i < a.recording.rows; ++i) {
        error = std::max(error, std::abs(a.recording.at(name, i) - b.recording.at(name, i)));
        peak = std::max(peak, std::abs(b.recording.at(name, i)));
    }
    return error / peak;
}

}  // namespace

TEST_CASE("Fox-Goodwin then DOP853 without a contact event is Fox-Goodwin under the same tolerance") {
    const Paper m = paper_at(750.0);
    const NewmarkSettings s = pair_settings(m.period() / 1024, 1e-6);
    const auto pair = run(m, s);
    const auto alone = run(m, named(s, "fox_goodwin"));
    CHECK(std::string(pair.method) == "fox_goodwin_then_dop853");
    CHECK(std::isnan(pair.handover_time));
    CHECK(pair.events.empty());
    CHECK(pair.report.stats.steps == alone.report.stats.steps);
    CHECK(pair.report.stats.rejected_steps == alone.report.stats.rejected_steps);
    REQUIRE(pair.recording.rows == alone.recording.rows);
    std::size_t differ = 0;
    for (const std::string& name : pair.recording.names)
        for (std::size_t i = 0; i < pair.recording.rows; ++i)
            differ += pair.recording.at(name, i) != alone.recording.at(name, i);
    CHECK(differ == 0u);
}

TEST_CASE("Fox-Goodwin then DOP853 with contact loss: DOP853 locates the events and keeps DOP853's accuracy") {
    // 2000 rpm, above the preset's jump speed (1329 rpm): the follower leaves the cam and lands again.
    const Paper m = paper_at(2000.0);
    const double dt = m.period() / 1024;
    const NewmarkSettings s = pair_settings(dt, 1e-8);
    const auto pair = run(m, s);
    const auto fox_goodwin = run(m, named(s, "fox_goodwin"));
    const auto dop853 = run(m, named(s, "dop853"));
    NewmarkSettings tight = named(s, "dop853");
    tight.tolerance = 1e-12;
    const auto reference = run(m, tight);

    // The events: DOP853's, both located; the handover at the start of the interval holding the first.
    REQUIRE(reference.events.size() >= 2);
    REQUIRE(pair.events.size() == reference.events.size());
    for (std::size_t k = 0; k < pair.events.size(); ++k) {
        CAPTURE(k);
        CHECK(pair.events[k].index == reference.events[k].index);
        CHECK(pair.events[k].direction == reference.events[k].direction);
        CHECK(std::abs(pair.events[k].time - reference.events[k].time) < 1e-3 * dt);
    }
    REQUIRE(std::isfinite(pair.handover_time));
    CHECK(pair.handover_time <= pair.events[0].time);
    CHECK(pair.events[0].time < pair.handover_time + dt);
    CHECK(std::abs(std::remainder(pair.handover_time, dt)) < 1e-9 * dt);  // on the output grid

    // Before the handover the rows are Fox-Goodwin's.
    std::size_t before = 0, differ = 0;
    for (std::size_t i = 0; i < pair.recording.rows && pair.recording.at("t", i) <= pair.handover_time; ++i, ++before)
        for (const std::string& name : pair.recording.names)
            differ += pair.recording.at(name, i) != fox_goodwin.recording.at(name, i);
    CHECK(before > 100u);
    CHECK(differ == 0u);

    // After the handover DOP853 carries Fox-Goodwin's error from before it through the flight, where
    // the landing amplifies it (a landing-time shift under a steep impact force): the pair is as
    // accurate as Fox-Goodwin alone, whose steps crowd at the two kinks instead, and converges as the
    // tolerance tightens.
    NewmarkSettings tighter = s;
    tighter.tolerance = 1e-10;
    const auto pair_tighter = run(m, tighter);
    for (const char* channel : {"cam.force", "a.y4"}) {  // contact force, follower acceleration
        CAPTURE(channel);
        const double e_pair = relative_error(pair, reference, channel);
        const double e_fox_goodwin = relative_error(fox_goodwin, reference, channel);
        const double e_tighter = relative_error(pair_tighter, reference, channel);
        CAPTURE(e_pair, e_fox_goodwin, e_tighter);
        CHECK(e_pair <= 2.0 * e_fox_goodwin);
        CHECK(e_tighter * 5.0 <= e_pair);
    }
    CHECK(pair.report.stats.steps * 4 < fox_goodwin.report.stats.steps);
}

TEST_CASE("Fox-Goodwin then DOP853 hands over where Fox-Goodwin cannot meet the tolerance") {
    // One halving at most: Fox-Goodwin's finest step T/8192 cannot hold 1e-10 per step through the
    // preset's rise; alone it throws there, in the pair DOP853 takes that interval over.
    const Paper m = paper_at(750.0);
    NewmarkSettings s = pair_settings(m.period() / 4096, 1e-10);
    s.max_halvings = 1;
    const auto pair = run(m, s);
    REQUIRE(std::isfinite(pair.handover_time));
    CHECK(pair.events.empty());
    RunOptions until_handover, one_more;
    until_handover.duration = pair.handover_time;
    one_more.duration = pair.handover_time + s.time_step;
    const auto alone = simulate(m, named(s, "fox_goodwin"), until_handover);
    CHECK_THROWS_AS(simulate(m, named(s, "fox_goodwin"), one_more), ConvergenceError);
    REQUIRE(alone.recording.rows > 10u);
    std::size_t differ = 0;
    for (const std::string& name : pair.recording.names)
        for (std::size_t i = 0; i < alone.recording.rows; ++i) differ += pair.recording.at(name, i) != alone.recording.at(name, i);
    CHECK(differ == 0u);
    // From there on DOP853 holds the tolerance: against a tighter DOP853 run, 1e-8 at most in force.
    NewmarkSettings tight = named(s, "dop853");
    tight.tolerance = 1e-12;
    CHECK(relative_error(pair, run(m, tight), "cam.force") < 1e-8);
}

TEST_CASE("Fox-Goodwin then DOP853 refuses settings it cannot honour, naming them") {
    const Paper m = paper_at(750.0);
    NewmarkSettings s = pair_settings(m.period() / 1024, 1e-6);
    s.beta = 0.25;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("fox_goodwin_then_dop853") && Catch::Contains("beta = 1/12"));
    s = pair_settings(m.period() / 1024, 1e-6);
    s.adaptive = false;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("adaptive = true"));
    s = pair_settings(m.period() / 1024, 1e-6);
    s.backend = Backend::sparse;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("dense backend only"));
}
