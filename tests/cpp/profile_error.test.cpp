// SPDX-License-Identifier: BSD-3-Clause
// Profile errors (cam manufacturing errors as a lift error e(theta)) against independent truth:
// - the component formulas written out again here, and central finite differences for e', e'', e''';
// - known trigonometric polynomials for the table fit (exact reproduction, projection, and the
//   least-squares normal equations A^T r = 0 built here from the points);
// - the design program re-evaluated from its segments (bit-identical without an error);
// - the undercut check: a dent that truly undercuts (pitch-curve radius computed here by hand) is
//   refused, also when it is narrower than the sampling step of a program segment.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "angles.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/translating_roller.hpp"
#include "camfollower/motion/profile_error.hpp"
#include "camfollower/motion/program.hpp"

using namespace camfollower;
using Catch::Contains;

namespace {

// Central differences of e, e', e'' at theta, compared with e', e'', e''' (each against its own scale).
template <class Eval>
void check_derivatives(const Eval& f, double theta, double h, const double scale[3], double rel = 1e-6) {
    const auto p = f(theta + h), m = f(theta - h), c = f(theta);
    INFO("theta = " << theta / deg << " deg");
    CHECK(std::abs((p[0] - m[0]) / (2 * h) - c[1]) <= rel * scale[0]);
    CHECK(std::abs((p[1] - m[1]) / (2 * h) - c[2]) <= rel * scale[1]);
    CHECK(std::abs((p[2] - m[2]) / (2 * h) - c[3]) <= rel * scale[2]);
}

std::array<double, 4> as_array(const LiftError& v) { return {v.e, v.de, v.d2e, v.d3e}; }
std::array<double, 4> as_array(const FollowerMotion& v) { return {v.h, v.dh, v.d2h, v.d3h}; }

// A trigonometric polynomial with known coefficients: mean + sum a_k cos k t + b_k sin k t.
struct Trig {
    double mean;
    std::vector<int> k;
    std::vector<double> a, b;
    double operator()(double t) const {
        double v = mean;
        for (std::size_t i = 0; i < k.size(); ++i) v += a[i] * std::cos(k[i] * t) + b[i] * std::sin(k[i] * t);
        return v;
    }
    double slope(double t) const {
        double v = 0.0;
        for (std::size_t i = 0; i < k.size(); ++i) v += k[i] * (b[i] * std::cos(k[i] * t) - a[i] * std::sin(k[i] * t));
        return v;
    }
};

// The design lift as the program computed it before profile errors existed.
FollowerMotion design(const MotionProgram& p, double theta) {
    const double t = MotionProgram::wrap(theta);
    const Segment& s = p.segments()[p.segment_index(t)];
    const double beta = s.span(), dh = s.lift();
    const LawValue v = s.law.evaluate((t - s.theta_start) / beta);
    return {s.h_start + dh * v.S, dh * v.V / beta, dh * v.A / (beta * beta), dh * v.J / (beta * beta * beta)};
}

std::string undercut_message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no exception)";
}

// Pitch-curve radius of curvature of a zero-offset translating roller, R = s0 + h: written out from
// the curve (R cos t, R sin t), kappa = (R^2 + 2 R'^2 - R R'') / (R^2 + R'^2)^(3/2).
double pitch_radius(double R, double dR, double d2R) {
    return std::pow(R * R + dR * dR, 1.5) / (R * R + 2 * dR * dR - R * d2R);
}
}  // namespace

TEST_CASE("waviness: A cos(k theta + phi) and its derivatives") {
    const double A = 12e-6, phi = 0.4;
    const int k = 7;
    const ProfileError w = ProfileError::waviness(A, k, phi);
    for (double t : {0.0, 0.3, 1.7, 3.9, 6.1, -2.0, 20.0}) {
        CHECK(w.evaluate(t).e == Approx(A * std::cos(k * t + phi)).margin(1e-18));
        const double scale[3] = {A * k * k, A * k * k * k, A * k * k * k * k};
        check_derivatives([&](double x) { return as_array(w.evaluate(x)); }, t, 1e-5, scale);
    }
    CHECK(w.features().empty());
    CHECK(w.sampling_step() == Approx(2 * pi / (32.0 * k)));
}

