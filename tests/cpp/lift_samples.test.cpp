// SPDX-License-Identifier: BSD-3-Clause
// What the lift synthesis measures (synthesis/lift_samples.hpp), on a one-mass follower on a flat face
// whose equation of motion is written out here: M y'' + C y' + KS y + P = K (h(theta) - y). Its static
// equilibrium is (K h - P) / (K + KS) in closed form; far below its natural frequency the follower lags
// that path by e = -(M y_qs'' + C y_qs') / (K + KS), y_qs'' = K omega^2 h'' / (K + KS) (time
// derivatives by the chain rule), the first term of the quasi-static expansion.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "camfollower/camfollower.hpp"

using namespace camfollower;
using namespace camfollower::synthesis;

namespace {

constexpr double M = 0.5, K = 2e5, KS = 1e4, C = 5.0, P = 150.0, LIFT = 0.02;

MotionProgram rise_and_return(const MotionLaw& law) {
    const double d = pi / 180.0;
    return MotionProgram({{MotionLaw::dwell(), 0.0, 40 * d, 0.0, 0.0},
                          {law, 40 * d, 160 * d, 0.0, LIFT},
                          {MotionLaw::dwell(), 160 * d, 200 * d, LIFT, LIFT},
                          {law, 200 * d, 320 * d, LIFT, 0.0},
                          {MotionLaw::dwell(), 320 * d, 360 * d, 0.0, 0.0}});
}

Mechanism<> one_mass(const MotionProgram& program, double rpm) {
    MechanismBuilder b;
    b.set_camshaft_speed_rpm(rpm);
    b.add_dof("y", M, {0, 1, 0});
    b.add_spring("return", "y", "ground", KS, C, P);
    const ContactPairSpec c{"cam",
                            program,
                            TranslatingFlat(0.03),
                            HertzContact{K, 1.0, 0.0},
                            0.0,
                            "ground",
                            "ground",
                            "y",
                            "ground",
                            CamEccentricity{},
                            "ground"};
    b.add_contact(c);
    return Mechanism<>(b);
}

}  // namespace

TEST_CASE("lift samples: the dwells of a program and the quasi-static path in closed form") {
    const MotionProgram program = rise_and_return(MotionLaw::cycloidal());
    const auto dwells = dwell_windows(program);
    REQUIRE(dwells.size() == 3);
    CHECK(dwells[1].first == Approx(160 * pi / 180).epsilon(1e-15));
    CHECK(dwells[1].second == Approx(200 * pi / 180).epsilon(1e-15));
    const Mechanism<> m = one_mass(program, 600.0);
    std::vector<double> theta;
    for (int k = 0; k <= 720; ++k) theta.push_back(two_pi * k / 720.0);  // the grid itself
    theta.push_back(1.2345);                                             // and between its points
    const std::vector<double> path = quasi_static_path(m, 0, theta);
    for (std::size_t i = 0; i < theta.size(); ++i) {
        const double h = program.evaluate(std::fmod(theta[i], two_pi)).h;
        INFO("theta = " << theta[i]);
        // On the grid: the closed form. Between: linear interpolation's error, at most
        // max|h''| (0.5 deg)^2 / 8 K / (K + KS), max|h''| = 2 pi LIFT / beta^2 for the cycloidal rise.
        const double step = two_pi / 720, beta = 120 * pi / 180;
        const double between = 2 * pi * LIFT / (beta * beta) * step * step / 8 * K / (K + KS);
        const double tolerance = i + 1 < theta.size() ? 1e-14 : 1.01 * between;
        CHECK(path[i] == Approx((K * h - P) / (K + KS)).margin(tolerance));
    }
    // Solved at every angle (angles = 0): the closed form everywhere.
    const std::vector<double> exact = quasi_static_path(m, 0, {1.2345, 3.0}, 0);
    for (std::size_t i = 0; i < 2; ++i)
        CHECK(exact[i] == Approx((K * program.evaluate(i ? 3.0 : 1.2345).h - P) / (K + KS)).margin(1e-14));
    CHECK_THROWS_WITH(quasi_static_path(m, 3, theta), Catch::Contains("dof index 3 is not in [0, 1)"));
    CHECK_THROWS_WITH(quasi_static_path(m, 0, theta, 1), Catch::Contains("angles must be 0 (every theta) or >= 2"));
}

