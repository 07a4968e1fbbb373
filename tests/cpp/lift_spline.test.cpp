// SPDX-License-Identifier: BSD-3-Clause
// Lift tables as B-splines. Truth comes from outside the code under test: closed-form functions and
// their hand-derived derivatives, the textbook 4-5-6-7 law (laws.hpp closed form), the spline
// approximation theory (error O(step^(degree + 1 - k)) in the k-th derivative), the noise level put in.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "angles.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/motion/smoothness.hpp"

using namespace camfollower;

namespace {

// h = a (1 - cos t) + b sin 2t and its derivatives, by hand.
struct Smooth {
    double a = 0.004, b = 0.001;
    FollowerMotion at(double t) const {
        return {a * (1 - std::cos(t)) + b * std::sin(2 * t), a * std::sin(t) + 2 * b * std::cos(2 * t),
                a * std::cos(t) - 4 * b * std::sin(2 * t), -a * std::sin(t) - 8 * b * std::cos(2 * t)};
    }
};

std::vector<double> equally_spaced(std::size_t n, double first = 0.0, double step = 2 * pi) {
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i) t[i] = first + step * static_cast<double>(i) / static_cast<double>(n);
    return t;
}

// Largest |error| of h'' and h''' over a fine grid.
std::pair<double, double> derivative_errors(const MotionProgram& p, const Smooth& f) {
    double e2 = 0.0, e3 = 0.0;
    for (int i = 0; i < 4000; ++i) {
        const double t = 2 * pi * (i + 0.37) / 4000;
        const FollowerMotion s = p.evaluate(t), x = f.at(t);
        e2 = std::max(e2, std::abs(s.d2h - x.d2h));
        e3 = std::max(e3, std::abs(s.d3h - x.d3h));
    }
    return {e2, e3};
}

// Peak |h''| over the revolution on a dense grid (m/rad^2).
double dense_peak_acceleration(const MotionProgram& p) {
    double peak = 0.0;
    for (int i = 0; i < 72000; ++i) peak = std::max(peak, std::abs(p.evaluate(2 * pi * i / 72000.0).d2h));
    return peak;
}
}  // namespace

TEST_CASE("an interpolating spline reproduces its table points") {
    const Smooth f;
    for (int degree : {1, 3, 5, 7}) {
        INFO("degree " << degree);
        // Unequal spacing, the table starting after 0.
        std::vector<double> theta, h;
        for (int i = 0; i < 40; ++i) {
            const double t = 0.05 + 2 * pi * (i + 0.3 * std::sin(i)) / 40.5;
            theta.push_back(t), h.push_back(f.at(t).h);
        }
        const MotionProgram p = MotionProgram::from_table(theta, h, {degree, 0.0});
        for (std::size_t i = 0; i < theta.size(); ++i) CHECK(std::abs(p.evaluate(theta[i]).h - h[i]) < 1e-12);
        const Segment s = Segment::from_table(theta, h, {degree, 0.0});
        for (std::size_t i = 0; i < theta.size(); ++i) CHECK(std::abs(s.lift_at(theta[i]).h - h[i]) < 1e-12);
        CHECK(s.h_start == h.front());
        CHECK(s.h_end == h.back());
    }
}

TEST_CASE("a periodic quintic spline converges at the theoretical rate in h'' and h'''") {
    // Spline theory: error in the k-th derivative O(step^(6 - k)) for a quintic: 4 for h'', 3 for h'''.
    const Smooth f;
    std::vector<std::pair<double, double>> errors;
    for (std::size_t n : {16u, 32u, 64u, 128u}) {
        const std::vector<double> theta = equally_spaced(n);
        std::vector<double> h;
        for (double t : theta) h.push_back(f.at(t).h);
        errors.push_back(derivative_errors(MotionProgram::from_table(theta, h), f));
    }
    for (std::size_t i = 1; i < errors.size(); ++i) {
        const double order2 = std::log2(errors[i - 1].first / errors[i].first);
        const double order3 = std::log2(errors[i - 1].second / errors[i].second);
        std::printf("quintic periodic, N = %d: |h'' error| %.3e (order %.2f), |h''' error| %.3e (order %.2f)\n",
                    16 << i, errors[i].first, order2, errors[i].second, order3);
        CHECK(order2 > 3.7);
        CHECK(order2 < 4.5);
        CHECK(order3 > 2.7);
        CHECK(order3 < 3.5);
    }
    CHECK(errors.back().first < 1e-7 * 0.008);  // relative to the peak h'' ~ 8 mm/rad^2
}

