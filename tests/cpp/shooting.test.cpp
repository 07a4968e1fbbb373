// SPDX-License-Identifier: BSD-3-Clause
// Shooting for the periodic steady state (solver/shooting.hpp): on a linear forced system against the
// closed-form periodic response of the average-acceleration scheme and of the ODE, Floquet multipliers
// against the eigenvalues of the first-order system, and on the paper's mechanism against a long
// transient run.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"
#include "linear_system_instances.hpp"
#include "run.hpp"

using namespace camfollower;
using cd = std::complex<double>;

namespace {

// Two masses on springs, a dashpot on each, the first one forced by F cos(w t); modes well above w.
struct Forced2 {
    double w = 2 * pi * 10.0, F = 50.0;
    LinearSystem<2> system() const {
        LinearSystem<2> s;
        s.M << 2.0, 0.0, 0.0, 1.0;
        s.K << 3.0e5, -1.0e5, -1.0e5, 1.0e5;
        s.C << 40.0, -10.0, -10.0, 10.0;
        s.external = [w = w, F = F](double t) { return Eigen::Vector2d(F * std::cos(w * t), 0.0); };
        return s;
    }
    double period() const { return 2 * pi / w; }
    // Steady-state amplitude (complex) for the Laplace variable s: (K + s C + s^2 M) Q = F e1.
    Eigen::Vector2cd amplitude(cd s_var) const {
        const auto sys = system();
        const Eigen::Matrix2cd A = sys.K.cast<cd>() + s_var * sys.C.cast<cd>() + s_var * s_var * sys.M.cast<cd>();
        return A.partialPivLu().solve(Eigen::Vector2cd(F, 0.0));
    }
};

}  // namespace

TEST_CASE("shooting: a linear forced system lands on the closed-form periodic response") {
    const Forced2 f;
    const auto sys = f.system();
    const int steps = 1024;
    SolverSettings s;
    s.time_step = f.period() / steps;
    ShootingOptions o;
    o.period = f.period();
    o.tolerance = 1e-11;
    o.warmup_revolutions = 0;
    const PeriodicOrbit orbit = periodic_orbit(sys, s, o);
    REQUIRE(orbit.converged);
    // Linear: one Newton step from the forward-difference monodromy, then converged (within rounding).
    CHECK(orbit.iterations <= 2);
    // Average acceleration = trapezoidal rule on (q, v): its steady state for e^{i w t} forcing is the
    // frequency response at s_d = (2 i / h) tan(w h / 2) (bilinear transform), exactly.
    const double h = s.time_step;
    const cd sd(0.0, 2.0 / h * std::tan(f.w * h / 2));
    const Eigen::Vector2cd Qd = f.amplitude(sd);
    const Eigen::Vector2d q_discrete = Qd.real(), v_discrete = (sd * Qd).real();
    const double qmax = Qd.cwiseAbs().maxCoeff(), vmax = (sd * Qd).cwiseAbs().maxCoeff();
    INFO("q = " << orbit.q.transpose() << ", scheme's closed form " << q_discrete.transpose());
    CHECK((orbit.q - q_discrete).cwiseAbs().maxCoeff() < 1e-9 * qmax);
    CHECK((orbit.v - v_discrete).cwiseAbs().maxCoeff() < 1e-9 * vmax);
    // And the ODE's own periodic response, within the scheme's O((w h)^2) error.
    const Eigen::Vector2cd Q = f.amplitude(cd(0.0, f.w));
    CHECK((orbit.q - Q.real()).cwiseAbs().maxCoeff() < 1e-4 * qmax);
}

TEST_CASE("shooting: Floquet multipliers of a linear system are the scheme's amplification of its eigenvalues") {
    const Forced2 f;
    const auto sys = f.system();
    SolverSettings s;
    s.time_step = f.period() / 1024;
    ShootingOptions o;
    o.period = f.period();
    o.warmup_revolutions = 0;
    const PeriodicOrbit orbit = periodic_orbit(sys, s, o);
    REQUIRE(orbit.converged);
    REQUIRE(orbit.monodromy_at_orbit);
    REQUIRE(orbit.multipliers.size() == 4);
    // Eigenvalues lambda of x' = A x, A = [0 I; -M^-1 K  -M^-1 C]; trapezoidal amplification per step
    // (1 + lambda h / 2) / (1 - lambda h / 2), to the power of the steps per period.
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>().setIdentity();
    A.bottomLeftCorner<2, 2>() = -sys.M.inverse() * sys.K;
    A.bottomRightCorner<2, 2>() = -sys.M.inverse() * sys.C;
    const Eigen::Vector4cd lambda = Eigen::EigenSolver<Eigen::Matrix4d>(A).eigenvalues();
    const double h = s.time_step;
    for (int i = 0; i < 4; ++i) {
        const cd mu = std::pow((1.0 + lambda[i] * h / 2.0) / (1.0 - lambda[i] * h / 2.0), 1024.0);
        double nearest = 1e300;
        for (int j = 0; j < 4; ++j) nearest = std::min(nearest, std::abs(orbit.multipliers[j] - mu));
        INFO("lambda = " << lambda[i] << ", scheme multiplier " << mu << ", exp(lambda T) "
                         << std::exp(lambda[i] * f.period()));
        CHECK(nearest < 1e-5);
        // the ODE's exp(lambda T) within the scheme's error
        CHECK(std::abs(std::exp(lambda[i] * f.period()) - mu) < 2e-2 * std::abs(mu) + 1e-6);
    }
    CHECK(orbit.spectral_radius() < 1.0);
}

