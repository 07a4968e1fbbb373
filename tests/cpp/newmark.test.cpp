// SPDX-License-Identifier: BSD-3-Clause
// Newmark-beta / HHT-alpha solver on linear systems with exact solutions.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "camfollower/model/mechanism.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/solver/newmark.hpp"
#include "camfollower/solver/step_limit.hpp"
#include "driven_sdof.hpp"
#include "linear_system_instances.hpp"
#include "run.hpp"

using namespace camfollower;

namespace {

// Damped SDOF released from x0 at rest: x = e^{-zeta w t} (x0 cos wd t + zeta w x0 / wd sin wd t).
struct Sdof {
    double m = 2.0, k = 800.0, c = 4.0, x0 = 0.01;
    LinearSystem<1> system() const {
        LinearSystem<1> s;
        s.M(0, 0) = m, s.K(0, 0) = k, s.C(0, 0) = c, s.q0[0] = x0;
        return s;
    }
    double exact(double t) const {
        const double w = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m)), wd = w * std::sqrt(1 - zeta * zeta);
        return std::exp(-zeta * w * t) * (x0 * std::cos(wd * t) + zeta * w * x0 / wd * std::sin(wd * t));
    }
};

double max_error(const Sdof& sdof, const SolverSettings& settings, double duration) {
    const auto system = sdof.system();
    const auto r = run(system, settings, duration);
    double err = 0.0;
    for (std::size_t i = 0; i < r.rows; ++i) err = std::max(err, std::abs(r.q[i] - sdof.exact(r.t[i])));
    return err;
}

}  // namespace

TEST_CASE("linear SDOF: average acceleration matches the exact solution, order 2") {
    const Sdof sdof;
    const double period = 2 * pi / std::sqrt(sdof.k / sdof.m);
    SolverSettings s;
    double errors[4];
    for (int i = 0; i < 4; ++i) {
        s.time_step = period / (40.0 * (1 << i));
        errors[i] = max_error(sdof, s, 3 * period);
    }
    CHECK(errors[3] < 1e-3 * sdof.x0);  // ~ (w dt)^2 / 12 phase error per radian
    for (int i = 0; i < 3; ++i) {
        const double order = std::log2(errors[i] / errors[i + 1]);
        INFO("dt = T/" << 40 * (1 << i) << ": error " << errors[i] << ", observed order " << order);
        CHECK(order == Approx(2.0).margin(0.05));
    }
}

TEST_CASE("HHT-alpha is second order too, and damps a high-frequency mode") {
    const Sdof sdof;
    const double period = 2 * pi / std::sqrt(sdof.k / sdof.m);
    const double e1 = max_error(sdof, SolverSettings::hht(-0.1, period / 80), 3 * period);
    const double e2 = max_error(sdof, SolverSettings::hht(-0.1, period / 160), 3 * period);
    CHECK(std::log2(e1 / e2) == Approx(2.0).margin(0.1));

    // Undamped oscillator, dt = period / 2 (unresolved): trapezoidal keeps the amplitude, HHT kills it.
    Sdof stiff;
    stiff.c = 0.0;
    const double T = 2 * pi / std::sqrt(stiff.k / stiff.m);
    const auto system = stiff.system();
    auto final_energy_ratio = [&](const SolverSettings& s) {
        const auto r = run(system, s, 50 * T);
        const double x = r.q.back(), v = r.v.back();
        return (stiff.m * v * v + stiff.k * x * x) / (stiff.k * stiff.x0 * stiff.x0);
    };
    SolverSettings trapezoidal;
    trapezoidal.time_step = T / 2;
    CHECK(final_energy_ratio(trapezoidal) == Approx(1.0).epsilon(1e-12));
    CHECK(final_energy_ratio(SolverSettings::hht(-0.3, T / 2)) < 1e-4);
}

