// SPDX-License-Identifier: BSD-3-Clause
// The mechanism builder: assembly, bad input; the paper preset's contact tangent and its imposed
// backlash against the closed forms of paper eqs 2-4 and 12-18 (the preset itself: paper_preset.test.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/mechanism_modes.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "run.hpp"

using namespace camfollower;

namespace {

// The paper preset's DOFs (y1..y4, x1..x3), its cam (r_b + r_r = 38 mm, offset 10 mm) and guide
// stiffness K_rb, written again from Tables 1-2.
constexpr int paper_y1 = 0, paper_y2 = 1, paper_x1 = 4, paper_x2 = 5, paper_x3 = 6;
constexpr double paper_rp = 0.038, paper_offset = 0.010, paper_guide_stiffness = 2.5e8;

// Pressure angle of a translating roller at offset e (paper eqs 2-4): atan((h' - e) / (s0 + h)),
// s0 = sqrt((r_b + r_r)^2 - e^2).
double roller_pressure_angle(const FollowerMotion& m, double e) {
    return std::atan2(m.dh - e, std::sqrt(paper_rp * paper_rp - e * e) + m.h);
}

// The paper's side rule for its backlash (its eqs 12-18), written again for the paper program
// (rise 30-180 deg, return 210-360 deg): the rod rides at e + b on the rise and at e - b on the
// return, each dwell keeps the side of the segment before it, and the switch ramps over `width` from
// the start of the segment that changes side along the smoothstep 3 x^2 - 2 x^3 (width 0: a jump).
double paper_side(double theta, double width) {
    const double rise = degrees_to_radians(30.0), fall = degrees_to_radians(210.0);
    const double t = theta - two_pi * std::floor(theta / two_pi);
    const bool riding_up = t >= rise && t < fall;  // since the rise started
    const double since = riding_up ? t - rise : t >= fall ? t - fall : t + two_pi - fall;
    const double to = riding_up ? 1.0 : -1.0, from = -to;
    if (since >= width) return to;
    const double x = since / width;
    return from + (to - from) * x * x * (3.0 - 2.0 * x);
}

}  // namespace

TEST_CASE("paper preset: tangent stiffness is K + K_h g g^T with g from the closed-form pressure angle; its modes") {
    const Mechanism<7> preset = presets::paper();
    const MotionProgram program = MotionProgram::paper_default();
    const double K_h = 1.9e8;  // the paper's linear contact law (N/m): its stiffness wherever it is closed
    for (double theta_deg : {0.0, 100.0, 290.0}) {
        INFO("theta = " << theta_deg << " deg");
        const double theta = degrees_to_radians(theta_deg);
        const Mechanism<7>::Vector q = preset.static_equilibrium(theta);
        REQUIRE(preset.static_contact_force(theta, q, 0) > 0.0);
        // d delta / dq: the normal (-sin a, cos a) from the cam (x1, y1) to the roller (x2, y2).
        const double alpha = roller_pressure_angle(program.evaluate(theta), paper_offset);
        Mechanism<7>::Vector g = Mechanism<7>::Vector::Zero();
        g[paper_x1] = -std::sin(alpha), g[paper_y1] = std::cos(alpha);
        g[paper_x2] = std::sin(alpha), g[paper_y2] = -std::cos(alpha);
        const Mechanism<7>::Matrix expected = preset.stiffness() + K_h * g * g.transpose();
        CHECK((preset.tangent_stiffness(theta, q) - expected).cwiseAbs().maxCoeff() <=
              1e-12 * expected.cwiseAbs().maxCoeff());
        // The natural frequencies are that pencil's (K_t phi = omega^2 M phi).
        const Eigen::GeneralizedSelfAdjointEigenSolver<Mechanism<7>::Matrix> eig(expected, preset.mass());
        const Eigen::VectorXd f = eig.eigenvalues().cwiseSqrt() / two_pi;
        const Eigen::VectorXd modes = lowest_modes(preset, theta).frequencies_hz;
        REQUIRE(modes.size() == 7);
        CHECK((modes - f).cwiseAbs().maxCoeff() <= 1e-12 * f.maxCoeff());
    }
}