TEST_CASE("shooting: the variational monodromy of a linear system is the trapezoidal rule's amplification") {
    // The average-acceleration scheme on a linear system is the trapezoidal rule on x = (q, v): per
    // step x1 = (I - h A / 2)^-1 (I + h A / 2) x0 + forcing, so over N steps the monodromy is that
    // matrix to the power N, exactly (the variational equations are exact for a linear system).
    const Forced2 f;
    const auto sys = f.system();
    const int steps = 512;
    SolverSettings s;
    s.time_step = f.period() / steps;
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>().setIdentity();
    A.bottomLeftCorner<2, 2>() = -sys.M.inverse() * sys.K;
    A.bottomRightCorner<2, 2>() = -sys.M.inverse() * sys.C;
    const double h = s.time_step;
    const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
    const Eigen::Matrix4d step = (I - h / 2 * A).inverse() * (I + h / 2 * A);
    Eigen::Matrix4d expected = I;
    for (int k = 0; k < steps; ++k) expected = step * expected;
    for (const MonodromyMethod method : {MonodromyMethod::variational, MonodromyMethod::differences}) {
        ShootingOptions o;
        o.period = f.period();
        o.warmup_revolutions = 0;
        o.monodromy_method = method;
        const PeriodicOrbit orbit = periodic_orbit(sys, s, o);
        REQUIRE(orbit.converged);
        REQUIRE(orbit.monodromy_method == method);
        const double error = (orbit.monodromy - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
        INFO(monodromy_method_name(method) << ": relative error " << error);
        // Forward differences carry their truncation and rounding error; the variational one only rounding.
        CHECK(error < (method == MonodromyMethod::variational ? 1e-11 : 1e-5));
        // The first revolution (with the monodromy), the Newton step (exact: linear), the monodromy again
        // at the orbit for its multipliers: 3 revolutions, against 1 + 4 + 1 + 4 by differences.
        if (method == MonodromyMethod::variational) {
            CHECK(orbit.variational_revolutions == 2.0);
            CHECK(orbit.revolutions == 3.0);
        } else {
            CHECK(orbit.variational_revolutions == 0.0);
            CHECK(orbit.revolutions >= 10.0);
        }
    }
}

TEST_CASE("shooting: the variational and finite-difference monodromies agree on the nonlinear mechanism") {
    // The paper mechanism (Hertz contact: the tangent changes along the revolution) under each
    // scheme of the Newmark family, HHT's alpha term included. Its lightly damped modes keep the
    // monodromy's entries large, so forward differences are accurate to ~1e-8 here (on the damped
    // variant the entries decay to ~1e-5 and differences scatter by 1e-4 with the perturbation).
    const auto m = presets::paper();
    for (const Method method : {Method::newmark, Method::fox_goodwin, Method::hht}) {
        SolverSettings s;
        s.method = method;
        if (method == Method::hht) s.hht_alpha = -0.1;
        s.time_step = m.period() / 8192;
        ShootingOptions o;
        o.tolerance = 1e-10;
        o.monodromy_method = MonodromyMethod::differences;
        const PeriodicOrbit fd = periodic_orbit(m, s, o);
        o.monodromy_method = MonodromyMethod::variational;
        const PeriodicOrbit var = periodic_orbit(m, s, o);
        REQUIRE(fd.converged);
        REQUIRE(var.converged);
        REQUIRE(var.monodromy_at_orbit);
        REQUIRE(fd.monodromy_at_orbit);
        const double scale = fd.monodromy.cwiseAbs().maxCoeff();
        const double difference = (fd.monodromy - var.monodromy).cwiseAbs().maxCoeff() / scale;
        INFO(method_name(method) << ": monodromies differ by " << difference << " relative; revolutions "
                                 << var.revolutions << " against " << fd.revolutions);
        CHECK(difference < 1e-6);
        CHECK(var.variational_revolutions == var.monodromies);
        CHECK((fd.q - var.q).cwiseAbs().maxCoeff() <= 1e-9 * fd.q_scale);
        CHECK(std::abs(var.spectral_radius() - fd.spectral_radius()) < 1e-6);
        CHECK(var.iterations <= fd.iterations);
        CHECK(var.revolutions < fd.revolutions / 3);
    }
}

TEST_CASE("shooting: the paper mechanism's periodic orbit is the one a long transient run converges to") {
    const auto m = presets::paper_damped();
    SolverSettings s;
    s.time_step = m.period() / 4096;
    ShootingOptions o;
    o.tolerance = 1e-11;
    const PeriodicOrbit orbit = periodic_orbit(m, s, o);
    REQUIRE(orbit.converged);
    INFO("iterations " << orbit.iterations << ", revolutions " << orbit.revolutions << ", spectral radius "
                       << orbit.spectral_radius());
    CHECK(orbit.spectral_radius() < 1.0);
    // Transient: 40 revolutions from the static state (the same fixed-step Newmark).
    const auto transient = run(m, s, 40 * m.period(), 4096);
    const auto& state = transient.final_state;
    CHECK(transient.stats.steps == 40u * 4096u);
    const double qs = orbit.q_scale, vs = orbit.v_scale;
    const double dq = (state.q - orbit.q).cwiseAbs().maxCoeff() / qs,
                 dv = (state.v - orbit.v).cwiseAbs().maxCoeff() / vs;
    INFO("relative difference q " << dq << ", v " << dv);
    CHECK(dq < 1e-8);
    CHECK(dv < 1e-8);
    CHECK(orbit.revolutions < 40);
}

TEST_CASE("shooting: bad options are refused naming the option") {
    const Forced2 f;
    const auto sys = f.system();
    SolverSettings s;
    s.time_step = f.period() / 1000.5;
    ShootingOptions o;
    o.period = f.period();
    CHECK_THROWS_WITH(periodic_orbit(sys, s, o), Catch::Contains("divides the period"));
    s.time_step = f.period() / 1000;
    o.tolerance = 0.0;
    CHECK_THROWS_WITH(periodic_orbit(sys, s, o), Catch::Contains("shooting tolerance"));
    o.tolerance = 1e-9;
    o.monodromy = Eigen::MatrixXd::Identity(3, 3);
    CHECK_THROWS_WITH(periodic_orbit(sys, s, o), Catch::Contains("monodromy guess"));
    o.monodromy.resize(0, 0);
    // The explicit methods carry no variational equations: asked for by name, refused by name.
    o.monodromy_method = MonodromyMethod::variational;
    SolverSettings explicit_method = s;
    explicit_method.method = Method::dormand_prince;
    explicit_method.tolerance = 1e-6;
    CHECK_THROWS_WITH(periodic_orbit(sys, explicit_method, o),
                      Catch::Contains("monodromy 'variational'") && Catch::Contains("'differences'"));
    CHECK_THROWS_WITH(monodromy_method_from_name("exact"), Catch::Contains("monodromy must be 'auto'"));
    o.monodromy_method = MonodromyMethod::automatic;
    // The nonlinear mechanism does not reach 1e-15 (below rounding) in one Newton step from its static state.
    const auto m = presets::paper_damped();
    s.time_step = m.period() / 2048;
    ShootingOptions one;
    one.max_iterations = 1;
    one.warmup_revolutions = 0;
    one.tolerance = 1e-15;
    const PeriodicOrbit orbit = periodic_orbit(m, s, one);
    CHECK_FALSE(orbit.converged);
    CHECK_THROWS_WITH(require_converged(orbit, one),
                      Catch::Contains("did not converge") && Catch::Contains("mismatch"));
}

TEST_CASE("long runs keep time as t0 + n dt: no drift to excite lightly damped modes") {
    LinearSystem<1> sys;
    SolverSettings s;
    s.time_step = 1e-5 / 3.0;  // not a binary fraction: a running sum drifts
    Newmark<LinearSystem<1>> stepper(sys, s);
    auto state = stepper.start(0.0, LinearSystem<1>::Vector::Zero(), LinearSystem<1>::Vector::Zero());
    const std::uint64_t n = 1u << 22;
    const IntegrationReport report =
        integrate(stepper, state, double(n) * s.time_step, [](const auto&, std::uint64_t) { return true; });
    REQUIRE(report.planned_steps == n);
    CHECK(state.t == double(n) * s.time_step);
    double sum = 0.0;  // what summing step by step gives
    for (std::uint64_t i = 0; i < n; ++i) sum += s.time_step;
    CHECK(std::abs(sum - double(n) * s.time_step) > 1e-12);  // the drift the driver avoids
}