TEST_CASE("dent: -depth at the centre, the (1 - x^2)^4 shape, zero outside, C3 at the edges") {
    const double c = 40 * deg, w = 3 * deg, d = 0.2e-3;
    const ProfileError dent = ProfileError::dent(c, w, d);
    CHECK(dent.evaluate(c).e == -d);
    CHECK(dent.evaluate(c).de == 0.0);
    for (double x : {-0.8, -0.5, -0.1, 0.3, 0.65, 0.95}) {
        INFO("x = " << x);
        CHECK(dent.evaluate(c + x * w / 2).e == Approx(-d * std::pow(1 - x * x, 4)).epsilon(1e-10));
    }
    for (double x : {-3.0, -1.0001, 1.2, 40.0}) CHECK(dent.evaluate(c + x * w / 2).e == 0.0);
    for (double x : {-1.0, 1.0}) CHECK(std::abs(dent.evaluate(c + x * w / 2).e) <= d * 1e-40);
    CHECK(dent.evaluate(c + 2 * pi).e == -d);  // periodic

    const double s = 2 / w;
    const double scale[3] = {8 * d * s * s, 48 * d * s * s * s, 400 * d * s * s * s * s};
    for (double x : {-0.9, -0.6, -0.2, 0.05, 0.45, 0.8, 0.99})
        check_derivatives([&](double t) { return as_array(dent.evaluate(t)); }, c + x * w / 2, 1e-5 * w, scale);

    // At each edge e, e', e'', e''' vanish from inside, and e''' changes by no more than its slope
    // (|e''''| = 384 d s^4 at the edge) allows across a small step: the jerk is continuous.
    for (double edge : {c - w / 2, c + w / 2}) {
        const double delta = 1e-7 * w;
        const LiftError in = dent.evaluate(edge + (edge < c ? delta : -delta));
        const LiftError out = dent.evaluate(edge + (edge < c ? -delta : delta));
        CHECK(out.e == 0.0);
        CHECK(out.d3e == 0.0);
        CHECK(std::abs(in.e) <= d * 1e-20);
        CHECK(std::abs(in.d3e - out.d3e) <= 1.01 * 384 * d * std::pow(s, 4) * delta);
        // FD of e'' across the edge agrees with e''' on both sides (~0).
        const double fd = (dent.evaluate(edge + delta).d2e - dent.evaluate(edge - delta).d2e) / (2 * delta);
        CHECK(std::abs(fd) <= 1e-6 * scale[1]);
    }
    const std::vector<double> f = dent.features();
    REQUIRE(f.size() == 3);
    CHECK(f[0] == Approx(c - w / 2));
    CHECK(f[1] == Approx(c));
    CHECK(f[2] == Approx(c + w / 2));
}

TEST_CASE("dent across theta = 0 wraps, and a negative depth is a bump") {
    const ProfileError dent = ProfileError::dent(1 * deg, 10 * deg, -5e-6);
    CHECK(dent.evaluate(1 * deg).e == 5e-6);
    CHECK(dent.evaluate(-2 * deg).e == Approx(dent.evaluate(358 * deg).e).epsilon(1e-12));
    CHECK(dent.evaluate(-2 * deg).e > 0.0);
    CHECK(dent.evaluate(-3.5 * deg).e == Approx(5e-6 * std::pow(1 - 0.81, 4)).epsilon(1e-9));
    CHECK(dent.evaluate(-4.5 * deg).e == 0.0);
    const std::vector<double> f = dent.features();
    REQUIRE(f.size() == 3);
    CHECK(f[0] == Approx(1 * deg));
    CHECK(f[1] == Approx(6 * deg));
    CHECK(f[2] == Approx(356 * deg));
}