TEST_CASE("trapezoidal rule conserves the energy of an undamped linear system to round-off") {
    // Three masses in a chain, ground -200- m1 -100- m2 -150- m3 (N/m), built as a Mechanism<> (compiled
    // once in camfollower::precompiled): no contact, no damping, no load.
    MechanismBuilder b;
    b.add_dof("m1", 2.0, {0, 1, 0});
    b.add_dof("m2", 1.0, {0, 1, 0});
    b.add_dof("m3", 0.5, {0, 1, 0});
    b.add_spring("k1", "m1", "ground", 200.0, 0.0, 0.0);
    b.add_spring("k2", "m1", "m2", 100.0, 0.0, 0.0);
    b.add_spring("k3", "m2", "m3", 150.0, 0.0, 0.0);
    const Mechanism<> s(b);
    Eigen::Matrix3d K, M = Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal();
    K << 300, -100, 0, -100, 250, -150, 0, -150, 150;
    REQUIRE(s.stiffness() == K);
    REQUIRE(s.mass() == M);
    REQUIRE(s.damping().isZero(0.0));
    const Eigen::Vector3d q0(0.01, -0.02, 0.03);
    RunOptions options;
    options.duration = 20.0;
    options.record.decimation = 1;
    const auto run_from_q0 = [&](const SolverSettings& settings) {
        return simulate(s, settings, options, Eigen::VectorXd(q0), Eigen::VectorXd(Eigen::VectorXd::Zero(3))).recording;
    };
    // Energy of recorded row i.
    const auto energy = [&](const Recording& r, std::size_t i) {
        Eigen::Vector3d q, v;
        for (int k = 0; k < 3; ++k)
            q[k] = r.channel(r.block(0) + std::size_t(k))[i], v[k] = r.channel(r.block(1) + std::size_t(k))[i];
        return 0.5 * v.dot(M * v) + 0.5 * q.dot(K * q);
    };
    SolverSettings settings;
    settings.time_step = 1e-3;
    const Recording r = run_from_q0(settings);
    REQUIRE(r.rows == 20001);
    const double e0 = 0.5 * q0.dot(K * q0);
    REQUIRE(energy(r, 0) == Approx(e0).epsilon(1e-15));
    double drift = 0;
    for (std::size_t i = 0; i < r.rows; ++i) drift = std::max(drift, std::abs(energy(r, i) - e0));
    INFO("relative energy drift over 20000 steps: " << drift / e0);
    CHECK(drift / e0 < 1e-12);
    // With Newmark's damped variant (gamma > 1/2) it must decay: the check can fail.
    settings.gamma = 0.6;
    settings.beta = 0.3025;
    const Recording d = run_from_q0(settings);
    CHECK(energy(d, d.rows - 1) < 0.9 * e0);
}

TEST_CASE("decimation keeps every n-th row of the full run") {
    const Sdof sdof;
    SolverSettings s;
    s.time_step = 1e-3;
    const auto system = sdof.system();
    const auto full = run(system, s, 1.0);
    const auto dec = run(system, s, 1.0, 7);
    REQUIRE(full.rows == 1001);
    REQUIRE(dec.rows == 1000 / 7 + 1);
    for (std::size_t i = 0; i < dec.rows; ++i) {
        CHECK(dec.t[i] == full.t[7 * i]);
        CHECK(dec.q[i] == full.q[7 * i]);
    }
}

TEST_CASE("bad settings and durations are rejected with the parameter named") {
    const Sdof sdof;
    const auto system = sdof.system();
    SolverSettings s;
    s.time_step = 0.0;
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)), Catch::Contains("time_step must be finite and > 0"));
    s.time_step = NAN;
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)), Catch::Contains("time_step"));
    s = SolverSettings::hht(-0.5);
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)), Catch::Contains("hht_alpha must be in [-0.33"));
    // Each of gamma, beta, hht_alpha belongs to one method: a value another method would ignore is refused.
    s = SolverSettings{};
    s.hht_alpha = -0.1;
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)), Catch::Contains("hht_alpha applies to method 'hht' only"));
    s = SolverSettings::hht(-0.1);
    s.beta = 0.3;
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)),
                      Catch::Contains("gamma and beta apply to method 'newmark' only"));
    s = SolverSettings::named(Method::dop853, 1e-3, 1e-6);
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)),
                      Catch::Contains("the Newmark stepper runs methods 'newmark'"));
    s = SolverSettings{};
    s.beta = 0.0;
    CHECK_THROWS_WITH((Newmark<LinearSystem<1>>(system, s)), Catch::Contains("beta must be in (0, 0.5]"));
    s = SolverSettings{};
    CHECK_THROWS_WITH(run(system, s, -1.0), Catch::Contains("duration must be finite and > 0"));
    CHECK_THROWS_WITH(run(system, s, INFINITY), Catch::Contains("duration"));
    CHECK_THROWS_WITH(run(system, s, 1.0, 0), Catch::Contains("decimation must be >= 1"));
    CHECK_THROWS_WITH(run(system, s, 1e9), Catch::Contains("too many"));
    CHECK_THROWS_WITH(run(system, s, 1e3, 1, 1e6),
                      Catch::Contains("max_output_bytes") && Catch::Contains("increase decimation"));
}

TEST_CASE("a step that cannot converge halves, then reports time, step, iterations and residual") {
    const Sdof sdof;
    SolverSettings s;
    s.time_step = 1e-3;
    s.max_iterations = 1;  // one Newton iteration can never confirm convergence
    s.max_halvings = 3;
    const auto system = sdof.system();
    CHECK_THROWS_AS(run(system, s, 0.01), ConvergenceError);
    CHECK_THROWS_WITH(run(system, s, 0.01), Catch::Contains("did not converge at t = 0 s") &&
                                                Catch::Contains("time step 0.000125 s (3 halvings)") &&
                                                Catch::Contains("after 1 iterations; residual"));
}

