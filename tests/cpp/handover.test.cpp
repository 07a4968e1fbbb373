// SPDX-License-Identifier: BSD-3-Clause
// Fox-Goodwin unless the run meets a contact event, DOP853 when it does (solver/handover.hpp,
// Method::fox_goodwin_or_dop853): without an event the run is Fox-Goodwin's under the same tolerance,
// value for value; with contact loss (the paper preset above its jump speed) it is DOP853's, value for
// value, its events where a tight DOP853 run locates them, far more accurate than Fox-Goodwin alone,
// and the restart time is the start of the interval holding the first event; where Fox-Goodwin cannot
// meet the tolerance the run is DOP853's too.
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
    s.method = Method::fox_goodwin_or_dop853;
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

// The number of recorded values that differ between two runs (rows must match).
std::size_t differing_values(const RunResult<Paper>& a, const RunResult<Paper>& b) {
    REQUIRE(a.recording.rows == b.recording.rows);
    REQUIRE(a.recording.names == b.recording.names);
    std::size_t differ = 0;
    for (const std::string& name : a.recording.names)
        for (std::size_t i = 0; i < a.recording.rows; ++i) differ += a.recording.at(name, i) != b.recording.at(name, i);
    return differ;
}

}  // namespace

TEST_CASE("Fox-Goodwin or DOP853 without a contact event is Fox-Goodwin under the same tolerance") {
    const Paper m = paper_at(750.0);
    const NewmarkSettings s = pair_settings(m.period() / 1024, 1e-6);
    const auto pair = run(m, s);
    const auto alone = run(m, named(s, "fox_goodwin"));
    CHECK(std::string(pair.method) == "fox_goodwin");
    CHECK(std::isnan(pair.restart_time));
    CHECK(pair.events.empty());
    CHECK(pair.report.stats.steps == alone.report.stats.steps);
    CHECK(pair.report.stats.rejected_steps == alone.report.stats.rejected_steps);
    CHECK(differing_values(pair, alone) == 0u);
}

TEST_CASE("Fox-Goodwin or DOP853 with contact loss is DOP853's run, its events located") {
    // 2000 rpm, above the preset's jump speed (1329 rpm): the follower leaves the cam and lands again.
    const Paper m = paper_at(2000.0);
    const double dt = m.period() / 1024;
    const NewmarkSettings s = pair_settings(dt, 1e-8);
    const auto pair = run(m, s);
    const auto dop853 = run(m, named(s, "dop853"));
    const auto fox_goodwin = run(m, named(s, "fox_goodwin"));
    NewmarkSettings tight = named(s, "dop853");
    tight.tolerance = 1e-12;
    const auto reference = run(m, tight);

    CHECK(std::string(pair.method) == "dop853");
    CHECK(pair.report.stats.steps == dop853.report.stats.steps);
    CHECK(differing_values(pair, dop853) == 0u);
    CHECK_THAT(pair.method_choice, Catch::Contains("run again from the start by dop853"));
    // The events: both located where the tight run locates them; the restart time is the start of the
    // output interval in which Fox-Goodwin met the first.
    REQUIRE(reference.events.size() >= 2);
    REQUIRE(pair.events.size() == reference.events.size());
    for (std::size_t k = 0; k < pair.events.size(); ++k) {
        CAPTURE(k);
        CHECK(pair.events[k].index == reference.events[k].index);
        CHECK(pair.events[k].direction == reference.events[k].direction);
        CHECK(std::abs(pair.events[k].time - reference.events[k].time) < 1e-3 * dt);
    }
    REQUIRE(std::isfinite(pair.restart_time));
    CHECK(pair.restart_time <= pair.events[0].time);
    CHECK(pair.events[0].time < pair.restart_time + dt);
    CHECK(std::abs(std::remainder(pair.restart_time, dt)) < 1e-9 * dt);  // on the output grid
    // Why DOP853 from the start: Fox-Goodwin alone is second order at the kinks, and the error it
    // leaves before the loss is amplified by the landing.
    for (const char* channel : {"cam.force", "a.y4"}) {  // contact force, follower acceleration
        CAPTURE(channel);
        const double e_pair = relative_error(pair, reference, channel);
        const double e_fox_goodwin = relative_error(fox_goodwin, reference, channel);
        CAPTURE(e_pair, e_fox_goodwin);
        CHECK(e_pair * 10.0 <= e_fox_goodwin);
    }
}

TEST_CASE("Fox-Goodwin or DOP853 is DOP853's run where Fox-Goodwin cannot meet the tolerance") {
    // One halving at most: Fox-Goodwin's finest step T/8192 cannot hold 1e-10 per step through the
    // preset's rise; alone it throws there, in the pair DOP853 runs instead.
    const Paper m = paper_at(750.0);
    NewmarkSettings s = pair_settings(m.period() / 4096, 1e-10);
    s.max_halvings = 1;
    const auto pair = run(m, s);
    CHECK(std::string(pair.method) == "dop853");
    CHECK(differing_values(pair, run(m, named(s, "dop853"))) == 0u);
    REQUIRE(std::isfinite(pair.restart_time));
    RunOptions until_restart, one_more;
    until_restart.duration = pair.restart_time;
    one_more.duration = pair.restart_time + s.time_step;
    CHECK_NOTHROW(simulate(m, named(s, "fox_goodwin"), until_restart));
    CHECK_THROWS_AS(simulate(m, named(s, "fox_goodwin"), one_more), ConvergenceError);
}

TEST_CASE("Fox-Goodwin or DOP853 refuses settings it cannot honour, naming them") {
    const Paper m = paper_at(750.0);
    NewmarkSettings s = pair_settings(m.period() / 1024, 1e-6);
    s.beta = 0.25;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("fox_goodwin_or_dop853") && Catch::Contains("beta = 1/12"));
    s = pair_settings(m.period() / 1024, 1e-6);
    s.adaptive = false;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("adaptive = true"));
    s = pair_settings(m.period() / 1024, 1e-6);
    s.backend = Backend::sparse;
    CHECK_THROWS_WITH(run(m, s), Catch::Contains("dense backend only"));
}
