// SPDX-License-Identifier: BSD-3-Clause
// The 7-DOF model: contact law, network assembly, static equilibrium, modes, dynamics limits.
#include <catch2/catch.hpp>

#include <cmath>

#include "camfollower/camfollower.hpp"
#include "run.hpp"

using namespace camfollower;
using Model = CamFollowerModel;

TEST_CASE("Hertz contact: force law, exact tangent, unilateral") {
    for (double n : {1.0, 1.5, 10.0 / 9.0}) {
        const HertzContact law{2e9, n, 0.3};
        const double d = 2e-6, dd = 0.05, h = 1e-12;
        const ContactResponse r = law(d, dd);
        CHECK(r.force == Approx(2e9 * std::pow(d, n) * (1 + 0.3 * dd)).epsilon(1e-14));
        CHECK(r.stiffness == Approx((law(d + h, dd).force - law(d - h, dd).force) / (2 * h)).epsilon(1e-6));
        CHECK(r.damping == Approx((law(d, dd + 1e-6).force - law(d, dd - 1e-6).force) / 2e-6).epsilon(1e-6));
        CHECK(r.in_contact);
        const ContactResponse open = law(-1e-9, dd);
        CHECK(open.force == 0.0);
        CHECK(open.stiffness == 0.0);
        CHECK_FALSE(open.in_contact);
    }
    // A fast separation with damping cannot pull.
    CHECK(HertzContact{1e8, 1.0, 10.0}(1e-6, -1.0).force == 0.0);
}

