// SPDX-License-Identifier: BSD-3-Clause
// Radau IIA of order 5 (solver/radau.hpp): its tableau against the order conditions, its observed
// order and adaptive error against closed forms, a stiff system against its exact solution (matrix
// exponential by eigenvectors) in far fewer steps than an explicit method's stability allows, the
// paper preset against DOP853, a contact loss located like DOP853's, bad settings.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/radau.hpp"
#include "camfollower/solver/simulate.hpp"
#include "driven_sdof.hpp"
#include "linear_system_instances.hpp"
#include "run.hpp"

using namespace camfollower;

namespace {

SolverSettings radau(double time_step, double tolerance = 1e-6) {
    SolverSettings s;
    s.method = method_from_name("radau");
    s.time_step = time_step;
    s.tolerance = tolerance;
    return s;
}

}  // namespace

TEST_CASE("Radau IIA tableau: order conditions B(5), C(3), the eigen-decomposition, the estimate and the polynomial") {
    const radau5::Tableau t = radau5::tableau();
    const Eigen::Vector3d b = t.A.row(2).transpose();  // stiffly accurate: b is the last row
    for (int i = 0; i < 3; ++i) CHECK(t.A.row(i).sum() == Approx(t.c[i]).epsilon(1e-14));
    // B(5): sum b_i c_i^(k-1) = 1/k; and not B(6) (order 5, not more).
    for (int k = 1; k <= 6; ++k) {
        double sum = 0.0;
        for (int i = 0; i < 3; ++i) sum += b[i] * std::pow(t.c[i], k - 1);
        CAPTURE(k);
        if (k <= 5) CHECK(std::abs(sum - 1.0 / k) < 1e-14);
        else CHECK(std::abs(sum - 1.0 / k) > 1e-4);
    }
    // C(3): sum_j a_ij c_j^(k-1) = c_i^k / k, stage order 3.
    for (int i = 0; i < 3; ++i)
        for (int k = 1; k <= 3; ++k) {
            double sum = 0.0;
            for (int j = 0; j < 3; ++j) sum += t.A(i, j) * std::pow(t.c[j], k - 1);
            CHECK(std::abs(sum - std::pow(t.c[i], k) / k) < 1e-14);
        }
    // The published eigenvalues of A^-1: 3 + 3^(2/3) - 3^(1/3) and 3 + (3^(1/3) - 3^(2/3)) / 2 +-
    // i (3^(5/6) + 3^(7/6)) / 2 (Hairer & Wanner, IV.8).
    CHECK(t.mu_real == Approx(3.0 + std::cbrt(9.0) - std::cbrt(3.0)).epsilon(1e-13));
    CHECK(t.mu_pair.real() == Approx(3.0 + 0.5 * (std::cbrt(3.0) - std::cbrt(9.0))).epsilon(1e-13));
    CHECK(std::abs(t.mu_pair.imag()) ==
          Approx(0.5 * (std::pow(3.0, 5.0 / 6.0) + std::pow(3.0, 7.0 / 6.0))).epsilon(1e-13));
    // Z = v_real w_real + 2 Re(v_pair w_pair) inverts the transformation, and A^-1 Z maps like diag(mu).
    const Eigen::Vector3d Z(0.3, -1.7, 2.2);
    const double w_real = t.w_row_real.dot(Z);
    const std::complex<double> w_pair = (t.w_row_pair * Z.cast<std::complex<double>>())(0);
    const Eigen::Vector3d back = t.v_real * w_real + 2.0 * (t.v_pair * w_pair).real();
    CHECK((back - Z).norm() < 1e-13);
    const Eigen::Vector3d AZ = t.A.inverse() * Z;
    const Eigen::Vector3d mapped = t.v_real * (t.mu_real * w_real) + 2.0 * (t.v_pair * (t.mu_pair * w_pair)).real();
    CHECK((AZ - mapped).norm() < 1e-12 * AZ.norm());
    // The error weights as published (Hairer & Wanner IV.8; scipy's Radau): -(13 +- 7 sqrt 6) / 3, -1/3.
    CHECK(t.e[0] == Approx(-(13.0 + 7.0 * std::sqrt(6.0)) / 3.0).epsilon(1e-12));
    CHECK(t.e[1] == Approx((-13.0 + 7.0 * std::sqrt(6.0)) / 3.0).epsilon(1e-12));
    CHECK(t.e[2] == Approx(-1.0 / 3.0).epsilon(1e-12));
    // The collocation polynomial passes through the stages: sum_k c_i^(k+1) Q_k = Z_i.
    const Eigen::Vector3d Q = t.dense * Z;
    for (int i = 0; i < 3; ++i)
        CHECK(t.c[i] * Q[0] + t.c[i] * t.c[i] * Q[1] + std::pow(t.c[i], 3) * Q[2] == Approx(Z[i]).epsilon(1e-13));
}