// The paper's imposed backlash (its eqs 12-18) as the preset's named option: the contact geometry at
// the offset e' = e + b s(theta), s from the side rule above, and the guide spring K_rb anchored on
// the displaced rod (a load K_rb b s on x3). (The offset's rate in the terms' time derivatives:
// paper_preset.test.cpp, against finite differences.)
TEST_CASE(
    "paper preset's imposed backlash: pressure angle at e +- b by the paper's side rule, the rod displaced by b") {
    const MotionProgram program = MotionProgram::paper_default();
    const double b = 1e-4;
    for (double width_deg : {0.0, 10.0, 30.0}) {
        INFO("switch width " << width_deg << " deg");
        const double width = degrees_to_radians(width_deg);
        presets::PaperOptions options;
        options.paper_backlash = b;
        options.paper_backlash_switch_width = width;
        const Mechanism<7> preset = presets::paper({}, program, options);
        double worst_alpha = 0.0, worst_load = 0.0, worst_x3 = 0.0, x3_max = 0.0;
        for (int k = 0; k < 720; ++k) {
            const double theta = (k + 0.3) * degrees_to_radians(0.5);
            const double side = paper_side(theta, width), e = paper_offset + b * side;
            auto w = preset.workspace();
            preset.prepare(theta / preset.omega(), w);
            const ContactTerms& c = w.contact(0).terms;
            const double alpha = roller_pressure_angle(program.evaluate(theta), e);
            worst_alpha = std::max(worst_alpha, std::abs(std::atan2(c.sin_alpha, c.cos_alpha) - alpha));
            double load = 0.0;  // the time-only load on the rod's lateral DOF
            for (int i = 0; i < c.count; ++i)
                if (c.dof[std::size_t(i)] == paper_x3) load += c.p[std::size_t(i)];
            worst_load = std::max(worst_load, std::abs(load - paper_guide_stiffness * b * side));
            if (k % 20 != 0) continue;
            // At rest the lateral chain balances: K_hc (x2 - x3) + F sin a = 0 on the roller and
            // K_hc (x3 - x2) + K_rb x3 = K_rb b s on the rod, so x3 = b s - F sin a / K_rb.
            const Mechanism<7>::Vector q = preset.static_equilibrium(theta);
            const double F = preset.static_contact_force(theta, q, 0);
            worst_x3 =
                std::max(worst_x3, std::abs(q[paper_x3] - (b * side - F * std::sin(alpha) / paper_guide_stiffness)));
            x3_max = std::max(x3_max, std::abs(q[paper_x3]));
        }
        INFO("worst: pressure angle " << worst_alpha << " rad, guide load " << worst_load << " N, x3 " << worst_x3
                                      << " m");
        CHECK(worst_alpha < 1e-13);
        CHECK(worst_load <= 1e-12 * paper_guide_stiffness * b);
        CHECK(worst_x3 < 1e-13);
        CHECK(x3_max > 0.5 * b);  // the side switch moves the rod
    }
    presets::PaperOptions both;
    both.paper_backlash = 1e-4;
    both.guide_clearance = 1e-4;
    CHECK_THROWS_WITH(presets::paper({}, MotionProgram::paper_default(), both),
                      Catch::Contains("two models of the same guide clearance"));
}