TEST_CASE("table: a sampled trigonometric polynomial is reproduced between the points") {
    const Trig p{3e-6, {1, 2, 3, 4}, {5e-6, -2e-6, 1e-6, 0.5e-6}, {-1e-6, 4e-6, 0.0, -2.5e-6}};
    const double tol = 1e-12 * 5e-6;

    SECTION("9 equally spaced points (offset start), max_harmonic defaults to 4") {
        std::vector<double> th, e;
        for (int i = 0; i < 9; ++i) th.push_back(0.1 + 2 * pi * i / 9), e.push_back(p(th.back()));
        const ProfileError fit = ProfileError::table(th, e);
        for (double t = 0.0; t < 2 * pi; t += 0.0371) {
            CHECK(std::abs(fit.evaluate(t).e - p(t)) <= tol);
            CHECK(std::abs(fit.evaluate(t).de - p.slope(t)) <= 4 * tol);
        }
    }
    SECTION("13 unequally spaced points, max_harmonic 4 (least squares, zero residual)") {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> jitter(-0.2, 0.2);
        std::vector<double> th, e;
        for (int i = 0; i < 13; ++i) th.push_back(2 * pi * (i + 0.5 + jitter(rng)) / 13), e.push_back(p(th.back()));
        const ProfileError fit = ProfileError::table(th, e, 4);
        for (double t = 0.0; t < 2 * pi; t += 0.0371) CHECK(std::abs(fit.evaluate(t).e - p(t)) <= tol);
    }
}

TEST_CASE("table: a lower max_harmonic returns the least-squares projection") {
    SECTION("equally spaced: harmonics 7 and 11 are orthogonal to 1..5 over 36 points") {
        const Trig low{1e-6, {1, 2, 3}, {4e-6, 1e-6, -2e-6}, {2e-6, 0.0, 1e-6}};
        const Trig high{0.0, {7, 11}, {3e-6, -1e-6}, {1e-6, 2e-6}};
        std::vector<double> th, e;
        for (int i = 0; i < 36; ++i) th.push_back(2 * pi * i / 36), e.push_back(low(th.back()) + high(th.back()));
        const ProfileError fit = ProfileError::table(th, e, 5);
        for (double t = 0.0; t < 2 * pi; t += 0.05) CHECK(std::abs(fit.evaluate(t).e - low(t)) <= 1e-12 * 4e-6);
    }
    SECTION("any spacing, noisy data: the residual is orthogonal to every basis function") {
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (bool equal : {true, false}) {
            INFO((equal ? "equally spaced" : "unequally spaced"));
            const int n = 40, K = 6;
            std::vector<double> th, e;
            for (int i = 0; i < n; ++i) {
                th.push_back(2 * pi * (i + (equal ? 0.0 : 0.5 + 0.4 * u(rng))) / n);
                e.push_back(1e-5 * u(rng));
            }
            const ProfileError fit = ProfileError::table(th, e, K);
            for (int k = 0; k <= K; ++k)
                for (int sine = 0; sine < 2; ++sine) {
                    if (k == 0 && sine) continue;
                    double dot = 0.0, norm = 0.0;
                    for (int i = 0; i < n; ++i) {
                        const double basis = sine ? std::sin(k * th[i]) : std::cos(k * th[i]);
                        dot += basis * (e[i] - fit.evaluate(th[i]).e);
                        norm += std::abs(basis * e[i]);
                    }
                    INFO("k = " << k << (sine ? " sin" : " cos"));
                    CHECK(std::abs(dot) <= 1e-12 * norm);
                }
        }
    }
}