TEST_CASE("Radau IIA with fixed steps is fifth order on a driven damped oscillator") {
    const DrivenSdof sdof;
    const double T = sdof.period();
    double errors[4];
    for (int i = 0; i < 4; ++i) {
        SolverSettings s = radau(T / (20 * (1 << i)));
        s.tolerance.reset();
        s.max_step = s.time_step;  // fixed steps
        errors[i] = max_error(sdof, s, 3 * T);
    }
    for (int i = 1; i < 4; ++i) {
        const double observed = std::log2(errors[i - 1] / errors[i]);
        INFO("T/" << 20 * (1 << i) << ": error " << errors[i] << ", observed order " << observed);
        CHECK(std::abs(observed - 5.0) < 0.1);
    }
    CHECK(errors[3] > 1e-13);  // above rounding: the orders measure the method
}

TEST_CASE("Radau IIA: the adaptive error follows the tolerance") {
    const DrivenSdof sdof;
    const double T = sdof.period();
    const double peak = sdof.F / sdof.k * 10.0;  // generous bound of |x|
    double previous = 1.0;
    for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
        const double err = max_error(sdof, radau(T / 64, tol), 3 * T);
        INFO("tolerance " << tol << ": max error " << err << " (" << err / peak << " of the peak)");
        CHECK(err < 30.0 * tol * peak);
        CHECK(err < previous);
        previous = err;
    }
}

TEST_CASE(
    "Radau IIA on a stiff system: exact to the tolerance in a few hundred steps, where explicit stability needs "
    "~10^5") {
    // A soft mode (~16 rad/s) driven at 6 rad/s, and a stiff, damped one (~1.4e5 rad/s, 35 % of critical).
    LinearSystem<2> stiff;
    stiff.M << 1.0, 0.0, 0.0, 1.0;
    stiff.K << 250.0 + 1e10, -1e10, -1e10, 1e10;
    stiff.C << 1e5, -1e5, -1e5, 1e5;
    stiff.external = [](double t) { return Eigen::Vector2d(std::sin(6.0 * t), 0.0); };
    const double duration = 2.0;
    // Exact: y' = A y + g sin(6 t), y = (q, v) from rest; particular Im((6i - A)^-1 g e^(6it)), free
    // part by the eigenvectors of A.
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>().setIdentity();
    A.bottomLeftCorner<2, 2>() = -stiff.K;
    A.bottomRightCorner<2, 2>() = -stiff.C;
    const Eigen::Vector4cd g(0, 0, 1, 0);
    const std::complex<double> i6(0.0, 6.0);
    const Eigen::Vector4cd P =
        (i6 * Eigen::Matrix4cd::Identity() - A.cast<std::complex<double>>()).partialPivLu().solve(g);
    const Eigen::EigenSolver<Eigen::Matrix4d> eig(A);
    const Eigen::Matrix4cd V = eig.eigenvectors();
    const Eigen::Vector4cd coeff = V.partialPivLu().solve(-P.imag().cast<std::complex<double>>());
    auto exact_q1 = [&](double t) {
        Eigen::Vector4cd free = Eigen::Vector4cd::Zero();
        for (int k = 0; k < 4; ++k) free += V.col(k) * (coeff[k] * std::exp(eig.eigenvalues()[k] * t));
        return (P * std::exp(i6 * t)).imag()[0] + free.real()[0];
    };
    const double omega_max = eig.eigenvalues().cwiseAbs().maxCoeff();
    for (double tol : {1e-5, 1e-7}) {
        const auto r = run(stiff, radau(0.01, tol), duration);
        double err = 0.0, peak = 0.0;
        for (std::size_t i = 0; i < r.rows; ++i) {
            err = std::max(err, std::abs(r.q[2 * i] - exact_q1(r.t[i])));
            peak = std::max(peak, std::abs(exact_q1(r.t[i])));
        }
        // Dormand-Prince's stability boundary is h |lambda| ~ 3.3.
        const double explicit_steps = duration * omega_max / 3.3;
        INFO("tolerance " << tol << ": error " << err / peak << " of the peak, " << r.stats.steps << " steps, "
                          << r.stats.rejected_steps << " rejected; explicit stability needs ~" << explicit_steps);
        CHECK(err < 50.0 * tol * peak);
        CHECK(double(r.stats.steps) < 1e-2 * explicit_steps);
    }
}