TEST_CASE("lift samples: the objective keeps the dwells' samples, the limits see the whole revolution") {
    const MotionProgram program = rise_and_return(MotionLaw::cycloidal());
    const Mechanism<> m = one_mass(program, 600.0);
    std::vector<double> theta, q, a, force;
    for (int k = 1; k <= 360; ++k) {
        const double t = two_pi * (k - 0.5) / 360.0;  // none on a segment boundary
        theta.push_back(t);
        q.push_back((K * program.evaluate(std::fmod(t, two_pi)).h - P) / (K + KS) + 1e-6 * std::sin(7 * t));
        a.push_back(std::cos(3 * t));
        force.push_back(100.0 + 50.0 * std::cos(t));
    }
    const LiftSamples r = lift_samples(m, 0, 0, LiftObjective::residual, theta, q, a, force);
    // 40 + 40 + 40 deg of dwells, a sample every degree.
    std::size_t expected = 0;
    for (double t : theta) {
        const double c = std::fmod(t, two_pi), d = pi / 180;
        expected += (c < 40 * d) || (c >= 160 * d && c < 200 * d) || (c >= 320 * d);
    }
    REQUIRE(expected == 120);
    REQUIRE(r.values.size() == expected);
    for (std::size_t i = 0; i < r.values.size(); ++i)
        CHECK(r.values[i] == Approx(1e-6 * std::sin(7 * r.theta[i])).margin(1e-12));
    // The samples nearest the extremes are half a degree off them: cos t at pi, cos 3t at multiples of pi / 3.
    CHECK(r.min_force == Approx(100.0 - 50.0 * std::cos(0.5 * pi / 180)).epsilon(1e-12));
    CHECK(r.peak_acceleration == Approx(std::cos(1.5 * pi / 180)).epsilon(1e-12));
    CHECK(r.dwells.peak_to_peak == Approx(2e-6).epsilon(0.01));  // sin 7t spans a full period in a 40 deg dwell
    const LiftSamples acc = lift_samples(m, 0, 0, LiftObjective::acceleration, theta, q, a, force);
    REQUIRE(acc.values.size() == theta.size());
    CHECK(acc.values[10] == a[10]);
    CHECK_THROWS_WITH(lift_samples(m, 0, 0, LiftObjective::residual, theta, q, a, std::vector<double>(3)),
                      Catch::Contains("one value per sample"));
    CHECK_THROWS_WITH(lift_objective("jerk"), Catch::Contains("objective must be one of"));
    CHECK(lift_objective("follower_error") == LiftObjective::follower_error);
}

TEST_CASE("evaluate_lift: slowly, the follower lags its quasi-static path by M y_qs'' / (K + KS)") {
    // 60 rpm against 103 Hz: (omega / omega_n)^2 ~ 1e-4. The 4-5-6-7 law's jerk is continuous, so the
    // free vibration it leaves is of that order too.
    const MotionProgram program = rise_and_return(MotionLaw::polynomial_4567());
    const Mechanism<> m = one_mass(program, 60.0);
    SolverSettings s;
    s.time_step = m.period() / 65536;
    ShootingOptions o;
    o.tolerance = 1e-11;
    const auto e = evaluate_lift(m, s, o, 0, 0, LiftObjective::follower_error, 16);
    REQUIRE(e.orbit.converged);
    REQUIRE(e.samples.values.size() == 65536 / 16);
    const double w = m.omega();
    double peak = 0, worst = 0;
    for (std::size_t i = 0; i < e.samples.values.size(); ++i) {
        const FollowerMotion f = program.evaluate(std::fmod(e.samples.theta[i], two_pi));
        const double lag = -(M * K * w * w * f.d2h + C * K * w * f.dh) / ((K + KS) * (K + KS));
        peak = std::max(peak, std::abs(lag));
        worst = std::max(worst, std::abs(e.samples.values[i] - lag));
    }
    INFO("peak lag " << peak << " m, largest difference " << worst << " m");
    CHECK(peak > 1e-7);
    CHECK(worst < 0.01 * peak);
    CHECK(e.samples.min_force > 0.0);
    // The residual objective of the same orbit: its dwells' samples only, their rms as reported.
    const auto r = evaluate_lift(m, s, o, 0, 0, LiftObjective::residual, 16);
    double squares = 0;
    for (double v : r.samples.values) squares += v * v;
    CHECK(std::sqrt(squares / double(r.samples.values.size())) == Approx(r.samples.dwells.rms).epsilon(1e-12));
    CHECK_THROWS_WITH(evaluate_lift(m, s, o, 1, 0, LiftObjective::residual), Catch::Contains("contact index 1"));
}
