// SPDX-License-Identifier: BSD-3-Clause
// Polynomial segments from boundary conditions, custom laws inside programs, and continuity across
// segment boundaries. Truth: the 3-4-5 and 4-5-6-7 closed forms in laws.hpp (written independently of
// the solver here), the conditions themselves, and the textbook end behaviour of each law (cycloidal:
// zero acceleration, non-zero jerk at its ends; simple harmonic and constant acceleration: non-zero
// acceleration at their ends).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "angles.hpp"
#include "camfollower/motion/program.hpp"

using namespace camfollower;

namespace {

// Largest relative difference between a segment and a normalized law over the segment.
double worst_difference(const Segment& s, const MotionLaw& law, double lift) {
    const double beta = s.span();
    double worst = 0.0;
    for (int i = 0; i <= 500; ++i) {
        const double x = i / 500.0;
        const FollowerMotion m = s.lift_at(s.theta_start + beta * x);
        const LawValue v = law.evaluate(x);
        const PeakCoefficients c = law.peaks();
        worst = std::max({worst, std::abs(m.h - s.h_start - lift * v.S) / lift,
                          std::abs(m.dh - lift * v.V / beta) / (lift * c.velocity / beta),
                          std::abs(m.d2h - lift * v.A / (beta * beta)) / (lift * c.acceleration / (beta * beta)),
                          std::abs(m.d3h - lift * v.J / std::pow(beta, 3)) / (lift * c.jerk / std::pow(beta, 3))});
    }
    return worst;
}
}  // namespace

TEST_CASE("3-4-5 and 4-5-6-7 come out of their boundary conditions") {
    const double a = 30 * deg, b = 150 * deg, lift = 0.012;
    const Segment p345 = Segment::polynomial(a, b, {0.002, 0, 0}, {0.002 + lift, 0, 0});
    const Segment p4567 = Segment::polynomial(a, b, {0.002, 0, 0, 0}, {0.002 + lift, 0, 0, 0});
    CHECK(p345.law.name() == "polynomial(degree=5)");
    CHECK(p4567.law.name() == "polynomial(degree=7)");
    CHECK(worst_difference(p345, MotionLaw::polynomial_345(), lift) < 1e-12);
    CHECK(worst_difference(p4567, MotionLaw::polynomial_4567(), lift) < 1e-12);
    // Their normalized peaks are the textbook coefficients (found numerically here).
    const PeakCoefficients c = p4567.law.peaks(), t = MotionLaw::polynomial_4567().peaks();
    CHECK(c.velocity == Approx(t.velocity).epsilon(1e-10));
    CHECK(c.acceleration == Approx(t.acceleration).epsilon(1e-10));
    CHECK(c.jerk == Approx(t.jerk).epsilon(1e-10));
    CHECK(p345.law.peaks().jerk == Approx(60.0).epsilon(1e-10));  // |J| = 60 at both ends
    // The normalized form is the closed form too.
    CHECK(p4567.law.evaluate(0.3).A == Approx(MotionLaw::polynomial_4567().evaluate(0.3).A).epsilon(1e-12));
    CHECK(p345.law.has_zero_end_acceleration());
    CHECK(Segment::polynomial(a, b, {0, 0, 1e-3}, {lift, 0, 0}).law.has_zero_end_acceleration() == false);
}

TEST_CASE("general boundary conditions and interior points are met to 1e-10") {
    const double a = 1.0, b = 2.5;
    const std::vector<double> start{0.003, 0.004, -0.002, 0.01}, end{0.009, -0.001, 0.003};
    const std::vector<std::pair<double, double>> interior{{1.4, 0.006}, {2.0, 0.011}};
    const Segment s = Segment::polynomial(a, b, start, end, interior);
    REQUIRE(s.law.polynomial()->degree() == 8);
    const FollowerMotion m0 = s.lift_at(a), m1 = s.lift_at(b);
    CHECK(std::abs(m0.h - start[0]) < 1e-10);
    CHECK(std::abs(m0.dh - start[1]) < 1e-10);
    CHECK(std::abs(m0.d2h - start[2]) < 1e-10);
    CHECK(std::abs(m0.d3h - start[3]) < 1e-10);
    CHECK(std::abs(m1.h - end[0]) < 1e-10);
    CHECK(std::abs(m1.dh - end[1]) < 1e-10);
    CHECK(std::abs(m1.d2h - end[2]) < 1e-10);
    for (const auto& [t, h] : interior) CHECK(std::abs(s.lift_at(t).h - h) < 1e-10);
    // Derivatives are those of h: central differences of the evaluated lift.
    const double t = 1.7, e = 1e-4;
    CHECK(s.lift_at(t).dh == Approx((s.lift_at(t + e).h - s.lift_at(t - e).h) / (2 * e)).epsilon(1e-6));
    CHECK(s.lift_at(t).d3h == Approx((s.lift_at(t + e).d2h - s.lift_at(t - e).d2h) / (2 * e)).epsilon(1e-6));
}

TEST_CASE("a polynomial with zero net lift works inside a program") {
    // A bump over 60-120 deg returning to the dwell level, C2 both ends.
    const Segment bump = Segment::polynomial(60 * deg, 120 * deg, {0.001, 0, 0}, {0.001, 0, 0}, {{90 * deg, 0.003}});
    const MotionProgram p(
        {{MotionLaw::dwell(), 0, 60 * deg, 0.001, 0.001}, bump, {MotionLaw::dwell(), 120 * deg, 2 * pi, 0.001, 0.001}});
    CHECK(p.evaluate(90 * deg).h == Approx(0.003).epsilon(1e-12));
    CHECK(p.max_lift() >= 0.003);
    CHECK(p.max_lift() < 0.0031);
    REQUIRE_THROWS_WITH(bump.law.evaluate(0.5), Catch::Contains("no net lift"));
    const PeakCoefficients c = bump.law.peaks();
    CHECK(std::isinf(c.acceleration));
    CHECK(bump.law.lift_peaks().acceleration.value > 0.0);
    CHECK(p.continuity().continuous_through() == 2);  // h''' of a degree-6 bump is not zero at its ends
}