namespace {

// A small mechanism around one follower type: camshaft bearing (cam_x, cam_y), the follower coordinate
// on its return spring, and for translating followers a lateral DOF in a guide. Damped Hertz contact
// (exponent 1.5, chi > 0) so that every term of the tangent is exercised.
template <class F>
MechanismBuilder small_mechanism(const F& follower, const MotionProgram& program, bool lateral) {
    MechanismBuilder b;
    b.add_dof("cx", 1.0, {1, 0, 0});
    b.add_dof("cy", 1.0, {0, 1, 0});
    b.add_dof("s", lateral ? 0.2 : 2e-4);  // kg, or kg m^2 for an arm
    b.add_spring("bearing_x", "cx", "ground", 1e8, 50.0);
    b.add_spring("bearing_y", "cy", "ground", 1e8, 50.0);
    b.add_spring("return", "s", "ground", lateral ? 2e4 : 20.0, 0.0, lateral ? 300.0 : 3.0);
    ContactPairSpec c{"cam",    program,           follower, HertzContact{1e11, 1.5, 0.5}, 0.3, "cx", "cy", "s",
                      "ground", CamEccentricity{}, "ground"};
    if (lateral) {
        b.add_dof("lat", 0.2, {1, 0, 0});
        b.add_spring("guide", "lat", "ground", 1e8);
        c.lateral = "lat";
    }
    b.add_contact(c);
    return b;
}

// cq df/dq + cv df/dv (v following q as dv = vf dq) against central differences of force().
template <class M>
double tangent_error(const M& m, double t, const typename M::Vector& q0, const typename M::Vector& v0) {
    using Vector = typename M::Vector;
    auto w = m.workspace();
    m.prepare(t, w);
    const double vf = 1e5;
    Vector f(m.size()), fp(m.size()), fm(m.size());
    m.force(w, q0, v0, f);
    LowRank<Vector> uv(m.size(), m.max_rank());
    m.tangent(w, q0, v0, 1.0, vf, uv);
    REQUIRE(uv.rank == 1);
    const Eigen::MatrixXd analytic = uv.U.leftCols(1) * uv.V.leftCols(1).transpose();
    double worst = 0.0;
    for (int j = 0; j < m.size(); ++j) {
        Vector e = Vector::Zero(m.size());
        e[j] = 1e-12;
        m.force(w, q0 + e, v0 + vf * e, fp);
        m.force(w, q0 - e, v0 - vf * e, fm);
        worst = std::max(worst, ((fp - fm) / 2e-12 - analytic.col(j)).norm());
    }
    return worst / analytic.norm();
}

template <class M>
double penetration_rate_error(const M& m, double tc, const typename M::Vector& q0, const typename M::Vector& v0) {
    auto delta = [&](double t) {
        auto w = m.workspace();
        m.prepare(t, w);
        return ContactPair::penetration(w.contact(0).terms, typename M::Vector(q0 + (t - tc) * v0));
    };
    auto w = m.workspace();
    m.prepare(tc, w);
    const double h = 1e-7, fd = (delta(tc + h) - delta(tc - h)) / (2 * h);
    return std::abs(ContactPair::penetration_rate(w.contact(0).terms, q0, v0) - fd) / std::max(std::abs(fd), 1e-3);
}

}  // namespace

TEST_CASE("every follower type: contact tangent and penetration rate against finite differences") {
    const MotionProgram lift = MotionProgram::paper_default(0.010), swing = MotionProgram::paper_default(0.2618);
    const Eigen::Vector2d pivot(0.06, 0.05);
    const MechanismBuilder cases[] = {
        small_mechanism(TranslatingRoller(0.03, 0.008, 0.01), lift, true),
        small_mechanism(TranslatingFlat(0.03, degrees_to_radians(5.0), 0.002), lift, true),
        small_mechanism(OscillatingRoller(0.03, 0.008, pivot, 0.06), swing, false),
        small_mechanism(OscillatingFlat(0.03, pivot, 0.0), swing, false),
    };
    for (const MechanismBuilder& b : cases) {
        const Mechanism<> m(b);
        INFO("follower " << follower_type_name(b.contacts[0].follower));
        Mechanism<>::Vector v0 = Mechanism<>::Vector::Zero(m.size());
        for (int k = 0; k < m.size(); ++k) v0[k] = 0.01 * (k + 1) * (k % 2 ? -1 : 1);
        for (double theta_deg : {10.0, 80.0, 150.0, 250.0, 320.0}) {
            const double t = degrees_to_radians(theta_deg) / m.omega();
            const Mechanism<>::Vector q0 = m.static_equilibrium(degrees_to_radians(theta_deg));
            INFO("theta = " << theta_deg << " deg");
            CHECK(tangent_error(m, t, q0, v0) < 1e-5);
            CHECK(penetration_rate_error(m, t, q0, v0) < 1e-6);
        }
    }
}