TEST_CASE("table, Fourier: derivatives against finite differences") {
    const ProfileError f = ProfileError::fourier(1e-6, {2e-6, -1e-6, 0.0, 3e-7}, {0.0, 1e-6, 2e-6, -1e-7});
    const double scale[3] = {2e-5, 8e-5, 3e-4};
    for (double t : {0.2, 1.1, 2.9, 4.4, 5.8})
        check_derivatives([&](double x) { return as_array(f.evaluate(x)); }, t, 1e-5, scale);
    // 40 harmonics: the restarted recurrence stays accurate.
    std::vector<double> a(40), b(40);
    for (int k = 1; k <= 40; ++k) a[k - 1] = 1e-6 / k, b[k - 1] = -0.5e-6 / k;
    const ProfileError g = ProfileError::fourier(0.0, a, b);
    for (double t : {0.7, 3.3, 6.0}) {
        double direct = 0.0;
        for (int k = 1; k <= 40; ++k) direct += a[k - 1] * std::cos(k * t) + b[k - 1] * std::sin(k * t);
        CHECK(g.evaluate(t).e == Approx(direct).margin(1e-19));
    }
}

TEST_CASE("components add") {
    const ProfileError w = ProfileError::waviness(5e-6, 3), d = ProfileError::dent(1.0, 0.2, 2e-5);
    const ProfileError sum = w + d;
    CHECK(sum.components().size() == 2);
    for (double t : {0.95, 1.0, 1.07, 2.0}) {
        CHECK(sum.evaluate(t).e == Approx(w.evaluate(t).e + d.evaluate(t).e).margin(1e-20));
        CHECK(sum.evaluate(t).d3e == Approx(w.evaluate(t).d3e + d.evaluate(t).d3e).margin(1e-14));
    }
    CHECK(ProfileError().empty());
    CHECK(ProfileError().evaluate(1.0).e == 0.0);
}

TEST_CASE("program with a profile error: design lift + e, derivatives, lift extremes, breakpoints") {
    const MotionProgram p = MotionProgram::paper_default();
    const double A = 20e-6;
    // 12 waves: crests at 0, 30, ..., 180, 210 deg (the top dwell's ends), troughs at 15 deg (in the
    // bottom dwell): max lift = 10 mm + A, min lift = -A.
    const ProfileError err = ProfileError::waviness(A, 12) + ProfileError::dent(100 * deg, 4 * deg, 5e-6);
    const MotionProgram q = p.with_profile_error(err);
    REQUIRE(q.profile_error() != nullptr);
    CHECK(p.profile_error() == nullptr);
    for (double t : {0.1, 0.8, 1.7, 1.745, 2.6, 4.0, 5.9}) {
        const FollowerMotion a = q.evaluate(t), b = p.evaluate(t);
        const LiftError e = err.evaluate(t);
        CHECK(a.h == b.h + e.e);
        CHECK(a.d2h == b.d2h + e.d2e);
        const double scale[3] = {0.02, 0.2, 5.0};
        check_derivatives([&](double x) { return as_array(q.evaluate(x)); }, t, 1e-6, scale);
    }
    CHECK(q.max_lift() == Approx(0.010 + A).margin(1e-13));
    CHECK(q.min_lift() == Approx(-A).margin(1e-13));
    CHECK(p.max_lift() == 0.010);
    const std::vector<double> bp = q.breakpoints();
    const std::vector<double> expected{0, 30 * deg, 98 * deg, 100 * deg, 102 * deg, 180 * deg, 210 * deg, 2 * pi};
    REQUIRE(bp.size() == expected.size());
    for (std::size_t i = 0; i < bp.size(); ++i) CHECK(bp[i] == Approx(expected[i]).margin(1e-12));
    CHECK(q.sampling_step() == Approx(2 * pi / (32 * 12)));

    // Replaced, not stacked; an empty error gives the design program back.
    const MotionProgram r = q.with_profile_error(ProfileError::waviness(A, 3));
    CHECK(r.evaluate(1.0).h == p.evaluate(1.0).h + A * std::cos(3.0));
    const MotionProgram back = q.with_profile_error(ProfileError());
    CHECK(back.profile_error() == nullptr);
    CHECK(back.max_lift() == 0.010);
    CHECK(back.evaluate(1.0).h == p.evaluate(1.0).h);
}

