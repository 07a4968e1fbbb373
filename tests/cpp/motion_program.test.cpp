// SPDX-License-Identifier: BSD-3-Clause
// Motion program: paper Table 1, continuity at every boundary, periodicity, validation.
#include <catch2/catch.hpp>

#include <cmath>

#include "angles.hpp"
#include "camfollower/motion/program.hpp"

using namespace camfollower;

namespace {

// Left and right limits of h and its derivatives at theta.
std::pair<FollowerMotion, FollowerMotion> limits(const MotionProgram& p, double theta, double eps = 1e-11) {
    return {p.evaluate(theta - eps), p.evaluate(theta + eps)};
}
}  // namespace

TEST_CASE("paper Table 1 program: levels, lifts and the rise acceleration peak") {
    const MotionProgram p = MotionProgram::paper_default();
    REQUIRE(p.segments().size() == 4);
    CHECK(p.evaluate(15 * deg).h == 0.0);
    CHECK(p.evaluate(195 * deg).h == Approx(0.010).epsilon(1e-14));
    CHECK(p.evaluate(105 * deg).h == Approx(0.005).epsilon(1e-13));  // symmetric law: half lift at mid-rise
    CHECK(p.evaluate(285 * deg).h == Approx(0.005).epsilon(1e-13));
    // Modified trapezoid rise over 150 deg: peak h'' = 10 mm * (8 pi / (pi + 2)) / beta^2,
    // reached at x = 1/8..3/8, i.e. theta = 48.75..86.25 deg.
    const double beta = 150 * deg;
    const double expected = 0.010 * (8 * pi / (pi + 2)) / (beta * beta);
    CHECK(p.evaluate(60 * deg).d2h == Approx(expected).epsilon(1e-12));
    CHECK(p.max_lift() == 0.010);
    CHECK(p.min_lift() == 0.0);
}

TEST_CASE("paper program is C2: h, h' and h'' continuous at every segment boundary") {
    const MotionProgram p = MotionProgram::paper_default();
    for (double b : {0.0, 30 * deg, 180 * deg, 210 * deg, 360 * deg}) {
        INFO("boundary at " << b / deg << " deg");
        const auto [l, r] = limits(p, b);
        CHECK(std::abs(l.h - r.h) < 1e-12);
        CHECK(std::abs(l.dh - r.dh) < 1e-10);
        CHECK(std::abs(l.d2h - r.d2h) < 1e-8);
    }
}

TEST_CASE("constant acceleration program: h'' jumps by the documented 4 dh / beta^2") {
    const double lift = 0.02, beta = 120 * deg;
    const MotionProgram p({{MotionLaw::constant_acceleration(), 0.0, beta, 0.0, lift},
                           {MotionLaw::dwell(), beta, 180 * deg, lift, lift},
                           {MotionLaw::cycloidal(), 180 * deg, 2 * pi, lift, 0.0}});
    const auto [l, r] = limits(p, 0.0);
    CHECK(std::abs(l.dh - r.dh) < 1e-10);  // velocity still continuous
    CHECK(r.d2h - l.d2h == Approx(4 * lift / (beta * beta)).epsilon(1e-9));
    const auto [ml, mr] = limits(p, beta / 2);
    CHECK(ml.d2h - mr.d2h == Approx(8 * lift / (beta * beta)).epsilon(1e-9));
}

TEST_CASE("derivatives of h against central differences over a whole revolution") {
    const MotionProgram p = MotionProgram::paper_default();
    const double h = 1e-6;
    for (int k = 0; k < 720; ++k) {
        const double t = (k + 0.29) * 0.5 * deg;
        const auto lo = p.evaluate(t - h), mid = p.evaluate(t), hi = p.evaluate(t + h);
        INFO("theta = " << t / deg << " deg");
        CHECK((hi.h - lo.h) / (2 * h) == Approx(mid.dh).margin(1e-9));
        CHECK((hi.dh - lo.dh) / (2 * h) == Approx(mid.d2h).margin(1e-8));
    }
}

TEST_CASE("the program is periodic in theta") {
    const MotionProgram p = MotionProgram::paper_default();
    for (double t : {0.1, 1.0, 3.0, 5.5}) {
        for (int k : {-3, -1, 1, 10, 1000}) {
            const auto a = p.evaluate(t), b = p.evaluate(t + 2 * pi * k);
            CHECK(b.h == Approx(a.h).margin(1e-12));
            CHECK(b.d2h == Approx(a.d2h).margin(1e-9));
        }
    }
    CHECK(p.segment_index(-1e-3) == 3);
    CHECK(p.segment_index(2 * pi) == 0);
}