TEST_CASE("network assembly: symmetric, grounded springs on the diagonal only") {
    const Model m;
    const auto& K = m.stiffness_matrix();
    CHECK((K - K.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(K(Model::y1, Model::y1) == 2.6e8);
    CHECK(K(Model::y2, Model::y3) == -1.7e8);
    CHECK(K(Model::y4, Model::y4) == 2.5e8 + 1.4e4);
    CHECK(K(Model::x3, Model::x3) == 2.5e8 + 2.5e8);
    CHECK(K(Model::y1, Model::y2) == 0.0);  // coupled by the contact only
    CHECK(m.damping_matrix()(Model::y3, Model::y4) == -0.08);
    CHECK(m.mass_matrix()(Model::y2, Model::y2) == 0.07);
    // Rigid translation of the follower chain in y stretches only the ground springs.
    Model::Vector rigid = Model::Vector::Zero();
    rigid[Model::y2] = rigid[Model::y3] = rigid[Model::y4] = 1.0;
    CHECK((K * rigid)[Model::y4] == 1.4e4);
    CHECK((K * rigid)[Model::y2] == 0.0);
}

TEST_CASE("static equilibrium on the dwell: the axial contact force is the spring preload") {
    const Model m;
    const auto q = m.initial_state();
    const auto c = m.at_time(0.0);
    const auto nl = m.nonlinear(c, q, Model::Vector::Zero());
    const double preload = 1.4e4 * 0.013;  // K_rs delta_rs = 182 N
    CHECK(nl.contact.force * c.kinematics.cos_alpha == Approx(preload).epsilon(1e-9));
    // The normal force is larger: the dwell pressure angle is atan(-e / s0) = -15.26 deg.
    CHECK(nl.contact.force == Approx(preload / std::cos(std::atan(0.01 / std::sqrt(0.038 * 0.038 - 1e-4)))).epsilon(1e-9));
    CHECK(m.spring_preload() + 1.4e4 * q[Model::y4] == Approx(preload).epsilon(1e-12));
    // Every DOF balanced: K q + F_c g - external = 0.
    const Model::Vector r = m.stiffness_matrix() * q + nl.force;
    CHECK(r.cwiseAbs().maxCoeff() < 1e-9 * preload);
    // The bearing carries the axial load: y1 = -182 N / K_vs.
    CHECK(q[Model::y1] == Approx(-preload / 2.6e8).epsilon(1e-9));
}

TEST_CASE("quasi-static equilibrium converges at every cam angle, axial force = spring force") {
    const Model m;
    for (int deg = 0; deg < 360; deg += 5) {
        const double theta = degrees_to_radians(deg);
        INFO("theta = " << deg << " deg");
        const auto q = m.static_equilibrium(theta);
        const auto c = m.at_time(theta / m.omega());
        const auto nl = m.nonlinear(c, q, Model::Vector::Zero());
        // The follower chain is in series: the contact's axial part carries the return spring.
        CHECK(nl.contact.force * c.kinematics.cos_alpha == Approx(m.spring_preload() + 1.4e4 * q[Model::y4]).epsilon(1e-9));
        CHECK(q[Model::y4] == Approx(c.kinematics.h).margin(20e-6));
    }
}

TEST_CASE("gravity adds the follower weight to the axial contact force") {
    CamFollowerParameters p;
    p.gravity = 9.81;
    const Model m(p);
    const auto c = m.at_time(0.0);
    const auto nl = m.nonlinear(c, m.initial_state(), Model::Vector::Zero());
    CHECK(nl.contact.force * c.kinematics.cos_alpha == Approx(182.0 + 9.81 * (0.07 + 0.34 + 1.36)).epsilon(1e-9));
}

TEST_CASE("modal analysis: contact-free camshaft bearing mode and the specified topology's modes") {
    const Model m;
    const ModalResult free = modal_analysis(m, 0.0, false);
    // Without contact the camshaft is two decoupled oscillators sqrt(K_vs / m_c) = 2447 Hz.
    int at_2447 = 0;
    for (int k = 0; k < 7; ++k) at_2447 += std::abs(free.frequencies_hz[k] - 2447.0) < 1e-6;
    CHECK(at_2447 == 2);
    // The follower on its return spring alone: sqrt(K_rs / (M_fc + M_f + M_eq)) / 2 pi, nearly.
    CHECK(free.frequencies_hz[0] == Approx(std::sqrt(1.4e4 / 1.77) / (2 * pi)).epsilon(1e-3));
    // With contact on the dwell: the values docs/model.md lists for this topology.
    const ModalResult with = modal_analysis(m, 0.0);
    const double expected[7] = {868, 2447, 2747, 3893, 5319, 10403, 12013};
    for (int k = 0; k < 7; ++k) CHECK(with.frequencies_hz[k] == Approx(expected[k]).margin(0.6));
    // Mass-normalized shapes.
    const Model::Matrix I = with.mode_shapes.transpose() * m.mass_matrix() * with.mode_shapes;
    CHECK((I - Model::Matrix::Identity()).cwiseAbs().maxCoeff() < 1e-10);
    // The contact stiffness projected on y varies with the pressure angle: modes shift on the flanks.
    CHECK(modal_analysis(m, degrees_to_radians(290.0)).frequencies_hz[0] != Approx(with.frequencies_hz[0]).epsilon(1e-3));
}

TEST_CASE("Sherman-Morrison and dense LU give the same trajectory") {
    const Model m;
    SolverSettings s;
    const auto a = run(m, s, 0.3 * m.period(), 10);
    s.linear_solver = LinearSolver::dense_lu;
    const auto b = run(m, s, 0.3 * m.period(), 10);
    REQUIRE(a.rows == b.rows);
    double dq = 0, df = 0;
    for (std::size_t i = 0; i < a.q.size(); ++i) dq = std::max(dq, std::abs(a.q[i] - b.q[i]));
    for (std::size_t i = 0; i < a.rows; ++i) df = std::max(df, std::abs(a.channel("contact_force")[i] - b.channel("contact_force")[i]));
    CHECK(dq < 1e-14);
    CHECK(df < 1e-6);
}

TEST_CASE("one revolution: y4 follows h, the dwell starts at rest, Newton needs about two iterations") {
    const Model m;
    SolverSettings s;
    const auto r = run(m, s, m.period(), 1);
    CHECK(r.stats.halvings == 0);
    CHECK(r.stats.mean_iterations() < 2.5);
    CHECK(Model::contact_loss(r.final_state.workspace, r.final_state.t).empty());
    double worst = 0;
    for (std::size_t i = 0; i < r.rows; ++i) {
        const double h = m.cam().program().evaluate(r.channel("theta")[i]).h;
        worst = std::max(worst, std::abs(r.q[7 * i + Model::y4] - h));
        if (r.channel("theta")[i] < degrees_to_radians(29.0)) CHECK(std::abs(r.a[7 * i + Model::y4]) < 1e-6);
    }
    CHECK(worst < 20e-6);  // static deflection (3.7 um) plus vibration
}

TEST_CASE("rigid limit: with stiffnesses x1e3 the follower acceleration approaches omega^2 h''") {
    auto worst_error = [](double scale, double dt) {
        CamFollowerParameters p;
        for (const char* name : {"bearing_stiffness_vertical", "bearing_stiffness_horizontal", "contact_stiffness",
                                 "roller_pin_stiffness_vertical", "roller_pin_stiffness_horizontal",
                                 "guide_stiffness", "rod_stiffness"})
            p.set(name, p.get(name) * scale);
        const Model m(p);
        SolverSettings s;
        s.time_step = dt;
        const auto r = run(m, s, m.period(), 10);
        double worst = 0;
        for (std::size_t i = 0; i < r.rows; ++i) {
            const double theory = m.omega() * m.omega() * m.cam().program().evaluate(r.channel("theta")[i]).d2h;
            worst = std::max(worst, std::abs(r.a[7 * i + Model::y4] - theory));
        }
        return worst;
    };
    const double peak = 43.993;  // omega^2 h_max C_a / beta^2
    const double flexible = worst_error(1.0, 3e-6), rigid = worst_error(1e3, 1e-7);
    INFO("max |a4 - omega^2 h''|: flexible " << flexible << " m/s^2, stiff x1e3 " << rigid << " m/s^2");
    CHECK(rigid < 0.01 * peak);
    CHECK(rigid < flexible / 10);
}

TEST_CASE("contact loss at high speed is detected and reported as intervals") {
    CamFollowerParameters p;
    p.camshaft_speed_rpm = 3000;  // inertia ~ 16 x: the 182 N preload cannot hold the follower
    const Model m(p);
    SolverSettings s;
    s.time_step = 1e-6;
    const auto r = run(m, s, m.period(), 1);
    const auto losses = Model::contact_loss(r.final_state.workspace, r.final_state.t);
    REQUIRE_FALSE(losses.empty());
    double lost = 0;
    for (const auto& [a, b] : losses) {
        CHECK(b > a);
        lost += b - a;
    }
    CHECK(lost > 0.0);
    for (std::size_t i = 0; i < r.rows; ++i)
        if (r.channel("in_contact")[i] == 0.0) CHECK(r.channel("contact_force")[i] == 0.0);
}

TEST_CASE("parameters: by name, validated, unknown names listed") {
    CamFollowerParameters p;
    CHECK(p.get("contact_stiffness") == 1.9e8);
    CHECK(p.camshaft_mass == Approx(1.0999).margin(1e-4));
    p.set("roller_mass", 0.1);
    CHECK(p.roller_mass == 0.1);
    CHECK_THROWS_WITH(p.set("roller_mass", -1.0), Catch::Contains("roller_mass must be finite and > 0"));
    CHECK(p.roller_mass == 0.1);  // unchanged after a rejected set
    CHECK_THROWS_WITH(p.set("rod_stiffness", -5.0), Catch::Contains("rod_stiffness must be finite and > 0"));
    CHECK_THROWS_WITH(p.set("spring_stiffness", 0.0), Catch::Contains("spring_stiffness must be finite and > 0"));
    CHECK_THROWS_WITH(p.set("rod_damping", -1.0), Catch::Contains("rod_damping must be finite and >= 0"));
    p.set("rod_damping", 0.0);  // dampers may be zero
    CHECK_THROWS_WITH(p.set("guide_stiffness", NAN), Catch::Contains("guide_stiffness must be finite"));
    CHECK_THROWS_WITH(p.set("contact_exponent", 0.5), Catch::Contains("contact_exponent must be in [1, 3]"));
    CHECK_THROWS_WITH(p.set("offset", 0.05), Catch::Contains("|offset| < base_radius + roller_radius"));
    CHECK_THROWS_WITH(p.set("stiffnes", 1.0), Catch::Contains("unknown parameter 'stiffnes'") &&
                                                 Catch::Contains("rod_stiffness"));
    CamFollowerParameters bad;
    bad.follower_mass = 0.0;
    CHECK_THROWS_WITH(Model(bad), Catch::Contains("follower_mass"));
}

TEST_CASE("backlash side: + on rises, - on returns, dwells keep the last side, smooth ramp") {
    const MotionProgram p = MotionProgram::paper_default();
    const double deg = pi / 180;
    const BacklashSide hard(p, 0.0);
    CHECK(hard.at(10 * deg).side == -1.0);  // dwell after the return
    CHECK(hard.at(100 * deg).side == 1.0);
    CHECK(hard.at(195 * deg).side == 1.0);  // dwell after the rise
    CHECK(hard.at(300 * deg).side == -1.0);
    const BacklashSide smooth(p, 10 * deg);
    CHECK(smooth.at(35 * deg).side == Approx(0.0).margin(1e-12));  // halfway through the ramp
    CHECK(smooth.at(41 * deg).side == 1.0);
    const double fd = (smooth.at(33 * deg + 1e-7).side - smooth.at(33 * deg - 1e-7).side) / 2e-7;
    CHECK(smooth.at(33 * deg).dside == Approx(fd).epsilon(1e-6));
    CHECK_THROWS_WITH((Defects{0, 0, -1e-6, 0}.validate()), Catch::Contains("backlash must be finite and >= 0"));
    // An eccentricity that would push the effective offset past the pitch circle is refused.
    CHECK_THROWS_WITH(Model({}, MotionProgram::paper_default(), Defects{0.03, 0, 0, 0}),
                      Catch::Contains("must stay below base_radius + roller_radius"));
}

TEST_CASE("contact damping: exact (non-symmetric) tangent keeps Newton fast, both linear solvers agree") {
    CamFollowerParameters p;
    p.contact_damping = ContactDampingModel::hunt_crossley;
    p.restitution = 0.2;
    p.reference_speed = 0.01;  // chi = 3 (1 - 0.2) / (2 * 0.01) = 120 s/m
    p.contact_exponent = 1.5;
    p.contact_stiffness = 1e11;  // N/m^1.5: tangent 1.5 F / delta ~ 1.9e8 N/m at the 1.5 um static penetration
    const Model m(p);
    SolverSettings s;
    const auto a = run(m, s, 0.6 * m.period(), 10);
    s.linear_solver = LinearSolver::dense_lu;
    const auto b = run(m, s, 0.6 * m.period(), 10);
    CHECK(a.stats.halvings == 0);
    // Nonlinear law: quadratic convergence takes a few iterations, not tens.
    CHECK(a.stats.mean_iterations() < 4.0);
    CHECK(a.stats.max_iterations_in_a_step <= 6);
    double dq = 0;
    for (std::size_t i = 0; i < a.q.size(); ++i) dq = std::max(dq, std::abs(a.q[i] - b.q[i]));
    CHECK(dq < 1e-12);
    // The damped contact dissipates: less residual vibration on the top dwell than without it.
    p.contact_damping = ContactDampingModel::none;
    const Model undamped(p);
    const auto c = run(undamped, SolverSettings{}, 0.6 * m.period(), 10);
    auto dwell_vibration = [&](const Histories<Model>& r) {
        double worst = 0;
        for (std::size_t i = 0; i < r.rows; ++i)
            if (r.channel("theta")[i] > degrees_to_radians(185.0) && r.channel("theta")[i] < degrees_to_radians(209.0))
                worst = std::max(worst, std::abs(r.a[7 * i + Model::y4]));  // theory: 0 on the dwell
        return worst;
    };
    INFO("peak |a4| on the top dwell: damped " << dwell_vibration(a) << ", undamped " << dwell_vibration(c));
    CHECK(dwell_vibration(a) < 0.9 * dwell_vibration(c));
}

TEST_CASE("penetration rate and Newton tangent against finite differences, with and without defects") {
    CamFollowerParameters p;
    p.contact_damping = ContactDampingModel::lankarani_nikravesh;
    p.restitution = 0.5;
    p.reference_speed = 0.1;
    p.contact_exponent = 1.5;
    p.contact_stiffness = 1e11;
    const Defects cases[] = {Defects{}, Defects{1e-3, 0.3, 0, 0}, Defects{0, 0, 1e-3, degrees_to_radians(40.0)}};
    for (const Defects& d : cases) {
        const Model m(p, MotionProgram::paper_default(), d);
        INFO("eccentricity " << d.eccentricity << ", backlash " << d.backlash);
        Model::Vector v0;
        v0 << 0.02, -0.5, 0.3, 0.1, -0.04, 0.07, 0.01;
        const Model::Vector q0 = m.initial_state();
        // Along q(t) = q0 + (t - tc) v0 the penetration changes at the reported rate.
        for (double tc : {0.011, 0.0165, 0.027, 0.05, 0.071}) {
            INFO("t = " << tc);
            auto delta = [&](double t) { return m.nonlinear(m.at_time(t), q0 + (t - tc) * v0, v0).delta; };
            const double h = 1e-7;
            const double fd = (delta(tc + h) - delta(tc - h)) / (2 * h);
            CHECK(m.nonlinear(m.at_time(tc), q0, v0).delta_dot == Approx(fd).epsilon(1e-6).margin(1e-9));
            // d force / dq with v following q (dv/dq = vf I, as inside a Newmark step) is g w^T.
            const double vf = 1e5;
            const auto c = m.at_time(tc);
            const auto nl = m.nonlinear(c, q0, v0);
            REQUIRE(nl.contact.in_contact);
            const Model::Matrix analytic = c.g * m.tangent_row(c, nl, vf).transpose();
            for (int j = 0; j < 7; ++j) {
                const double eps = 1e-12;
                Model::Vector e = Model::Vector::Zero();
                e[j] = eps;
                const Model::Vector fd_col = (m.nonlinear(c, q0 + e, v0 + vf * e).force -
                                              m.nonlinear(c, q0 - e, v0 - vf * e).force) / (2 * eps);
                CHECK((fd_col - analytic.col(j)).norm() <= 1e-5 * analytic.norm());
            }
        }
    }
}
