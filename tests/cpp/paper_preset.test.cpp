// SPDX-License-Identifier: BSD-3-Clause
// The paper's 7-DOF model as the preset presets::paper (model/presets/paper.hpp) against closed forms:
// the contact law, the network's Table 2 entries, static and quasi-static equilibrium (force balance
// of the follower chain, with the pressure angle of paper eqs 2-4 written out here), gravity, the
// modes (the values docs/model.md lists, computed independently), dynamics limits (y4 follows h, the
// rigid limit omega^2 h'', contact loss at high speed), the parameter card, the paper backlash's side
// rule, and the Newton tangent and penetration rate against finite differences.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "camfollower/contact/hertz.hpp"
#include "camfollower/contact/paper_backlash.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/mechanism_modes.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/model/presets/paper_parameters.hpp"
#include "run.hpp"

using namespace camfollower;
using Model = Mechanism<presets::paper_dofs>;
using Vector = Model::Vector;
using Matrix = Model::Matrix;

namespace {

// The preset's DOFs, in the paper's order (named in a namespace: y1 is also <cmath>'s Bessel function).
namespace dof {
enum : int { y1 = 0, y2 = 1, y3 = 2, y4 = 3, x1 = 4, x2 = 5, x3 = 6 };
}

// Table 1-2 values, written again: bearing and return spring stiffness, spring preload deflection,
// cam geometry (r_b + r_r = 38 mm, offset 10 mm).
constexpr double K_vs = 2.6e8, K_rs = 1.4e4, delta_rs = 0.013;
constexpr double preload_force = K_rs * delta_rs;  // 182 N
constexpr double rp = 0.038, offset = 0.010;
const double s0 = std::sqrt(rp * rp - offset * offset);  // paper eq 2

// Pressure angle at cam angle theta (paper eqs 3-4): alpha = atan((h' - e) / (s0 + h)).
double pressure_angle(double theta) {
    const FollowerMotion m = MotionProgram::paper_default().evaluate(theta);
    return std::atan2(m.dh - offset, s0 + m.h);
}

// d delta / dq of the cam contact: normal n = (-sin a, cos a) from the cam (x1, y1) to the roller
// (x2, y2); the roller's axial coordinate carries the lift, with the lever cos a.
Vector contact_gradient(double alpha) {
    Vector g = Vector::Zero();
    g[dof::x1] = -std::sin(alpha), g[dof::y1] = std::cos(alpha);
    g[dof::x2] = std::sin(alpha), g[dof::y2] = -std::cos(alpha);
    return g;
}

// The return spring's preload P (its force on y4 is -(P + K_rs y4)), as the preset calibrated it.
double spring_preload(const Model& m) {
    for (const SpringSpec& s : m.description().structure.springs())
        if (s.name == "K_rs") return s.preload;
    FAIL("the preset has no spring K_rs");
    return 0.0;
}

// Largest |f(q0 + e_j eps, v0 + vf e_j eps) - ...| / 2 eps - (cq df/dq + cv df/dv) e_j over the DOFs
// j, relative to the tangent's norm: the rank-one tangent against central differences of force().
double tangent_error(const Model& m, double t, const Vector& q0, const Vector& v0) {
    auto w = m.workspace();
    m.prepare(t, w);
    const double vf = 1e5;
    Vector f, fp, fm;
    m.force(w, q0, v0, f);
    REQUIRE(w.contact(0).last.in_contact);
    LowRank<Vector> uv(Model::Vector::RowsAtCompileTime, m.max_rank());
    m.tangent(w, q0, v0, 1.0, vf, uv);
    Matrix analytic = Matrix::Zero();
    for (int k = 0; k < uv.rank; ++k) analytic += uv.U.col(k) * uv.V.col(k).transpose();
    double worst = 0.0;
    for (int j = 0; j < 7; ++j) {
        const double eps = 1e-12;
        Vector e = Vector::Zero();
        e[j] = eps;
        m.force(w, q0 + e, v0 + vf * e, fp);
        m.force(w, q0 - e, v0 - vf * e, fm);
        worst = std::max(worst, ((fp - fm) / (2 * eps) - analytic.col(j)).norm());
    }
    // (a law separating faster than it can pull has no tangent: then the differences must vanish too)
    return analytic.norm() > 0.0 ? worst / analytic.norm() : worst;
}

// The penetration along q(t) = q0 + (t - tc) v0 at time t.
double penetration_along(const Model& m, double t, double tc, const Vector& q0, const Vector& v0) {
    auto w = m.workspace();
    m.prepare(t, w);
    return ContactPair::penetration(w.contact(0).terms, Vector(q0 + (t - tc) * v0));
}

}  // namespace

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