TEST_CASE("invalid programs are rejected with the parameter named") {
    const MotionLaw mt = MotionLaw::modified_trapezoid(), dw = MotionLaw::dwell();
    SECTION("gap") {
        CHECK_THROWS_WITH(MotionProgram({{dw, 0.0, 30 * deg, 0, 0}, {mt, 40 * deg, 2 * pi, 0, 0}}),
                          Catch::Contains("segments[1].theta_start") && Catch::Contains("gap"));
    }
    SECTION("overlap") {
        CHECK_THROWS_WITH(MotionProgram({{dw, 0.0, 30 * deg, 0, 0}, {mt, 20 * deg, 2 * pi, 0, 0}}),
                          Catch::Contains("overlaps"));
    }
    SECTION("does not start at 0") {
        CHECK_THROWS_WITH(MotionProgram({{mt, 1 * deg, 2 * pi, 0, 0}}), Catch::Contains("start at 0"));
    }
    SECTION("does not reach 360") {
        CHECK_THROWS_WITH(MotionProgram({{dw, 0, 300 * deg, 0, 0}}), Catch::Contains("end at 360"));
    }
    SECTION("beta <= 0") {
        CHECK_THROWS_WITH(MotionProgram({{dw, 0, 0, 0, 0}, {dw, 0, 2 * pi, 0, 0}}),
                          Catch::Contains("segments[0] spans 0 rad") && Catch::Contains("must be at least 1e-06 rad"));
    }
    SECTION("levels do not chain") {
        CHECK_THROWS_WITH(MotionProgram({{mt, 0, pi, 0, 0.01}, {mt, pi, 2 * pi, 0.02, 0.0}}),
                          Catch::Contains("segments[1].h_start") && Catch::Contains("levels must chain"));
    }
    SECTION("does not close") {
        CHECK_THROWS_WITH(MotionProgram({{mt, 0, pi, 0, 0.01}, {dw, pi, 2 * pi, 0.01, 0.01}}),
                          Catch::Contains("close over one revolution"));
    }
    SECTION("dwell with a lift") {
        CHECK_THROWS_WITH(MotionProgram({{dw, 0, pi, 0, 0.01}, {mt, pi, 2 * pi, 0.01, 0.0}}),
                          Catch::Contains("a dwell must have h_end == h_start"));
    }
    SECTION("non-finite") {
        CHECK_THROWS_WITH(MotionProgram({{mt, 0, pi, 0, std::nan("")}, {mt, pi, 2 * pi, 0, 0}}),
                          Catch::Contains("segments[0].h_start/h_end must be in"));
        CHECK_THROWS_WITH(MotionProgram::paper_default().evaluate(INFINITY), Catch::Contains("theta must be finite"));
    }
    SECTION("empty") { CHECK_THROWS_AS(MotionProgram({}), std::invalid_argument); }
    SECTION("a segment shorter than the snapping tolerance cannot carry a step in the lift") {
        // Boundaries 4e-10 rad apart pass the 1e-9 rad tiling check; snapped, the rise would span
        // -5e-10 rad (or 0) and its 1 mm lift would be a step in h.
        const double r0 = pi - 9e-10, r1 = pi - 5e-10;
        CHECK_THROWS_WITH(MotionProgram({{dw, 0, pi, 0, 0},
                                         {mt, r0, r1, 0, 1e-3},
                                         {dw, r1, 2 * pi - 0.5, 1e-3, 1e-3},
                                         {mt, 2 * pi - 0.5, 2 * pi, 1e-3, 0}}),
                          Catch::Contains("segments[1] spans") && Catch::Contains("at least 1e-06 rad"));
        CHECK_THROWS_WITH(MotionProgram({{mt, 0, 1e-300, 0, 1e-3}, {mt, 1e-300, 2 * pi, 1e-3, 0}}),
                          Catch::Contains("segments[0] spans"));
        CHECK_NOTHROW(MotionProgram({{mt, 0, 2e-6, 0, 1e-9}, {mt, 2e-6, 2 * pi, 1e-9, 0}}));
    }
    SECTION("a segment on its own, at construction and evaluation") {
        CHECK_THROWS_WITH(Segment({mt, 1.0, 0.5, 0, 1e-3}).validate(), Catch::Contains("segment spans -0.5 rad"));
        CHECK_THROWS_WITH(Segment({mt, NAN, 0.5, 0, 1e-3}).validate(),
                          Catch::Contains("theta_start/theta_end must be finite"));
        CHECK_THROWS_WITH(Segment({dw, 0.0, 0.5, 0, 1e-3}).validate(),
                          Catch::Contains("a dwell must have h_end == h_start"));
        CHECK_THROWS_WITH(Segment::polynomial(0.0, 1e-300, {0.0, 0.0}, {1e-3, 0.0}),
                          Catch::Contains("polynomial segment: theta_end - theta_start"));
        const Segment rise{mt, 0.0, 1.0, 0.0, 1e-3};
        CHECK_THROWS_WITH(rise.lift_at(NAN), Catch::Contains("theta = nan rad is outside the segment"));
        CHECK_THROWS_WITH(rise.lift_at(1.5), Catch::Contains("theta = 1.5 rad is outside the segment [0, 1] rad"));
        CHECK_THROWS_WITH(MotionLaw::sine_constant_cosine(1e-310, 0.5, 0.5 - 1e-310),
                          Catch::Contains("b (sine fraction) must be 0 or at least 1e-06"));
        CHECK_THROWS_WITH(ProfileError::dent(1.0, 5e-324, 1e-5), Catch::Contains("dent width must be in [1e-06 rad"));
        // The smallest span and fraction allowed still evaluate to finite values.
        const Segment thin{MotionLaw::sine_constant_cosine(1e-6, 0.5, 0.5 - 1e-6), 0.0, 1e-6, 0.0, 1e-3};
        for (double x : {0.0, 1e-12, 2.5e-7, 5e-7, 1e-6}) {
            const FollowerMotion m = thin.lift_at(x);
            CHECK((std::isfinite(m.h) && std::isfinite(m.dh) && std::isfinite(m.d2h) && std::isfinite(m.d3h)));
        }
    }
    SECTION("lifts beyond a kilometre") {
        CHECK_THROWS_WITH(MotionProgram({{mt, 0, pi, 0, 1e154}, {mt, pi, 2 * pi, 1e154, 0}}),
                          Catch::Contains("segments[0].h_start/h_end must be in [-1000, 1000] m"));
    }
}
