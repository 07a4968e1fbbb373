// SPDX-License-Identifier: BSD-3-Clause
// Speed program: the closed-form angle against a quadrature of the speed, the acceleration against a
// difference of it, continuity at the ramps' ends, periodicity, the inverse, validation.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "camfollower/motion/speed_program.hpp"

using namespace camfollower;

namespace {

// Composite Simpson of the program's speed over [0, t] with n (even) intervals.
double integrated_angle(const SpeedProgram& p, double t, int n = 20000) {
    const double h = t / n;
    double sum = p.rate(0.0) + p.rate(t);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * p.rate(i * h);
    return sum * h / 3.0;
}

std::vector<SpeedProgram> programs() {
    const double w = 60.0;  // rad/s
    return {
        SpeedProgram(0.0, {{0.0, 0.5, w, RampShape::smooth}}),
        SpeedProgram(10.0, {{0.1, 0.4, w, RampShape::linear}}),
        SpeedProgram(0.0, {{0.0, 0.3, w, RampShape::smooth}, {0.8, 0.25, 0.0, RampShape::smooth}}),
        SpeedProgram(w, {}, SpeedModulation{0.2, 3, 0.7}),
        SpeedProgram(5.0, {{0.05, 0.3, w, RampShape::smooth}}, SpeedModulation{-0.1, 2, 0.0}),
    };
}
}  // namespace

TEST_CASE("speed program: the angle is the integral of the speed, the acceleration its derivative") {
    int k = 0;
    for (const SpeedProgram& p : programs()) {
        INFO("program " << k++);
        for (double t : {0.05, 0.2, 0.37, 0.47, 0.9, 1.3}) {  // none where a linear ramp's acceleration steps
            INFO("t = " << t);
            // Simpson across the ramps' kinks in the acceleration converges as h^2: 1e-9 rad is far below
            // any cam angle that matters and far above the quadrature's error.
            CHECK(p.angle(t) == Approx(integrated_angle(p, t)).margin(1e-9));
            const double h = 1e-6;
            const double difference = (p.rate(t + h) - p.rate(t - h)) / (2.0 * h);
            CHECK(p.at(t).acceleration == Approx(difference).margin(1e-5 * (1.0 + std::abs(difference))));
        }
    }
}

TEST_CASE("speed program: speed continuous at the ramps' ends, a smooth ramp's acceleration too") {
    const double w = 60.0;
    const SpeedProgram smooth(0.0, {{0.2, 0.5, w, RampShape::smooth}});
    const SpeedProgram linear(0.0, {{0.2, 0.5, w, RampShape::linear}});
    for (double t : {0.2, 0.7}) {
        const double e = 1e-9;
        CHECK(smooth.rate(t - e) == Approx(smooth.rate(t + e)).margin(1e-6));
        CHECK(smooth.at(t - e).acceleration == Approx(smooth.at(t + e).acceleration).margin(1e-5));
        CHECK(linear.rate(t - e) == Approx(linear.rate(t + e)).margin(1e-6));
    }
    // The linear ramp's acceleration steps from 0 to w / T; the smooth one peaks at twice that mid-ramp.
    CHECK(linear.at(0.3).acceleration == Approx(w / 0.5));
    CHECK(smooth.at(0.45).acceleration == Approx(2.0 * w / 0.5));
    CHECK(smooth.rate(0.45) == Approx(0.5 * w));
    CHECK(smooth.rate(5.0) == w);
    CHECK(smooth.nominal_speed() == w);
    CHECK_FALSE(smooth.periodic());
}