TEST_CASE("a program without a profile error evaluates bit-identically to the design formula") {
    const MotionProgram p = MotionProgram::paper_default();
    const MotionProgram steep(
        {{MotionLaw::cycloidal(), 0, 40 * deg, 0, 0.04}, {MotionLaw::polynomial_345(), 40 * deg, 2 * pi, 0.04, 0.0}});
    for (const MotionProgram* prog : {&p, &steep})
        for (int i = -50; i < 800; ++i) {
            const double t = 0.00917 * i;
            const FollowerMotion a = prog->evaluate(t), b = design(*prog, t);
            CHECK((a.h == b.h && a.dh == b.dh && a.d2h == b.d2h && a.d3h == b.d3h));
        }
    const std::vector<double> bp = p.breakpoints();
    REQUIRE(bp.size() == 5);
    for (std::size_t i = 0; i < 4; ++i) CHECK(bp[i] == p.segments()[i].theta_start);
    CHECK(bp[4] == 2 * pi);
    CHECK(std::isinf(p.sampling_step()));
}

TEST_CASE("undercut check: a deep narrow dent is refused, the healthy cam and a shallow dent pass") {
    const MotionProgram healthy = MotionProgram::paper_default();
    const TranslatingRoller roller(0.040, 0.0125, 0.0);
    CHECK_NOTHROW(check_undercut(healthy, roller));

    // 0.2 mm deep, 3 deg wide, centred at 15 deg on the bottom dwell (h = 0): e'' is most negative at
    // x^2 = 3/7, e'' = -d (64/49) 8 / (w/2)^2; there the pitch curve's radius (about 2 mm) is far
    // below the roller radius, on a convex stretch: the roller cannot trace it.
    const double d = 0.2e-3, w = 3 * deg;
    const double x = std::sqrt(3.0 / 7), u = 1 - x * x, s = 2 / w;
    const double R = 0.040 + 0.0125 - d * std::pow(u, 4), dR = 8 * d * x * u * u * u * s,
                 d2R = 8 * d * u * u * (1 - 7 * x * x) * s * s;
    const double rho = pitch_radius(R, dR, d2R);
    REQUIRE(rho > 0.0);     // convex there
    REQUIRE(rho < 0.0125);  // tighter than the roller: undercut
    const MotionProgram dented = healthy.with_profile_error(ProfileError::dent(15 * deg, w, d));
    const std::string message = undercut_message_of([&] { check_undercut(dented, roller); });
    CHECK_THAT(message, Contains("undercuts at theta = "));
    const double at = std::stod(message.substr(message.find("theta = ") + 8));
    CHECK(std::abs(at - 15.0) <= 1.5);

    // A dent 0.1 deg wide on the rise, between two of the 600 samples of the 150 deg rise segment
    // (every 0.25 deg from 30 deg): only the dent's features make the search look there.
    const double wn = 0.1 * deg, dn = 1e-6;
    const double sn = 2 / wn, c = 100.125 * deg;
    const FollowerMotion m = healthy.evaluate(c + x * wn / 2);
    const double rho_n = pitch_radius(0.0525 + m.h - dn * std::pow(u, 4), m.dh + 8 * dn * x * u * u * u * sn,
                                      m.d2h + 8 * dn * u * u * (1 - 7 * x * x) * sn * sn);
    REQUIRE(rho_n > 0.0);
    REQUIRE(rho_n < 0.0125);
    const std::string narrow =
        undercut_message_of([&] { check_undercut(healthy.with_profile_error(ProfileError::dent(c, wn, dn)), roller); });
    CHECK_THAT(narrow, Contains("undercuts at theta = "));
    CHECK(std::abs(std::stod(narrow.substr(narrow.find("theta = ") + 8)) - 100.125) <= 0.05);

    // 2 um over 3 deg bends the pitch curve only mildly: accepted.
    CHECK_NOTHROW(check_undercut(healthy.with_profile_error(ProfileError::dent(15 * deg, w, 2e-6)), roller));
    CHECK_NOTHROW(check_undercut(healthy.with_profile_error(ProfileError::waviness(5e-6, 20)), roller));
}