TEST_CASE("Bathe's 2-DOF worked example (Finite Element Procedures, trapezoidal rule) to its printed digits") {
    // M = diag(2, 1), K = [6 -2; -2 4], R = (0, 10), U0 = 0, dt = 0.28, Newmark gamma = 1/2, beta = 1/4.
    // Values as printed (3 significant digits); transcribed from the book by Kratos' GeoMechanics tests
    // ("Finite Element Procedures, Bathe K.J., 1996, page 782") and by gfsReboucas/Drivetrain.
    LinearSystem<2> s;
    s.M.diagonal() << 2.0, 1.0;
    s.K << 6, -2, -2, 4;
    s.external = [](double) { return Eigen::Vector2d(0.0, 10.0); };
    SolverSettings settings;
    settings.time_step = 0.28;
    const auto r = run(s, settings, 12 * 0.28);
    const double u1[12] = {0.00673, 0.0505, 0.189, 0.485, 0.961, 1.58, 2.23, 2.76, 3.00, 2.85, 2.28, 1.40};
    const double u2[12] = {0.364, 1.35, 2.68, 4.00, 4.95, 5.34, 5.13, 4.48, 3.64, 2.90, 2.44, 2.31};
    REQUIRE(r.rows == 13);
    // Agreement to the printed digits: within one unit of the last printed digit everywhere, and
    // identical after rounding in all but one entry (step 2: U1 = 0.050448, printed 0.0505).
    auto unit = [](double printed) { return std::pow(10.0, std::floor(std::log10(std::abs(printed))) - 2); };
    auto rounded = [&](double x, double printed) { return std::round(x / unit(printed)) * unit(printed); };
    int identical = 0;
    for (int i = 0; i < 12; ++i) {
        const double a = r.q[2 * (i + 1)], b = r.q[2 * (i + 1) + 1];
        INFO("step " << i + 1 << ": U = (" << a << ", " << b << ")");
        CHECK(std::abs(a - u1[i]) <= unit(u1[i]));
        CHECK(std::abs(b - u2[i]) <= unit(u2[i]));
        identical += (std::abs(rounded(a, u1[i]) - u1[i]) < 1e-9) + (std::abs(rounded(b, u2[i]) - u2[i]) < 1e-9);
    }
    CHECK(identical >= 23);
}

TEST_CASE("beta < 1/4: a step beyond the stability limit is refused; a blow-up is reported, not returned") {
    Sdof sdof;
    sdof.c = 0.0;
    const auto system = sdof.system();
    SolverSettings s;
    s.beta = 1.0 / 12.0;  // stable for omega dt < 2.449
    const double omega = std::sqrt(sdof.k / sdof.m);
    s.time_step = 2.0 / omega;
    const auto fine = run(system, s, 100 * s.time_step);
    CHECK(std::abs(fine.q.back()) <= 1.01 * sdof.x0);
    s.time_step = 2.6 / omega;
    CHECK_THROWS_WITH(run(system, s, 1.0),
                      Catch::Contains("time_step") && Catch::Contains("exceeds the stability limit"));
    // A state that overflows (here a load growing without bound) is an error, never a result.
    LinearSystem<1> exploding = system;
    exploding.external = [](double t) { return Eigen::Matrix<double, 1, 1>(std::exp(1000.0 * t)); };
    SolverSettings plain;
    plain.time_step = 1e-3;
    plain.max_halvings = 1;
    CHECK_THROWS_WITH(run(exploding, plain, 1.0), Catch::Contains("became non-finite"));
}