TEST_CASE("a grooved cam: the outer flank's penetration, tangent, statics and events") {
    const MotionProgram lift = MotionProgram::paper_default(0.010), swing = MotionProgram::paper_default(0.2618);
    const double clearance = 50e-6;
    struct Case {
        MechanismBuilder b;
        double outward;  // a follower displacement that puts the roller 40 um into the outer flank at most
    };
    Case cases[] = {
        {small_mechanism(TranslatingRoller(0.03, 0.008, 0.01), lift, true), 1.5 * clearance},
        {small_mechanism(OscillatingRoller(0.03, 0.008, {0.06, 0.05}, 0.06), swing, false), 1.5 * clearance / 0.06}};
    for (Case& k : cases) {
        k.b.contacts[0].groove = Groove{clearance, HertzContact{3e11, 1.5, 0.4}};
        const Mechanism<> m(k.b);
        INFO("follower " << follower_type_name(k.b.contacts[0].follower));
        const std::vector<std::string> events = m.event_names(), channels = m.channel_names();
        CHECK(events == std::vector<std::string>{"cam.contact", "cam.outer_contact"});
        CHECK(std::count(channels.begin(), channels.end(), "cam.outer_force") == 1);
        const int s = m.dof_index("s");
        Mechanism<>::Vector v0 = Mechanism<>::Vector::Zero(m.size());
        for (int j = 0; j < m.size(); ++j) v0[j] = 0.01 * (j + 1) * (j % 2 ? -1 : 1);
        for (double theta_deg : {10.0, 80.0, 150.0, 250.0}) {
            INFO("theta = " << theta_deg << " deg");
            const double t = degrees_to_radians(theta_deg) / m.omega();
            Mechanism<>::Vector q = m.static_equilibrium(degrees_to_radians(theta_deg));
            q[s] += k.outward;  // across the groove: off the inner flank, into the outer one
            auto w = m.workspace();
            m.prepare(t, w);
            Mechanism<>::Vector f(m.size());
            m.force(w, q, v0, f);
            std::vector<double> g(events.size());
            m.event_values(w, q, v0, g.data());
            // Both flanks are parallel curves 2 r + c apart: delta_outer = -delta_inner - c.
            const double inner = ContactPair::penetration(w.contact(0).terms, q);
            CHECK(g[0] == inner);
            CHECK(g[0] < 0.0);
            CHECK(g[1] == Approx(-inner - clearance).epsilon(1e-12));
            CHECK(g[1] > 0.0);
            CHECK(tangent_error(m, t, q, v0) < 1e-5);
        }
    }
    // At rest with a load pushing the follower away from the cam beyond its spring's preload, the outer
    // flank carries it: the net contact force is negative, and balances spring and load along the lever.
    MechanismBuilder b = small_mechanism(TranslatingRoller(0.03, 0.008, 0.0), lift, true);
    b.contacts[0].groove = Groove{clearance, std::nullopt};
    b.add_load("s", 500.0);
    const Mechanism<> m(b);
    const double theta = degrees_to_radians(100.0);
    const Mechanism<>::Vector q = m.static_equilibrium(theta);
    const double F = m.static_contact_force(theta, q, 0);
    const FollowerMotion motion = lift.evaluate(theta + b.contacts[0].phase);  // the cam's angle
    const double lever = std::cos(std::atan2(motion.dh, 0.038 + motion.h));    // zero offset: cos(alpha)
    CHECK(F < 0.0);
    CHECK(-F * lever == Approx(500.0 - (300.0 + 2e4 * q[m.dof_index("s")])).epsilon(1e-8));
}