TEST_CASE("bad input names the parameter and the allowed range") {
    CHECK_THROWS_WITH(ProfileError::waviness(NAN, 3), Contains("waviness amplitude"));
    CHECK_THROWS_WITH(ProfileError::waviness(1e-6, 0), Contains("waviness order must be an integer >= 1"));
    CHECK_THROWS_WITH(ProfileError::waviness(1e-6, 2, INFINITY), Contains("waviness phase"));
    CHECK_THROWS_WITH(ProfileError::dent(1.0, 0.0, 1e-5),
                      Contains("dent width must be in [1e-06 rad, 180 deg], got 0"));
    CHECK_THROWS_WITH(ProfileError::dent(1.0, 4.0, 1e-5), Contains("dent width must be in [1e-06 rad, 180 deg]"));
    CHECK_THROWS_WITH(ProfileError::dent(1.0, NAN, 1e-5), Contains("dent width"));
    CHECK_THROWS_WITH(ProfileError::dent(NAN, 0.1, 1e-5), Contains("dent centre"));
    CHECK_THROWS_WITH(ProfileError::dent(1.0, 0.1, NAN), Contains("dent depth"));
    CHECK_THROWS_WITH(ProfileError::fourier(0.0, {1e-6}, {}), Contains("same length"));
    CHECK_THROWS_WITH(ProfileError::fourier(0.0, {1e-6, NAN}, {0.0, 0.0}), Contains("harmonic 2 must be finite"));

    const std::vector<double> th{0.0, 1.0, 2.0, 3.0, 4.0}, e{0, 1e-6, 0, -1e-6, 0};
    CHECK_THROWS_WITH(ProfileError::table(th, {0, 1e-6}), Contains("same length, got 5 and 2"));
    CHECK_THROWS_WITH(ProfileError::table({0.0, 1.0}, {0.0, 0.0}), Contains("at least 3 points"));
    CHECK_THROWS_WITH(ProfileError::table({0.0, 1.0, 1.0, 3.0}, {0, 0, 0, 0}),
                      Contains("theta must be strictly increasing in [0, 360) deg; point 2"));
    CHECK_THROWS_WITH(ProfileError::table({-0.1, 1.0, 2.0}, {0, 0, 0}),
                      Contains("strictly increasing in [0, 360) deg; point 0"));
    CHECK_THROWS_WITH(ProfileError::table({0.0, 1.0, 2 * pi}, {0, 0, 0}), Contains("point 2 is at 360 deg"));
    CHECK_THROWS_WITH(ProfileError::table({0.0, NAN, 2.0}, {0, 0, 0}), Contains("point 1 must be finite"));
    CHECK_THROWS_WITH(ProfileError::table(th, {0, 0, NAN, 0, 0}), Contains("point 2 must be finite"));
    CHECK_THROWS_WITH(ProfileError::table(th, e, 3), Contains("max_harmonic must be in [1, 2]"));
    CHECK_THROWS_WITH(ProfileError::table(th, e, 0), Contains("max_harmonic must be in [1, 2]"));
    // Points crowded into 1 deg cannot determine harmonics up to 4.
    std::vector<double> crowded, zeros(9, 0.0);
    for (int i = 0; i < 9; ++i) crowded.push_back(i * 0.1 * deg);
    CHECK_THROWS_WITH(ProfileError::table(crowded, zeros), Contains("do not determine harmonics"));
    CHECK_THROWS_WITH(MotionProgram::paper_default().with_profile_error(ProfileError::waviness(1e-6, 2)).evaluate(NAN),
                      Contains("theta must be finite"));
}