TEST_CASE("a 4-5-6-7 rise sampled into a segment table reproduces the law between dwells") {
    const MotionLaw law = MotionLaw::polynomial_4567();
    const double a = 40 * deg, b = 160 * deg, lift = 0.008, beta = b - a;
    std::vector<double> theta, h;
    for (int i = 0; i <= 60; ++i) {
        const double x = i / 60.0;
        theta.push_back(a + beta * x), h.push_back(lift * law.evaluate(x).S);
    }
    const auto program = [&](const Segment& rise) {
        return MotionProgram(
            {{MotionLaw::dwell(), 0.0, a, 0.0, 0.0}, rise, {MotionLaw::polynomial_4567(), b, 2 * pi, lift, 0.0}});
    };
    // Relative errors of h .. h''' against the closed form, each over its own peak.
    const auto errors = [&](const MotionProgram& p) {
        const auto peaks = law.peaks();
        std::array<double, 4> e{};
        for (int i = 0; i <= 2000; ++i) {
            const double x = i / 2000.0;
            const FollowerMotion s = p.evaluate(a + beta * x);
            const LawValue v = law.evaluate(x);
            e[0] = std::max(e[0], std::abs(s.h - lift * v.S) / lift);
            e[1] = std::max(e[1], std::abs(s.dh - lift * v.V / beta) / (lift * peaks.velocity / beta));
            e[2] = std::max(e[2],
                            std::abs(s.d2h - lift * v.A / (beta * beta)) / (lift * peaks.acceleration / (beta * beta)));
            e[3] = std::max(e[3],
                            std::abs(s.d3h - lift * v.J / std::pow(beta, 3)) / (lift * peaks.jerk / std::pow(beta, 3)));
        }
        return e;
    };
    // The law's own end conditions (h', h'', h''' = 0; its h'''' is not zero).
    const MotionProgram exact = program(Segment::from_table(theta, h, {}, {0, 0, 0}, {0, 0, 0}));
    // The default: zeros through h'''' (degree - 1), one condition more than the law meets.
    const MotionProgram by_default = program(Segment::from_table(theta, h));
    const auto e = errors(exact), d = errors(by_default);
    std::printf("4567 from 61 points, end conditions h'..h''' = 0: relative errors h %.2e h' %.2e h'' %.2e h''' %.2e\n",
                e[0], e[1], e[2], e[3]);
    std::printf("4567 from 61 points, default h'..h'''' = 0:       relative errors h %.2e h' %.2e h'' %.2e h''' %.2e\n",
                d[0], d[1], d[2], d[3]);
    CHECK(e[0] < 1e-9);
    CHECK(e[1] < 1e-7);
    CHECK(e[2] < 1e-5);
    CHECK(e[3] < 2e-4);
    CHECK(d[0] < 1e-6);
    CHECK(d[2] < 1e-3);
    CHECK(d[3] < 5e-2);  // forced h'''' = 0 bends the jerk near the ends
    // Both are C3 (at least) into the dwell and into the return.
    for (const MotionProgram* p : {&exact, &by_default}) {
        const ContinuityReport c = p->continuity();
        CHECK(c.boundaries[0].continuous_through == 3);
        CHECK(c.boundaries[1].continuous_through == 3);
    }
    const MotionLaw& fitted = exact.segments()[1].law;
    CHECK(fitted.name() == "spline(degree=5, points=61)");
    CHECK(fitted.has_zero_end_acceleration());
    // The normalized form of a lifting spline law matches the law it was sampled from.
    CHECK(fitted.evaluate(0.3).S == Approx(law.evaluate(0.3).S).epsilon(1e-6));
    CHECK(fitted.peaks().acceleration == Approx(law.peaks().acceleration).epsilon(1e-4));
}