TEST_CASE("a grooved cam refuses what cannot run in a groove and names the contact and the value") {
    const auto with_groove = [](Follower f, double c) {
        MechanismBuilder b;
        b.add_dof("s", 0.2);
        b.add_spring("k", "s", "ground", 1e4, 0.0, 100.0);
        const bool arm = !is_translating(f);
        ContactPairSpec spec{"cam",    MotionProgram::paper_default(arm ? 0.2 : 0.01),
                             f,        HertzContact{},
                             0.0,      "ground",
                             "ground", "s",
                             "ground", CamEccentricity{},
                             "ground"};
        spec.groove = Groove{c, std::nullopt};
        b.add_contact(spec);
        return Mechanism<>(b);
    };
    CHECK_THROWS_WITH(with_groove(TranslatingFlat(0.03, 0.0, 0.0), 50e-6),
                      Catch::Contains("contact 'cam': a groove holds a roller; translating_flat has none"));
    CHECK_THROWS_WITH(with_groove(OscillatingFlat(0.03, {0.06, 0.05}, 0.0), 50e-6),
                      Catch::Contains("oscillating_flat has none"));
    CHECK_THROWS_WITH(with_groove(TranslatingRoller(0.03, 0.008, 0.0), 0.0),
                      Catch::Contains("contact 'cam' groove clearance must be finite and > 0"));
    CHECK_THROWS_WITH(with_groove(TranslatingRoller(0.03, 0.008, 0.0), NAN), Catch::Contains("groove clearance"));
    CHECK_THROWS_WITH(with_groove(TranslatingRoller(0.03, 0.008, 0.0), 0.05),
                      Catch::Contains("groove clearance 0.05 m must be below the roller radius 0.008 m") &&
                          Catch::Contains("did you mean mm?"));
    CHECK_NOTHROW(with_groove(OscillatingRoller(0.03, 0.008, {0.06, 0.05}, 0.06), 50e-6));
    // The outer flank folds where the pitch curve is concave tighter than roller + clearance.
    const MotionProgram program = MotionProgram::paper_default(0.01);
    const auto concave = [](double) { return -1.0 / 0.0085; };  // radius 8.5 mm everywhere
    CHECK_THROWS_WITH(check_outer_flank(program, concave, 0.0081 + 0.0005, "contact 'cam'"),
                      Catch::Contains("contact 'cam': the groove's outer flank undercuts") &&
                          Catch::Contains("concave with radius 0.0085 m"));
    CHECK_NOTHROW(check_outer_flank(program, concave, 0.0080, "contact 'cam'"));
}

TEST_CASE("two cams on one shaft: rank-two Woodbury update equals the dense LU, contacts tracked apart") {
    MechanismBuilder b;
    b.add_dof("shaft", 1.1, {0, 1, 0});
    b.add_spring("bearing", "shaft", "ground", 2.6e8, 750.0);
    for (const char* name : {"a", "b"}) {
        const std::string f = std::string("follower_") + name;
        b.add_dof(f, 0.4, {0, 1, 0});
        b.add_spring("spring_" + std::string(name), f, "ground", 1.4e4, 0.0, 180.0);
        b.add_contact({std::string("cam_") + name, MotionProgram::paper_default(), TranslatingRoller(0.03, 0.008, 0.01),
                       HertzContact{1.9e8, 1.0, 0.0}, name[0] == 'a' ? 0.0 : pi, "ground", "shaft", f, "ground",
                       CamEccentricity{}, "ground"});
    }
    const Mechanism<> m(b);
    REQUIRE(m.max_rank() == 2);
    SolverSettings s;
    const auto low_rank = run(m, s, m.period(), 10);
    s.linear_solver = LinearSolver::dense_lu;
    const auto dense = run(m, s, m.period(), 10);
    double dq = 0, qmax = 0;
    for (std::size_t i = 0; i < low_rank.q.size(); ++i)
        dq = std::max(dq, std::abs(low_rank.q[i] - dense.q[i])), qmax = std::max(qmax, std::abs(low_rank.q[i]));
    CHECK(dq <= 1e-12 * qmax);
    CHECK(low_rank.stats.mean_iterations() < 2.5);
    // Each cam lifts its own follower, half a revolution apart.
    const std::size_t quarter = low_rank.rows / 4;
    CHECK(low_rank.channel("cam_a.cam_angle")[quarter] ==
          Approx(low_rank.channel("cam_b.cam_angle")[quarter] - pi).margin(1e-12));
    CHECK(low_rank.channel("cam_a.force")[0] > 0.0);
    CHECK(low_rank.channel("cam_b.force")[0] > 0.0);
}

