// SPDX-License-Identifier: BSD-3-Clause
// Motion laws against textbook closed forms (Norton, Cam Design and Manufacturing Handbook,
// table of peak coefficients; the closed forms below are derived by hand from each law's definition,
// not read from the code), against finite differences, and against each other.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "camfollower/motion/laws.hpp"

using camfollower::MotionLaw;
using camfollower::pi;

namespace {

struct Textbook {
    const char* name;
    MotionLaw law;
    double cv, ca, cj;
};

std::vector<Textbook> textbook_laws() {
    const double inf = std::numeric_limits<double>::infinity();
    return {
        {"simple harmonic", MotionLaw::simple_harmonic(), pi / 2, pi * pi / 2, pi * pi * pi / 2},
        {"cycloidal", MotionLaw::cycloidal(), 2.0, 2 * pi, 4 * pi * pi},
        // modified trapezoid: S(1/2) = (2 + pi) / (16 pi) per unit Ca
        {"modified trapezoid", MotionLaw::modified_trapezoid(), 2.0, 8 * pi / (pi + 2), 32 * pi * pi / (pi + 2)},
        // modified sine: S(1/2) = (pi + 4) / (8 pi^2) per unit Ca
        {"modified sine", MotionLaw::modified_sine(), 4 * pi / (pi + 4), 4 * pi * pi / (pi + 4),
         16 * pi * pi * pi / (pi + 4)},
        // 3-4-5: A peaks where x(1-x) = 1/6, 1 - 2x = 1/sqrt(3)
        {"3-4-5 polynomial", MotionLaw::polynomial_345(), 15.0 / 8.0, 10.0 / std::sqrt(3.0), 60.0},
        // 4-5-6-7: A peaks where x(1-x) = 1/5, 1 - 2x = 1/sqrt(5)
        {"4-5-6-7 polynomial", MotionLaw::polynomial_4567(), 35.0 / 16.0, 84.0 * std::sqrt(5.0) / 25.0, 52.5},
        {"constant acceleration", MotionLaw::constant_acceleration(), 2.0, 4.0, inf},
    };
}

// Peaks found by brute force over the law's own evaluate(): a second, independent route.
camfollower::PeakCoefficients sampled_peaks(const MotionLaw& law, int n = 400000) {
    camfollower::PeakCoefficients p{0, 0, 0};
    for (int k = 0; k <= n; ++k) {
        const auto v = law.evaluate(static_cast<double>(k) / n);
        p.velocity = std::max(p.velocity, std::abs(v.V));
        p.acceleration = std::max(p.acceleration, std::abs(v.A));
        p.jerk = std::max(p.jerk, std::abs(v.J));
    }
    return p;
}

}  // namespace

TEST_CASE("peak coefficients match textbook closed forms to 1e-12") {
    for (const auto& t : textbook_laws()) {
        INFO(t.name);
        const auto p = t.law.peaks();
        CHECK(p.velocity == Approx(t.cv).epsilon(1e-12));
        CHECK(p.acceleration == Approx(t.ca).epsilon(1e-12));
        if (std::isinf(t.cj)) CHECK(std::isinf(p.jerk));
        else CHECK(p.jerk == Approx(t.cj).epsilon(1e-12));
    }
    // Rounded values printed in Norton's table, as a sanity check on the closed forms above.
    CHECK(MotionLaw::modified_trapezoid().peaks().acceleration == Approx(4.888).margin(5e-4));
    CHECK(MotionLaw::modified_sine().peaks().acceleration == Approx(5.528).margin(5e-4));
    CHECK(MotionLaw::modified_sine().peaks().velocity == Approx(1.760).margin(5e-4));
    CHECK(MotionLaw::polynomial_4567().peaks().acceleration == Approx(7.513).margin(5e-4));
}

TEST_CASE("peak coefficients agree with brute-force sampling of the law") {
    for (const auto& t : textbook_laws()) {
        INFO(t.name);
        const auto exact = t.law.peaks();
        const auto sampled = sampled_peaks(t.law);
        CHECK(sampled.velocity == Approx(exact.velocity).epsilon(1e-9));
        CHECK(sampled.acceleration == Approx(exact.acceleration).epsilon(1e-9));
        if (std::isfinite(exact.jerk)) CHECK(sampled.jerk == Approx(exact.jerk).epsilon(1e-9));
    }
}

TEST_CASE("every law starts at 0 and ends at 1 with zero velocity") {
    for (const auto& t : textbook_laws()) {
        INFO(t.name);
        const auto a = t.law.evaluate(0.0), b = t.law.evaluate(1.0);
        CHECK(a.S == Approx(0.0).margin(1e-15));
        CHECK(b.S == Approx(1.0).epsilon(1e-14));
        CHECK(a.V == Approx(0.0).margin(1e-14));
        CHECK(b.V == Approx(0.0).margin(1e-14));
        if (t.law.has_zero_end_acceleration()) {
            CHECK(a.A == Approx(0.0).margin(1e-12));
            CHECK(b.A == Approx(0.0).margin(1e-12));
        }
    }
    CHECK(MotionLaw::dwell().evaluate(0.3).S == 0.0);
}