TEST_CASE("impossible or bad polynomial conditions are refused, naming the parameter") {
    const double a = 1.0, b = 2.0;
    REQUIRE_THROWS_WITH(Segment::polynomial(a, a, {0}, {0}),
                        Catch::Contains("theta_end - theta_start must be finite and at least 1e-06 rad"));
    REQUIRE_THROWS_WITH(Segment::polynomial(b, a, {0}, {0}),
                        Catch::Contains("theta_end - theta_start must be finite and at least 1e-06 rad"));
    REQUIRE_THROWS_WITH(Segment::polynomial(std::nan(""), b, {0}, {0}), Catch::Contains("theta_start"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {}, {0}), Catch::Contains("start must hold at least"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0}, {}), Catch::Contains("end must hold at least"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0, std::nan("")}, {0}), Catch::Contains("start[1]"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0}, {0}, {{a, 0.001}}),
                        Catch::Contains("interior[0]") && Catch::Contains("strictly inside"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0}, {0}, {{1.5, 0.001}, {2.5, 0.0}}),
                        Catch::Contains("interior[1]") && Catch::Contains("strictly inside"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0}, {0}, {{1.5, 0.001}, {1.5, 0.002}}),
                        Catch::Contains("interior[1] repeats the angle of interior[0]"));
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, {0}, {0}, {{1.5, std::nan("")}}), Catch::Contains("interior[0]"));
    // Forty conditions: a degree-39 polynomial no double-precision solve can pin down.
    REQUIRE_THROWS_WITH(Segment::polynomial(a, b, std::vector<double>(20, 0.0), std::vector<double>(20, 1e-3)),
                        Catch::Contains("start/end/interior") && Catch::Contains("ill-conditioned"));
}

TEST_CASE("continuity: dwell into constant acceleration jumps in h''") {
    const MotionProgram p({{MotionLaw::dwell(), 0, 30 * deg, 0, 0},
                           {MotionLaw::constant_acceleration(), 30 * deg, 180 * deg, 0, 0.01},
                           {MotionLaw::dwell(), 180 * deg, 210 * deg, 0.01, 0.01},
                           {MotionLaw::constant_acceleration(), 210 * deg, 2 * pi, 0.01, 0}});
    const ContinuityReport c = p.continuity();
    REQUIRE(c.boundaries.size() == 4);
    CHECK(c.boundaries[0].left_segment == 0);
    CHECK(c.boundaries[0].right_segment == 1);
    CHECK(c.boundaries[0].theta == Approx(30 * deg));
    CHECK(c.boundaries[0].continuous_through == 1);
    // The jump is the textbook start acceleration 4 L / beta^2.
    CHECK(c.boundaries[0].jump[2] == Approx(4 * 0.01 / std::pow(150 * deg, 2)).epsilon(1e-12));
    CHECK(c.boundaries[3].right_segment == 0);  // the wrap
    CHECK(c.continuous_through() == 1);
    CHECK_NOTHROW(p.require_continuity(1));
    REQUIRE_THROWS_WITH(p.require_continuity(2), Catch::Contains("segments[0]") && Catch::Contains("segments[1]") &&
                                                     Catch::Contains("at 30 deg") && Catch::Contains("h''"));
    REQUIRE_THROWS_WITH(p.require_continuity(4), Catch::Contains("order must be in [0, 3]"));
}

TEST_CASE("continuity: cycloidal is continuous through h'', simple harmonic jumps in h''") {
    const auto program = [](const MotionLaw& law) {
        return MotionProgram({{MotionLaw::dwell(), 0, 30 * deg, 0, 0},
                              {law, 30 * deg, 180 * deg, 0, 0.01},
                              {MotionLaw::dwell(), 180 * deg, 210 * deg, 0.01, 0.01},
                              {law, 210 * deg, 2 * pi, 0.01, 0}});
    };
    const MotionProgram cycloidal = program(MotionLaw::cycloidal());
    CHECK(cycloidal.continuity().continuous_through() == 2);  // J(0) = 4 pi^2 L / beta^3: jerk jumps
    CHECK_NOTHROW(cycloidal.require_continuity(2));
    REQUIRE_THROWS_WITH(cycloidal.require_continuity(3), Catch::Contains("h''' (jerk"));
    const MotionProgram harmonic = program(MotionLaw::simple_harmonic());
    CHECK(harmonic.continuity().continuous_through() == 1);
    REQUIRE_THROWS_WITH(harmonic.require_continuity(2), Catch::Contains("h'' (acceleration"));
    CHECK(program(MotionLaw::polynomial_4567()).continuity().continuous_through() == 3);
    CHECK(MotionProgram::paper_default().continuity().continuous_through() == 2);
    // A level mismatch cannot be built (the program refuses it), so h jumps only through a profile-free
    // design never; a polynomial joining with a wrong slope shows up as order 0.
    const MotionProgram kinked({{MotionLaw::dwell(), 0, 30 * deg, 0, 0},
                                Segment::polynomial(30 * deg, 180 * deg, {0, 1e-3}, {0.01, 0, 0}),
                                {MotionLaw::cycloidal(), 180 * deg, 2 * pi, 0.01, 0}});
    CHECK(kinked.continuity().boundaries[0].continuous_through == 0);
    REQUIRE_THROWS_WITH(kinked.require_continuity(1), Catch::Contains("h' (velocity"));
}