TEST_CASE("bad descriptions: a clear error naming the element, and nothing half-built") {
    MechanismBuilder b;
    b.add_dof("y", 1.0);
    CHECK_THROWS_WITH(b.add_dof("y", 2.0), Catch::Contains("DOF 'y' is defined twice"));
    CHECK_THROWS_WITH(b.add_dof("z", 0.0), Catch::Contains("mass of DOF 'z'"));
    CHECK_THROWS_WITH(b.add_spring("k", "y", "y", 1.0), Catch::Contains("connects DOF 'y' to itself"));
    CHECK_THROWS_WITH(b.add_spring("k", "y", "ground", -1.0), Catch::Contains("stiffness of 'k'"));
    CHECK_THROWS_WITH(b.set_modal_damping({0.02, -0.1}), Catch::Contains("modal damping ratio [1]"));
    CHECK_THROWS_WITH(b.set_gravity({0, NAN, 0}), Catch::Contains("gravity"));
    b.add_spring("k", "y", "nowhere", 1.0);
    CHECK_THROWS_WITH(Mechanism<>(b), Catch::Contains("spring 'k' refers to DOF 'nowhere'"));
    MechanismBuilder c;
    c.add_dof("y", 1.0);
    c.add_spring("k", "y", "ground", 1e4, 0.0, 100.0);
    c.add_contact({"cam", MotionProgram::paper_default(), TranslatingRoller(0.03, 0.008, 0.0), HertzContact{}, 0.0,
                   "ground", "ground", "w", "ground", CamEccentricity{}, "ground"});
    CHECK_THROWS_WITH(Mechanism<>(c), Catch::Contains("contact 'cam' follower_dof refers to DOF 'w'"));
    // Mechanism<7>: the fixed size that is compiled anyway (camfollower::precompiled).
    CHECK_THROWS_WITH(Mechanism<7>(b), Catch::Contains("Mechanism<7> built from a description with 1 DOFs"));
    MechanismBuilder osc;
    osc.add_dof("arm", 1e-4);
    osc.add_spring("k", "arm", "ground", 10.0, 0.0, 1.0);
    osc.add_dof("x", 1.0);
    osc.add_spring("kx", "x", "ground", 1e6);
    osc.add_contact({"cam", MotionProgram::paper_default(0.2), OscillatingRoller(0.03, 0.008, {0.06, 0.05}, 0.06),
                     HertzContact{}, 0.0, "ground", "ground", "arm", "x", CamEccentricity{}, "ground"});
    CHECK_THROWS_WITH(Mechanism<>(osc), Catch::Contains("lateral is defined for translating followers only"));
}