TEST_CASE("end derivatives given by the user are met") {
    const Smooth f;
    std::vector<double> theta, h;
    for (int i = 0; i <= 20; ++i) theta.push_back(0.2 + 0.1 * i), h.push_back(f.at(0.2 + 0.1 * i).h);
    const FollowerMotion s0 = f.at(theta.front()), s1 = f.at(theta.back());
    const Segment s = Segment::from_table(theta, h, {5, 0.0}, {s0.dh, s0.d2h}, {s1.dh, s1.d2h, s1.d3h});
    const FollowerMotion a = s.lift_at(theta.front()), b = s.lift_at(theta.back());
    CHECK(a.dh == Approx(s0.dh).margin(1e-13));
    CHECK(a.d2h == Approx(s0.d2h).margin(1e-12));
    CHECK(b.dh == Approx(s1.dh).margin(1e-13));
    CHECK(b.d2h == Approx(s1.d2h).margin(1e-12));
    CHECK(b.d3h == Approx(s1.d3h).margin(1e-11));
    // And in between it follows the function closely.
    CHECK(std::abs(s.lift_at(1.234).d2h - f.at(1.234).d2h) < 1e-6);
}

TEST_CASE("smoothing a noisy table lowers the jerk peak and leaves residuals at the noise level") {
    const Smooth f;
    const std::size_t n = 360;
    const double sigma = 10e-6;  // 10 um of measuring noise
    std::mt19937 rng(12345);
    std::normal_distribution<double> noise(0.0, sigma);
    const std::vector<double> theta = equally_spaced(n);
    std::vector<double> h;
    for (double t : theta) h.push_back(f.at(t).h + noise(rng));
    // Keep harmonics up to ~6 per revolution (the lift has 1 and 2): lambda = 1 / (step * 6^6).
    const double step = 2 * pi / n, lambda = 1.0 / (step * std::pow(6.0, 6));
    const MotionProgram rough = MotionProgram::from_table(theta, h);
    const MotionProgram smooth = MotionProgram::from_table(theta, h, {5, lambda});
    const SmoothnessReport r = smoothness(rough), s = smoothness(smooth);
    const double true_jerk = 0.012;  // max |-a sin t - 8 b cos 2t| ~ 0.0117 m/rad^3
    std::printf(
        "noise 10 um, 360 points: jerk peak interpolating %.3g, smoothing %.3g m/rad^3 (true ~%.3g); "
        "residual RMS %.3g um, max %.3g um; roughness %.3g -> %.3g\n",
        r.peaks.jerk.value, s.peaks.jerk.value, true_jerk, s.residual.rms * 1e6, s.residual.max * 1e6, r.jerk_roughness,
        s.jerk_roughness);
    CHECK(r.peaks.jerk.value > 10 * true_jerk);  // interpolated noise dominates the jerk
    CHECK(s.peaks.jerk.value < 2 * true_jerk);
    CHECK(s.residual.rms > 0.6 * sigma);
    CHECK(s.residual.rms < 1.4 * sigma);
    CHECK(r.residual.max < 1e-12);
    CHECK(r.table_points == n);
    CHECK(r.jerk_roughness > 0.1);
    CHECK(s.jerk_roughness < 0.05);
    REQUIRE(!r.jerk_excursions.empty());
    CHECK(r.jerk_excursions.front().excursion > r.jerk_excursions.back().excursion * 0.999);
    // The smooth fit stays within a few sigma of the noise-free lift.
    double worst = 0.0;
    for (int i = 0; i < 1000; ++i)
        worst = std::max(worst, std::abs(smooth.evaluate(i * 2 * pi / 1000).h - f.at(i * 2 * pi / 1000).h));
    CHECK(worst < 4 * sigma);
}

TEST_CASE("smoothness report of a closed-form program: peaks where the textbook puts them") {
    const MotionProgram p = MotionProgram::paper_default();
    const SmoothnessReport r = smoothness(p);
    const double beta = 150 * deg;
    CHECK(r.peaks.velocity.value == Approx(0.010 * 2.0 / beta).epsilon(1e-9));
    CHECK(r.peaks.acceleration.value == Approx(0.010 * 8 * pi / (pi + 2) / (beta * beta)).epsilon(1e-9));
    const double at = r.peaks.velocity.theta;  // mid-rise or mid-return (equal peaks)
    CHECK((std::abs(at - 105 * deg) < 1e-5 || std::abs(at - 285 * deg) < 1e-5));
    CHECK(r.table_points == 0);
    CHECK(r.residual.rms == 0.0);
}