TEST_CASE("speed program: a modulated constant speed repeats every revolution") {
    const double w = 40.0, T = two_pi / w;
    const SpeedProgram p(w, {}, SpeedModulation{0.3, 2, 0.4});
    CHECK(p.periodic());
    CHECK_FALSE(p.is_constant());
    CHECK(p.nominal_speed() == w);
    for (double t : {0.0, 0.01, 0.1, 0.123}) {
        CHECK(p.angle(t + T) == Approx(p.angle(t) + two_pi).margin(1e-12));
        CHECK(p.rate(t + T) == Approx(p.rate(t)).margin(1e-9));
    }
    // Extremes of the speed: w (1 +- 0.3).
    double lo = 1e9, hi = 0.0;
    for (int i = 0; i <= 4000; ++i) {
        const double r = p.rate(T * i / 4000.0);
        lo = std::min(lo, r), hi = std::max(hi, r);
    }
    CHECK(lo == Approx(0.7 * w).epsilon(1e-5));
    CHECK(hi == Approx(1.3 * w).epsilon(1e-5));
}

TEST_CASE("speed program: time_at_angle inverts the angle") {
    for (const SpeedProgram& p : programs()) {
        const double last = p.angle(1.0);
        for (double f : {1e-3, 0.1, 0.5, 0.99}) {
            const double angle = f * last, t = p.time_at_angle(angle);
            CHECK(p.angle(t) == Approx(angle).margin(1e-10));
            CHECK(p.angle(t * (1.0 - 1e-9) - 1e-12) < angle);  // the first time it is reached
        }
    }
    const SpeedProgram constant = SpeedProgram::constant(50.0);
    CHECK(constant.time_at_angle(-1.0) == Approx(-0.02));
    // A program that stops reaches a last angle.
    const SpeedProgram stops(0.0, {{0.0, 0.3, 60.0, RampShape::smooth}, {0.5, 0.3, 0.0, RampShape::smooth}});
    const double last = stops.angle(10.0);
    CHECK(last == Approx(0.5 * 60 * 0.3 + 60 * 0.2 + 0.5 * 60 * 0.3).epsilon(1e-12));
    CHECK_THROWS_WITH(stops.time_at_angle(last + 0.1), Catch::Contains("never reached") && Catch::Contains("stops"));
    CHECK_THROWS_WITH(stops.time_at_angle(-0.1), Catch::Contains("starts at angle 0"));
}

TEST_CASE("speed program: scaled to another nominal speed") {
    // (Without a modulation: a modulation follows the base angle, which the scaling changes too.)
    const SpeedProgram p(10.0, {{0.1, 0.4, 60.0, RampShape::smooth}});
    const SpeedProgram q = p.scaled_to(90.0);
    CHECK(q.nominal_speed() == Approx(90.0));
    CHECK(q.initial_speed() == Approx(15.0));
    for (double t : {0.0, 0.2, 0.3, 1.0}) CHECK(q.rate(t) == Approx(1.5 * p.rate(t)).epsilon(1e-12));
}

TEST_CASE("speed program: bad input names the value and the range") {
    using R = std::vector<SpeedRamp>;
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{{0.0, 0.5, -1.0}}),
                      Catch::Contains("ramp 1 to_speed") && Catch::Contains("reversing"));
    CHECK_THROWS_WITH(SpeedProgram(-3.0, R{}), Catch::Contains("initial speed") && Catch::Contains("[0, "));
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{{0.0, 0.5, 10.0}, {0.4, 0.5, 20.0}}),
                      Catch::Contains("ramp 2 starts at 0.4 s") && Catch::Contains("overlap"));
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{{-1.0, 0.5, 10.0}}), Catch::Contains("ramp 1 starts at -1"));
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{{0.0, 0.0, 10.0}}), Catch::Contains("ramp 1 duration"));
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{{0.0, NAN, 10.0}}), Catch::Contains("ramp 1 duration"));
    CHECK_THROWS_WITH(SpeedProgram(0.0, R{}), Catch::Contains("never turns"));
    CHECK_THROWS_WITH(SpeedProgram(10.0, R{}, SpeedModulation{1.0, 1, 0.0}),
                      Catch::Contains("amplitude") && Catch::Contains("(-1, 1)"));
    CHECK_THROWS_WITH(SpeedProgram(10.0, R{}, SpeedModulation{0.1, 0, 0.0}), Catch::Contains("harmonic"));
    CHECK_THROWS_WITH(SpeedProgram(10.0, R{}).scaled_to(-5.0), Catch::Contains("camshaft speed"));
}