TEST_CASE("The processed velocity's step limit: closed forms, and damping lowers it") {
    const double omega = 20.0;
    // Undamped it is plain Newmark's, 1 / (omega sqrt(1/4 - beta)): sqrt(6) / omega for Fox-Goodwin.
    CHECK(processed_mode_step_limit(1.0 / 12.0, omega, 0.0) == Approx(std::sqrt(6.0) / omega).epsilon(1e-5));
    CHECK(processed_mode_step_limit(0.2, omega, 0.0) == Approx(1.0 / (omega * std::sqrt(0.05))).epsilon(1e-5));
    // Damping alone (a = -c v): the accelerations' sawtooth a_k = (-1)^k A with vN = 0 solves the scheme
    // when the processed velocity, vN - (3 a1 - 4 a + a_prev) / 24 = A / 3, gives a1 = -c dt A / 3 = -A.
    CHECK(processed_mode_step_limit(1.0 / 12.0, 0.0, 50.0) == Approx(3.0 / 50.0).epsilon(1e-5));
    double last = std::numeric_limits<double>::infinity();
    for (double zeta : {0.0, 0.1, 0.5, 1.0, 5.0, 50.0}) {
        INFO("damping ratio " << zeta);
        const double limit = processed_mode_step_limit(1.0 / 12.0, omega, 2.0 * zeta * omega);
        CHECK(limit < last);
        CHECK(2.0 * zeta * omega * limit < 3.2);  // heavily damped: c dt of about 3, as damping alone
        last = limit;
    }
    // The stepper: at damping ratio 0.5 omega dt = 2 is within Fox-Goodwin's undamped limit (2.45 with a
    // 10 % margin: 2.2) and beyond the processed velocity's (1.65, with the margin 1.48). The stepper
    // itself refuses it, naming the mode's damping; simulate() runs it with the trapezoidal velocity
    // (choose_velocity) and says why; at 2.5 both are refused; at 1.4 the processed velocity runs.
    Sdof sdof;
    sdof.c = std::sqrt(sdof.k * sdof.m);  // damping ratio 1/2
    const auto system = sdof.system();
    SolverSettings s;
    s.beta = 1.0 / 12.0;
    REQUIRE(newmark_parameters(s).processed);
    s.time_step = 2.0 / omega;
    Newmark<LinearSystem<1>> stepper(system, s);
    CHECK_THROWS_WITH(stepper.start(0.0, system.q0, Eigen::Matrix<double, 1, 1>::Zero()),
                      Catch::Contains("exceeds the stability limit") && Catch::Contains("damping ratio 0.5"));
    RunOptions options;
    options.duration = 100 * s.time_step;
    const auto trapezoidal = simulate(system, s, options);
    CHECK_THAT(trapezoidal.velocity_choice,
               Catch::StartsWith("trapezoidal velocity") && Catch::Contains("damping ratio 0.5"));
    const auto last_q = [](const Recording& r) { return r.channel(r.block(0))[r.rows - 1]; };
    CHECK(std::abs(last_q(trapezoidal.recording)) < 1e-3 * sdof.x0);
    s.time_step = 2.5 / omega;
    options.duration = 100 * s.time_step;
    CHECK_THROWS_WITH(simulate(system, s, options), Catch::Contains("exceeds the stability limit"));
    s.time_step = 1.4 / omega;
    options.duration = 100 * s.time_step;
    const auto processed = simulate(system, s, options);
    CHECK(processed.velocity_choice.empty());
    CHECK(std::abs(last_q(processed.recording)) < 1e-3 * sdof.x0);
}

TEST_CASE("Fox-Goodwin with its processed velocity is fourth order in displacement and velocity, damped") {
    // The damped SDOF driven from rest (closed form in driven_sdof.hpp): the trapezoidal velocity is
    // off by dt^2 / 12 x''' and the damping force would carry that into a second-order error; the
    // processed velocity (NewmarkParameters::processed) removes it. Starting from rest with a jerk of
    // F W / m checks the history's start too.
    const DrivenSdof sdof;
    const auto system = sdof.system();
    const double period = sdof.period();
    for (const char* method : {"fox_goodwin", "newmark"}) {
        INFO(method);
        SolverSettings s;
        s.method = method_from_name(method);
        if (s.method == Method::newmark) s.gamma = 0.5, s.beta = 1.0 / 12.0;  // Fox-Goodwin by its parameters
        REQUIRE(newmark_parameters(s).processed);
        double eq[4], ev[4];
        for (int i = 0; i < 4; ++i) {
            s.time_step = period / (20.0 * (1 << i));
            const auto r = run(system, s, 3 * period);
            eq[i] = ev[i] = 0.0;
            for (std::size_t k = 0; k < r.rows; ++k) {
                const double t = r.t[k], h = 1e-6;
                eq[i] = std::max(eq[i], std::abs(r.q[k] - sdof.exact(t)));
                const double v = (sdof.exact(t + h) - sdof.exact(t - h)) / (2 * h);
                ev[i] = std::max(ev[i], std::abs(r.v[k] - v));
            }
        }
        for (int i = 0; i < 3; ++i) {
            INFO("dt = T/" << 20 * (1 << i) << ": errors " << eq[i] << " m, " << ev[i] << " m/s");
            CHECK(std::log2(eq[i] / eq[i + 1]) == Approx(4.0).margin(0.3));
            CHECK(std::log2(ev[i] / ev[i + 1]) == Approx(4.0).margin(0.3));
        }
    }
    SolverSettings average;  // the paper's rule is not processed, nor is HHT
    CHECK_FALSE(newmark_parameters(average).processed);
    CHECK_FALSE(newmark_parameters(SolverSettings::hht()).processed);
    CHECK(newmark_parameters(SolverSettings::named(Method::fox_goodwin, 1e-3, 1e-6)).processed);
}