TEST_CASE("the paper's modified-trapezoid program as a 13-point and a 73-point table at 750 rpm") {
    // The true peak acceleration from the closed form: lift * C_a / beta^2 * omega^2.
    const double omega = 750 * 2 * pi / 60, beta = 150 * deg;
    const double truth = 0.010 * (8 * pi / (pi + 2)) / (beta * beta) * omega * omega;  // m/s^2
    const MotionProgram paper = MotionProgram::paper_default();
    double results[2] = {0, 0};
    int k = 0;
    for (int points : {13, 73}) {  // every 30 deg / every 5 deg, closing point at 360 deg included
        std::vector<double> theta, h;
        for (int i = 0; i < points; ++i) {
            const double t = 2 * pi * i / (points - 1);
            theta.push_back(t), h.push_back(paper.evaluate(t).h);
        }
        const MotionProgram table = MotionProgram::from_table(theta, h);  // closing point dropped
        CHECK(table.segments()[0].law.name() == "periodic spline(degree=5, points=" + std::to_string(points - 1) + ")");
        const double peak = dense_peak_acceleration(table) * omega * omega;
        const SmoothnessReport r = smoothness(table);
        CHECK(r.peaks.acceleration.value * omega * omega == Approx(peak).epsilon(1e-6));
        results[k++] = peak;
        std::printf(
            "paper program from %d table points, quintic spline: peak acceleration %.1f m/s^2 at 750 rpm "
            "(true %.1f m/s^2)\n",
            points, peak, truth);
    }
    // 13 points (30 deg apart) cannot resolve a law whose features are 150 / 8 deg wide: the peak is off,
    // but nowhere near the hundreds-fold spikes of linear interpolation. 73 points: close.
    CHECK(results[0] < 2 * truth);
    CHECK(results[0] > 0.5 * truth);
    CHECK(results[1] == Approx(truth).epsilon(0.1));
}

// (How long a 10 000-point table takes to build is measured in bench/throughput.cpp, BM_LiftTable.)
TEST_CASE("a 10 000-point table builds, interpolating and smoothing, and reproduces the lift") {
    std::vector<double> theta = equally_spaced(10000), h;
    const Smooth f;
    for (double t : theta) h.push_back(f.at(t).h);
    const MotionProgram p = MotionProgram::from_table(theta, h);
    const MotionProgram q = MotionProgram::from_table(theta, h, {5, 1e-12});
    const Segment s = Segment::from_table(theta, h, {5, 1e-12});
    CHECK(std::abs(p.evaluate(1.0).h - f.at(1.0).h) < 1e-12);
    CHECK(std::abs(q.evaluate(1.0).h - f.at(1.0).h) < 1e-9);
    CHECK(std::abs(s.lift_at(1.0).h - f.at(1.0).h) < 1e-9);
}

TEST_CASE("a periodic spline program: lift extremes include the overshoot, and it is C4 through the wrap") {
    const Smooth f;
    const std::vector<double> theta = equally_spaced(24, 0.1);
    std::vector<double> h;
    for (double t : theta) h.push_back(f.at(t).h);
    const MotionProgram p = MotionProgram::from_table(theta, h);
    double hi = -1, lo = 1;
    for (int i = 0; i < 100000; ++i) {
        const double v = p.evaluate(2 * pi * i / 100000.0).h;
        hi = std::max(hi, v), lo = std::min(lo, v);
    }
    CHECK(p.max_lift() == Approx(hi).margin(1e-12));
    CHECK(p.min_lift() == Approx(lo).margin(1e-12));
    const ContinuityReport c = p.continuity();
    REQUIRE(c.boundaries.size() == 1);
    CHECK(c.continuous_through() == 3);
    CHECK_NOTHROW(p.require_continuity(3));
    // Evaluation across the wrap is seamless.
    const FollowerMotion before = p.evaluate(2 * pi - 1e-9), after = p.evaluate(1e-9);
    CHECK(before.d3h == Approx(after.d3h).margin(1e-7));
}

TEST_CASE("a closed table: the repeated first point is dropped when it agrees, refused when it does not") {
    std::vector<double> theta = equally_spaced(12), h(12, 0.0);
    for (std::size_t i = 0; i < 12; ++i) h[i] = 0.001 * std::sin(theta[i]);
    theta.push_back(2 * pi), h.push_back(0.0);
    CHECK(MotionProgram::from_table(theta, h).segments()[0].law.spline()->theta().size() == 12);
    h.back() = 0.001;
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, h), Catch::Contains("h: the table repeats its first point"));
}