TEST_CASE("Radau IIA on the paper preset agrees with DOP853 at tight tolerance") {
    const Mechanism<presets::paper_dofs> m = presets::paper();
    const double T = m.period();
    SolverSettings d8 = radau(T / 512, 1e-10);
    d8.method = method_from_name("dop853");
    const auto ra = run(m, radau(T / 512, 1e-9), T);
    const auto dp = run(m, d8, T);
    REQUIRE(ra.rows == 513);
    REQUIRE(dp.rows == ra.rows);
    auto difference = [&](const char* channel) {
        const double* x = dp.channel(channel);
        const double* y = ra.channel(channel);
        double peak = 0.0, diff = 0.0;
        for (std::size_t i = 0; i < dp.rows; ++i)
            peak = std::max(peak, std::abs(x[i])), diff = std::max(diff, std::abs(x[i] - y[i]));
        return diff / peak;
    };
    const double force = difference("cam.force"), accel = difference("a.y4");
    INFO("force " << force << ", follower acceleration " << accel << " of the peak; radau " << ra.stats.steps
                  << " steps, " << ra.stats.newton_iterations << " Newton iterations, " << ra.stats.rejected_steps
                  << " rejected");
    // Radau's global error at 1e-9 is ~9e-9 of the peak force (docs/benchmarks.md), DOP853's at 1e-10 ~1e-9.
    CHECK(force < 1e-7);
    CHECK(accel < 1e-7);
    CHECK(force > 1e-11);  // two methods, not one
    CHECK(ra.stats.newton_iterations >= ra.stats.steps);
}

TEST_CASE("Radau IIA locates a contact loss and re-contact where DOP853 does") {
    CamFollowerParameters p;
    p.camshaft_speed_rpm = 2000.0;  // above the jump speed, 1329 rpm
    const Mechanism<presets::paper_dofs> m = presets::paper(p);
    const double T = m.period();
    SolverSettings d8 = radau(T / 1024, 1e-10);
    d8.method = method_from_name("dop853");
    RunOptions o;
    o.duration = T;
    const auto a = simulate(m, radau(T / 1024, 1e-10), o);
    const auto b = simulate(m, d8, o);
    REQUIRE(b.events.size() >= 2);
    REQUIRE(a.events.size() == b.events.size());
    for (std::size_t k = 0; k < a.events.size(); ++k) {
        CAPTURE(k, a.events[k].time, b.events[k].time);
        CHECK(a.events[k].direction == b.events[k].direction);
        CHECK(std::abs(a.events[k].time - b.events[k].time) < 1e-8 * T);
    }
}

TEST_CASE("Radau IIA refuses what it cannot honour, naming it") {
    const DrivenSdof sdof;
    SolverSettings s = radau(1e-3, 0.0);
    CHECK_THROWS_WITH(s.validate(), Catch::Contains("tolerance"));
    s = radau(1e-3);
    s.backend = Backend::sparse;
    RunOptions o;
    o.duration = 0.1;
    CHECK_THROWS_WITH(simulate(sdof.system(), s, o), Catch::Contains("radau runs on the dense backend only"));
}