TEST_CASE("each role of an element names a DOF of its own, each element a name of its own") {
    MechanismBuilder b;
    b.add_dof("f", 0.5);
    b.add_dof("g", 0.2);
    b.add_spring("spring", "f", "ground", 2e4, 0.0, 300.0);
    auto contact = [](const std::string& cam_x, const std::string& cam_y, const std::string& lateral,
                      const std::string& twist) {
        return ContactPairSpec{"cam",
                               MotionProgram::paper_default(),
                               TranslatingRoller(0.03, 0.008, 0.0),
                               HertzContact{},
                               0.0,
                               cam_x,
                               cam_y,
                               "f",
                               lateral,
                               CamEccentricity{},
                               twist};
    };
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "ground", "f", "ground")),
                      Catch::Contains("contact 'cam': lateral and follower_dof both name DOF 'f'"));
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "f", "ground", "ground")),
                      Catch::Contains("follower_dof and cam_y both name DOF 'f'"));
    CHECK_THROWS_WITH(b.add_contact(contact("g", "g", "ground", "ground")),
                      Catch::Contains("cam_y and cam_x both name DOF 'g'"));
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "ground", "g", "g")),
                      Catch::Contains("cam_twist and lateral both name DOF 'g'"));
    CHECK(b.contacts.empty());  // nothing half-added
    // The resolved pair checks indices too (a description that bypassed the builder).
    CHECK_THROWS_WITH(ContactPair(contact("ground", "ground", "ground", "ground"), -1, 0, 0, -1),
                      Catch::Contains("cam_y and cam_x") || Catch::Contains("follower_dof and cam_y"));
    ClearanceSpec guide{"guide", {{"g", 1.0}}, 1e-4, HertzContact{1e8, 1.0, 0.0}, 0.1, "g", 1e-3};
    CHECK_THROWS_WITH(b.add_clearance(guide), Catch::Contains("sliding_dof 'g' is also a DOF of the gap coordinate"));
    b.add_contact(contact("ground", "ground", "ground", "ground"));
    ClearanceSpec same_name{"cam", {{"g", 1.0}}, 1e-4, HertzContact{1e8, 1.0, 0.0}, 0.0, "", 1e-3};
    CHECK_THROWS_WITH(b.add_clearance(same_name),
                      Catch::Contains("clearance 'cam': the name is taken by contact 'cam'"));
    CHECK_THROWS_WITH(b.add_spring("cam", "g", "ground", 1.0),
                      Catch::Contains("element 'cam': the name is taken by contact"));
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "ground", "ground", "ground")),
                      Catch::Contains("contact 'cam': the name is taken by contact 'cam'"));
}

TEST_CASE("a model's size is bounded before it is assembled; a shaft mesh absurd for its section is refused") {
    MechanismBuilder b;
    ShaftSpec fine{"s", BeamSection::solid_circle(0.03, 210e9, 0.3, 7850.0), 0.05, 1e-6, {}, false, 0.0};
    CHECK_THROWS_WITH(b.add_shaft(fine), Catch::Contains("radius of gyration") && Catch::Contains("um written for mm"));
    ShaftSpec many{"s", BeamSection::solid_circle(0.03, 210e9, 0.3, 7850.0), 1.0, 1e-3, {}, false, 0.0};
    CHECK_THROWS_WITH(b.add_shaft(many), Catch::Contains("limit 500 per shaft"));
    for (const char* name : {"s", "t"})
        b.add_shaft({name, BeamSection::solid_circle(0.03, 210e9, 0.3, 7850.0), 0.5, 0.5 / 400, {}, false, 0.0});
    CHECK(b.structure.size() == 2 * 401 * 5);
    CHECK_THROWS_WITH(Mechanism<>(b), Catch::Contains("the mechanism has 4010 DOFs, more than the 3000"));
}