TEST_CASE("bad tables are refused, naming the parameter") {
    const std::vector<double> theta = equally_spaced(12);
    const std::vector<double> h(12, 0.001);
    std::vector<double> beyond = theta;
    beyond[11] = 2 * pi + 0.1;
    REQUIRE_THROWS_WITH(MotionProgram::from_table(beyond, h),
                        Catch::Contains("theta[11]") && Catch::Contains("[0, 360) deg"));
    std::vector<double> negative = theta;
    negative[0] = -0.1;
    REQUIRE_THROWS_WITH(MotionProgram::from_table(negative, h), Catch::Contains("theta[0]"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table({0, 1, 2, 3}, {0, 1e-3, 2e-3, 1e-3}),
                        Catch::Contains("theta") && Catch::Contains("at least 6"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table({0, 1, 2, 3}, {0, 1e-3, 2e-3, 1e-3}, {7, 0.0}),
                        Catch::Contains("at least 8"));
    std::vector<double> repeated = theta;
    repeated[5] = repeated[4];
    REQUIRE_THROWS_WITH(MotionProgram::from_table(repeated, h),
                        Catch::Contains("theta must be strictly increasing") && Catch::Contains("theta[5]"));
    const std::vector<double> reversed(theta.rbegin(), theta.rend());
    REQUIRE_THROWS_WITH(Segment::from_table(reversed, h), Catch::Contains("theta must be strictly increasing"));
    std::vector<double> nan_h = h;
    nan_h[3] = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, nan_h), Catch::Contains("h[3] must be finite"));
    std::vector<double> nan_theta = theta;
    nan_theta[2] = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH(Segment::from_table(nan_theta, h), Catch::Contains("theta[2] must be finite"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, std::vector<double>(11, 0.0)),
                        Catch::Contains("theta and h must have the same length"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, h, {4, 0.0}), Catch::Contains("degree must be odd"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, h, {9, 0.0}), Catch::Contains("degree must be odd"));
    REQUIRE_THROWS_WITH(MotionProgram::from_table(theta, h, {5, -1.0}), Catch::Contains("smoothing"));
    REQUIRE_THROWS_WITH(Segment::from_table({0.0}, {0.0}), Catch::Contains("theta: a segment table needs at least 2"));
    REQUIRE_THROWS_WITH(Segment::from_table(theta, h, {5, 0.0}, {0, 0, 0, 0, 0}),
                        Catch::Contains("start_derivatives may hold"));
    REQUIRE_THROWS_WITH(Segment::from_table(theta, h, {5, 0.0}, {0.0}, {std::nan("")}),
                        Catch::Contains("end_derivatives[0]"));
    // Fewer conditions than a segment of this degree needs: 2 points and one derivative in all.
    REQUIRE_THROWS_WITH(Segment::from_table({0.0, 1.0}, {0.0, 1e-3}, {7, 0.0}, {0.0}, {0.0}),
                        Catch::Contains("theta: a segment spline of degree 7 needs at least 8"));
}

TEST_CASE("a program checks that a spline segment's span and lift match its law") {
    const Segment s = Segment::from_table({0.5, 1.0, 1.5, 2.0}, {0.0, 1e-3, 3e-3, 4e-3});
    const MotionLaw dwell = MotionLaw::dwell();
    REQUIRE_NOTHROW(MotionProgram({{dwell, 0, 0.5, 0, 0}, s, {MotionLaw::cycloidal(), 2.0, 2 * pi, 4e-3, 0}}));
    Segment longer = s;
    longer.theta_end = 2.5;
    REQUIRE_THROWS_WITH(MotionProgram({{dwell, 0, 0.5, 0, 0}, longer, {MotionLaw::cycloidal(), 2.5, 2 * pi, 4e-3, 0}}),
                        Catch::Contains("segments[1]") && Catch::Contains("spans"));
    Segment higher = s;
    higher.h_end = 5e-3;
    REQUIRE_THROWS_WITH(MotionProgram({{dwell, 0, 0.5, 0, 0}, higher, {MotionLaw::cycloidal(), 2.0, 2 * pi, 5e-3, 0}}),
                        Catch::Contains("segments[1]") && Catch::Contains("lifts by"));
    // Raised as a whole (levels shifted, same lift): fine, the law is relative to its segment start.
    Segment raised = s;
    raised.h_start += 1e-3, raised.h_end += 1e-3;
    const MotionProgram p({{dwell, 0, 0.5, 1e-3, 1e-3}, raised, {MotionLaw::cycloidal(), 2.0, 2 * pi, 5e-3, 1e-3}});
    CHECK(p.evaluate(1.0).h == Approx(2e-3).margin(1e-15));
}