TEST_CASE("network assembly: the paper's DOFs, symmetric, Table 2 entries, grounded springs on the diagonal only") {
    const Model m = presets::paper();
    CHECK(m.dof_names() == std::vector<std::string>{"y1", "y2", "y3", "y4", "x1", "x2", "x3"});
    const Matrix& K = m.stiffness();
    CHECK((K - K.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(K(dof::y1, dof::y1) == 2.6e8);
    CHECK(K(dof::y2, dof::y3) == -1.7e8);
    CHECK(K(dof::y4, dof::y4) == 2.5e8 + 1.4e4);
    CHECK(K(dof::x3, dof::x3) == 2.5e8 + 2.5e8);
    CHECK(K(dof::y1, dof::y2) == 0.0);  // coupled by the contact only
    CHECK(m.damping()(dof::y3, dof::y4) == -0.08);
    CHECK(m.damping()(dof::y1, dof::y1) == 750.0);
    CHECK(m.mass()(dof::y2, dof::y2) == 0.07);
    CHECK(m.mass()(dof::x2, dof::x2) == 0.07);
    CHECK(m.mass()(dof::y4, dof::y4) == 1.36);
    // Rigid translation of the follower chain in y stretches only the ground springs.
    Vector rigid = Vector::Zero();
    rigid[dof::y2] = rigid[dof::y3] = rigid[dof::y4] = 1.0;
    CHECK((K * rigid)[dof::y4] == 1.4e4);
    CHECK((K * rigid)[dof::y2] == 0.0);
}

TEST_CASE("static equilibrium on the dwell: the axial contact force is the spring preload") {
    const Model m = presets::paper();
    const Vector q = m.initial_displacement();
    const double F = m.static_contact_force(0.0, q, 0);
    const double alpha = std::atan(-offset / s0);  // -15.26 deg on the dwell
    CHECK(pressure_angle(0.0) == Approx(alpha).epsilon(1e-15));
    CHECK(F * std::cos(alpha) == Approx(preload_force).epsilon(1e-9));
    // The normal force is larger than its axial part.
    CHECK(F == Approx(preload_force / std::cos(std::atan(offset / s0))).epsilon(1e-9));
    // The preload is calibrated: the spring force at this equilibrium is K_rs delta_rs.
    CHECK(spring_preload(m) + K_rs * q[dof::y4] == Approx(preload_force).epsilon(1e-12));
    // Every DOF balanced: K q + F g - p = 0.
    const Vector r = m.stiffness() * q + F * contact_gradient(alpha) - m.constant_load();
    CHECK(r.cwiseAbs().maxCoeff() < 1e-9 * preload_force);
    // The bearing carries the axial load: y1 = -182 N / K_vs.
    CHECK(q[dof::y1] == Approx(-preload_force / K_vs).epsilon(1e-9));
}

TEST_CASE("quasi-static equilibrium converges at every cam angle, axial force = spring force") {
    const Model m = presets::paper();
    const double P = spring_preload(m);
    const MotionProgram program = MotionProgram::paper_default();
    for (int deg = 0; deg < 360; deg += 5) {
        const double theta = degrees_to_radians(deg);
        INFO("theta = " << deg << " deg");
        const Vector q = m.static_equilibrium(theta);
        const double F = m.static_contact_force(theta, q, 0);
        // The follower chain is in series: the contact's axial part carries the return spring.
        CHECK(F * std::cos(pressure_angle(theta)) == Approx(P + K_rs * q[dof::y4]).epsilon(1e-9));
        CHECK(q[dof::y4] == Approx(program.evaluate(theta).h).margin(20e-6));
    }
}

TEST_CASE("gravity adds the follower weight to the axial contact force") {
    CamFollowerParameters p;
    p.gravity = 9.81;
    const Model m = presets::paper(p);
    const double F = m.static_contact_force(0.0, m.initial_displacement(), 0);
    CHECK(F * std::cos(pressure_angle(0.0)) == Approx(182.0 + 9.81 * (0.07 + 0.34 + 1.36)).epsilon(1e-9));
}

TEST_CASE("modal analysis: contact-free camshaft bearing mode and the specified topology's modes") {
    const Model m = presets::paper();
    // The same mechanism without its cam contact.
    MechanismBuilder without_contact = m.description();
    without_contact.contacts.clear();
    const MechanismModes free = lowest_modes(Model(without_contact), 0.0);
    REQUIRE(free.frequencies_hz.size() == 7);
    // Without contact the camshaft is two decoupled oscillators sqrt(K_vs / m_c) = 2447 Hz.
    int at_2447 = 0;
    for (int k = 0; k < 7; ++k) at_2447 += std::abs(free.frequencies_hz[k] - 2447.0) < 1e-6;
    CHECK(at_2447 == 2);
    // The follower on its return spring alone: sqrt(K_rs / (M_fc + M_f + M_eq)) / 2 pi, nearly.
    CHECK(free.frequencies_hz[0] == Approx(std::sqrt(1.4e4 / 1.77) / (2 * pi)).epsilon(1e-3));
    // With contact on the dwell: the values docs/model.md lists for this topology.
    const MechanismModes with = lowest_modes(m, 0.0);
    REQUIRE(with.frequencies_hz.size() == 7);
    const double expected[7] = {868, 2447, 2747, 3893, 5319, 10403, 12013};
    for (int k = 0; k < 7; ++k) CHECK(with.frequencies_hz[k] == Approx(expected[k]).margin(0.6));
    // Mass-normalized shapes.
    const Eigen::MatrixXd I = with.shapes.transpose() * Eigen::MatrixXd(m.mass()) * with.shapes;
    CHECK((I - Eigen::MatrixXd::Identity(7, 7)).cwiseAbs().maxCoeff() < 1e-10);
    // The contact stiffness projected on y varies with the pressure angle: modes shift on the flanks.
    CHECK(lowest_modes(m, degrees_to_radians(290.0)).frequencies_hz[0] != Approx(with.frequencies_hz[0]).epsilon(1e-3));
}

TEST_CASE("Sherman-Morrison and dense LU give the same trajectory") {
    const Model m = presets::paper();
    SolverSettings s;
    REQUIRE(s.linear_solver == LinearSolver::sherman_morrison);
    const auto a = run(m, s, 0.3 * m.period(), 10);
    s.linear_solver = LinearSolver::dense_lu;
    const auto b = run(m, s, 0.3 * m.period(), 10);
    REQUIRE(a.rows == b.rows);
    double dq = 0, df = 0;
    for (std::size_t i = 0; i < a.q.size(); ++i) dq = std::max(dq, std::abs(a.q[i] - b.q[i]));
    for (std::size_t i = 0; i < a.rows; ++i)
        df = std::max(df, std::abs(a.channel("cam.force")[i] - b.channel("cam.force")[i]));
    CHECK(dq < 1e-14);
    CHECK(df < 1e-6);
}

TEST_CASE("one revolution: y4 follows h, the dwell starts at rest, Newton needs about two iterations") {
    const Model m = presets::paper();
    const MotionProgram program = MotionProgram::paper_default();
    SolverSettings s;
    const auto r = run(m, s, m.period(), 1);
    CHECK(r.stats.halvings == 0);
    CHECK(r.stats.mean_iterations() < 2.5);
    CHECK(Model::contact_loss(r.final_state.workspace, 0, r.final_state.t).empty());
    double worst = 0;
    for (std::size_t i = 0; i < r.rows; ++i) {
        const double theta = r.channel("theta")[i];
        worst = std::max(worst, std::abs(r.q[7 * i + dof::y4] - program.evaluate(theta).h));
        if (theta < degrees_to_radians(29.0)) CHECK(std::abs(r.a[7 * i + dof::y4]) < 1e-6);
    }
    CHECK(worst < 20e-6);  // static deflection (3.7 um) plus vibration
}

TEST_CASE("rigid limit: with stiffnesses x1e3 the follower acceleration approaches omega^2 h''") {
    const MotionProgram program = MotionProgram::paper_default();
    auto worst_error = [&](double scale, double dt) {
        CamFollowerParameters p;
        for (const char* name :
             {"bearing_stiffness_vertical", "bearing_stiffness_horizontal", "contact_stiffness",
              "roller_pin_stiffness_vertical", "roller_pin_stiffness_horizontal", "guide_stiffness", "rod_stiffness"})
            p.set(name, p.get(name) * scale);
        const Model m = presets::paper(p);
        SolverSettings s;
        s.time_step = dt;
        const auto r = run(m, s, m.period(), 10);
        double worst = 0;
        for (std::size_t i = 0; i < r.rows; ++i) {
            const double theory = m.omega() * m.omega() * program.evaluate(r.channel("theta")[i]).d2h;
            worst = std::max(worst, std::abs(r.a[7 * i + dof::y4] - theory));
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
    const Model m = presets::paper(p);
    SolverSettings s;
    s.time_step = 1e-6;
    const auto r = run(m, s, m.period(), 1);
    const auto losses = Model::contact_loss(r.final_state.workspace, 0, r.final_state.t);
    REQUIRE_FALSE(losses.empty());
    double lost = 0;
    for (const auto& [a, b] : losses) {
        CHECK(b > a);
        lost += b - a;
    }
    CHECK(lost > 0.0);
    for (std::size_t i = 0; i < r.rows; ++i)
        if (r.channel("cam.in_contact")[i] == 0.0) CHECK(r.channel("cam.force")[i] == 0.0);
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
    CHECK_THROWS_WITH(p.set("stiffnes", 1.0),
                      Catch::Contains("unknown parameter 'stiffnes'") && Catch::Contains("rod_stiffness"));
    CamFollowerParameters bad;
    bad.follower_mass = 0.0;
    CHECK_THROWS_WITH(presets::paper(bad), Catch::Contains("follower_mass"));
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
    presets::PaperOptions negative;
    negative.paper_backlash = -1e-6;
    CHECK_THROWS_WITH(negative.validate(), Catch::Contains("paper_backlash must be finite and >= 0"));
    // A backlash that would push the offset e +- b past the pitch circle is refused.
    presets::PaperOptions too_wide;
    too_wide.paper_backlash = 0.03;
    CHECK_THROWS_WITH(presets::paper({}, MotionProgram::paper_default(), too_wide),
                      Catch::Contains("must stay below base_radius + roller_radius"));
}

TEST_CASE("contact damping: exact (non-symmetric) tangent keeps Newton fast, both linear solvers agree") {
    CamFollowerParameters p;
    p.contact_damping = ContactDampingModel::hunt_crossley;
    p.restitution = 0.2;
    p.reference_speed = 0.01;  // chi = 3 (1 - 0.2) / (2 * 0.01) = 120 s/m
    p.contact_exponent = 1.5;
    p.contact_stiffness = 1e11;  // N/m^1.5: tangent 1.5 F / delta ~ 1.9e8 N/m at the 1.5 um static penetration
    const Model m = presets::paper(p);
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
    const Model undamped = presets::paper(p);
    const auto c = run(undamped, SolverSettings{}, 0.6 * m.period(), 10);
    auto dwell_vibration = [&](const Histories<Model>& r) {
        double worst = 0;
        for (std::size_t i = 0; i < r.rows; ++i)
            if (r.channel("theta")[i] > degrees_to_radians(185.0) && r.channel("theta")[i] < degrees_to_radians(209.0))
                worst = std::max(worst, std::abs(r.a[7 * i + dof::y4]));  // theory: 0 on the dwell
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
    // Healthy; an eccentric cam (1 mm at phase 0.3 rad, the exact geometry); the paper backlash
    // (1 mm, its side switch ramped over 40 deg, so the offset's rate enters).
    presets::PaperOptions eccentric, backlash;
    eccentric.eccentricity.radius = 1e-3;
    eccentric.eccentricity.phase = 0.3;
    backlash.paper_backlash = 1e-3;
    backlash.paper_backlash_switch_width = degrees_to_radians(40.0);
    const std::pair<const char*, presets::PaperOptions> cases[] = {
        {"healthy", presets::PaperOptions{}}, {"eccentric", eccentric}, {"paper backlash", backlash}};
    for (const auto& [name, options] : cases) {
        const Model m = presets::paper(p, MotionProgram::paper_default(), options);
        INFO(name);
        Vector v0;
        v0 << 0.02, -0.5, 0.3, 0.1, -0.04, 0.07, 0.01;
        const Vector q0 = m.initial_displacement();
        // Along q(t) = q0 + (t - tc) v0 the penetration changes at the reported rate.
        for (double tc : {0.011, 0.0165, 0.027, 0.05, 0.071}) {
            INFO("t = " << tc);
            const double h = 1e-7;
            const double fd =
                (penetration_along(m, tc + h, tc, q0, v0) - penetration_along(m, tc - h, tc, q0, v0)) / (2 * h);
            auto w = m.workspace();
            m.prepare(tc, w);
            CHECK(ContactPair::penetration_rate(w.contact(0).terms, q0, v0) == Approx(fd).epsilon(1e-6).margin(1e-9));
            // d force / dq with v following q (dv/dq = vf I, as inside a Newmark step).
            CHECK(tangent_error(m, tc, q0, v0) <= 1e-5);
        }
    }
}