TEST_CASE("V, A, J are the derivatives of S, V, A (central differences)") {
    const double h = 1e-6;
    for (const auto& t : textbook_laws()) {
        INFO(t.name);
        for (int k = 1; k < 50; ++k) {
            const double x = (k + 0.37) / 51.0;
            // Skip points within h of a piece boundary of the SCC family (jerk may jump there).
            bool near_kink = false;
            for (double xb : {0.125, 0.375, 0.5, 0.625, 0.875}) near_kink |= std::abs(x - xb) < 10 * h;
            if (near_kink) continue;
            const auto lo = t.law.evaluate(x - h), mid = t.law.evaluate(x), hi = t.law.evaluate(x + h);
            INFO("x = " << x);
            CHECK((hi.S - lo.S) / (2 * h) == Approx(mid.V).margin(1e-7 * (1 + t.cv)));
            CHECK((hi.V - lo.V) / (2 * h) == Approx(mid.A).margin(1e-6 * (1 + t.ca)));
            if (std::isfinite(t.cj)) CHECK((hi.A - lo.A) / (2 * h) == Approx(mid.J).margin(1e-5 * (1 + t.cj)));
        }
    }
}

TEST_CASE("the sine-constant-cosine family reproduces the classical closed forms") {
    struct Pair {
        MotionLaw family, closed;
    };
    const Pair pairs[] = {
        {MotionLaw::sine_constant_cosine(0.5, 0.0, 0.5), MotionLaw::cycloidal()},
        {MotionLaw::sine_constant_cosine(0.0, 0.0, 1.0), MotionLaw::simple_harmonic()},
        {MotionLaw::sine_constant_cosine(0.0, 1.0, 0.0), MotionLaw::constant_acceleration()},
    };
    for (const auto& p : pairs) {
        INFO(p.family.name() << " vs " << p.closed.name());
        for (int k = 0; k <= 200; ++k) {
            const double x = k / 200.0;
            if (p.closed.kind() == camfollower::LawKind::constant_acceleration && k == 100) continue;
            const auto f = p.family.evaluate(x), c = p.closed.evaluate(x);
            CHECK(f.S == Approx(c.S).margin(1e-14));
            CHECK(f.V == Approx(c.V).margin(1e-13));
            CHECK(f.A == Approx(c.A).margin(1e-12));
            CHECK(f.J == Approx(c.J).margin(1e-10));
        }
    }
}

TEST_CASE("S, V and A are continuous across the SCC piece boundaries") {
    const double eps = 1e-10;
    for (const MotionLaw& law : {MotionLaw::modified_trapezoid(), MotionLaw::modified_sine(),
                                 MotionLaw::sine_constant_cosine(0.3, 0.3, 0.4)}) {
        INFO(law.name());
        const double b = law.b(), d = law.d();
        for (double xb : {b / 2, (1 - d) / 2, 0.5, (1 + d) / 2, 1 - b / 2}) {
            const auto l = law.evaluate(xb - eps), r = law.evaluate(xb + eps);
            const auto p = law.peaks();
            CHECK(std::abs(l.S - r.S) < 1e-8);
            CHECK(std::abs(l.V - r.V) < 1e-8 * p.velocity);
            CHECK(std::abs(l.A - r.A) < 1e-7 * p.acceleration);
        }
    }
    // The documented exception: constant acceleration jumps from +4 to -4 at x = 1/2.
    const auto ca = MotionLaw::constant_acceleration();
    CHECK(ca.evaluate(0.5 - 1e-12).A == 4.0);
    CHECK(ca.evaluate(0.5 + 1e-12).A == -4.0);
}

TEST_CASE("bad law parameters name the parameter and range") {
    CHECK_THROWS_WITH(MotionLaw::sine_constant_cosine(0.5, 0.5, 0.5), Catch::Contains("b + c + d must equal 1"));
    CHECK_THROWS_WITH(MotionLaw::sine_constant_cosine(-0.1, 0.6, 0.5),
                      Catch::Contains("b (sine fraction) must be in [0, 1]"));
    CHECK_THROWS_WITH(MotionLaw::sine_constant_cosine(0.25, std::nan(""), 0.25),
                      Catch::Contains("c (constant fraction)"));
    CHECK_THROWS_AS(MotionLaw::cycloidal().evaluate(1.5), std::invalid_argument);
    CHECK_THROWS_WITH(MotionLaw::cycloidal().evaluate(std::nan("")), Catch::Contains("x must be in [0, 1]"));
}