TEST_CASE("a pair's follower map and frame move the plain pair's penetration as they say", "[contact][conjugate]") {
    // s = offset + ratio q on the follower and lateral DOFs; the normal turned by frame_angle on the cam
    // centre's. Checked against the plain pair evaluated at the mapped coordinates: a second method.
    const MotionProgram program = MotionProgram::paper_default(0.010);
    ContactPairSpec plain{"plain",
                          program,
                          TranslatingRoller(0.04, 0.01, 0.004),
                          HertzContact{1e8, 1.0, 0.0},
                          0.3,
                          "cx",
                          "cy",
                          "f",
                          "lat",
                          CamEccentricity{},
                          "ground"};
    ContactPairSpec mapped = plain;
    mapped.name = "mapped";
    mapped.follower_ratio = -1.7, mapped.follower_offset = 0.0123, mapped.frame_angle = 2.1;
    const ContactPair a(plain, 0, 1, 2, 3), b(mapped, 0, 1, 2, 3);
    const Eigen::Vector4d q(3e-5, -2e-5, 0.004, 1e-5);  // cam x, cam y, follower, lateral
    const double c = std::cos(2.1), s = std::sin(2.1);
    for (double theta : {0.2, 1.1, 2.5, 4.0, 5.9}) {
        ContactTerms ta, tb;
        a.evaluate(theta, 50.0, ta);
        b.evaluate(theta, 50.0, tb);
        // The cam centre's ground displacement seen in the turned frame: R(-phi) d.
        const Eigen::Vector4d seen(c * q[0] + s * q[1], -s * q[0] + c * q[1], 0.0123 - 1.7 * q[2], -1.7 * q[3]);
        const double expected = ContactPair::penetration(ta, seen);
        CHECK(ContactPair::penetration(tb, q) == Approx(expected).margin(1e-15));
        // The rate likewise (velocities map as displacements, without the offset).
        const Eigen::Vector4d v(0.1, -0.2, 0.3, 0.05);
        const Eigen::Vector4d seen_v(c * v[0] + s * v[1], -s * v[0] + c * v[1], -1.7 * v[2], -1.7 * v[3]);
        CHECK(ContactPair::penetration_rate(tb, q, v) ==
              Approx(ContactPair::penetration_rate(ta, seen, seen_v)).margin(1e-12));
    }
}

TEST_CASE("conjugate cams: complement, the return pair's map and the pair's checks", "[contact][conjugate]") {
    const MotionProgram program = MotionProgram::paper_default(0.010);
    const MotionProgram back = program.complement(0.010);
    for (double theta = 0.0; theta < two_pi; theta += 0.05) {
        const FollowerMotion m = program.evaluate(theta), r = back.evaluate(theta);
        CHECK(m.h + r.h == Approx(0.010).margin(1e-17));
        CHECK(r.d2h == Approx(-m.d2h).margin(1e-15));
    }
    ConjugateCams cams{"cams",
                       program,
                       TranslatingRoller(0.04, 0.01),
                       TranslatingRoller(0.05, 0.012),
                       std::nullopt,
                       HertzContact{1e9, 1.0, 0.0},
                       std::nullopt,
                       0.0,
                       -2e-5,
                       "ground",
                       "ground",
                       "f"};
    const std::vector<ContactPairSpec> pairs = cams.contacts();
    REQUIRE(pairs.size() == 2);
    CHECK(pairs[0].name == "cams.lift");
    CHECK(pairs[1].name == "cams.return");
    CHECK(pairs[1].follower_ratio == -1.0);
    CHECK(pairs[1].follower_offset == Approx(0.010 - 2e-5));
    CHECK(pairs[1].frame_angle == Approx(pi));
    // No spring: the interference alone holds the follower, both contacts pressed equally at rest.
    MechanismBuilder b;
    b.add_dof("f", 0.5);
    b.add_conjugate_cams(cams);
    const Mechanism<> m(b);
    const Eigen::VectorXd q = m.static_equilibrium(0.0);
    CHECK(m.static_contact_force(0.0, q, 0) == Approx(1e9 * 1e-5).epsilon(1e-9));
    CHECK(m.static_contact_force(0.0, q, 1) == Approx(1e9 * 1e-5).epsilon(1e-9));
    // A return program that is not the complement is refused by name.
    cams.return_program = program;
    CHECK_THROWS_WITH(cams.contacts(), Catch::Contains("conjugate cams 'cams': the return program is not conjugate"));
}
