// SPDX-License-Identifier: BSD-3-Clause
// The mechanism builder: assembly, bad input, the paper preset against the original 7-DOF model.
#include <catch2/catch.hpp>

#include <cmath>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "run.hpp"

using namespace camfollower;

TEST_CASE("paper preset equals the original 7-DOF model: matrices, equilibrium, modes, one revolution") {
    const CamFollowerModel old_model;
    const Mechanism<7> preset = presets::paper();
    CHECK((preset.mass() - old_model.mass()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((preset.damping() - old_model.damping()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((preset.stiffness() - old_model.stiffness()).cwiseAbs().maxCoeff() == 0.0);
    const double q_scale = old_model.initial_state().cwiseAbs().maxCoeff();
    CHECK((preset.initial_displacement() - old_model.initial_state()).cwiseAbs().maxCoeff() <= 1e-12 * q_scale);

    // Accelerations and contact forces are fixed by a residual whose terms (K q ~ 1e6 N) cancel to
    // ~200 N, so their last ~8 (acceleration) and ~10 (force) digits are rounding: the original model
    // run with its two linear solvers (same equations, other rounding) shows that spread. The preset
    // must agree with the original to 1e-12 in displacement and within that spread elsewhere.
    SolverSettings s;
    const auto a = run(old_model, s, old_model.period(), 1);
    const auto b = run(preset, s, preset.period(), 1);
    SolverSettings lu = s;
    lu.linear_solver = LinearSolver::dense_lu;
    const auto c = run(old_model, lu, old_model.period(), 1);
    REQUIRE(a.rows == b.rows);
    REQUIRE(a.rows == c.rows);
    struct Spread {
        double q = 0, a = 0, force = 0;
    };
    auto spread = [&](const Histories<CamFollowerModel>& x, const auto& y, const char* force_y) {
        Spread d;
        for (std::size_t i = 0; i < x.q.size(); ++i) {
            d.q = std::max(d.q, std::abs(x.q[i] - y.q[i]));
            d.a = std::max(d.a, std::abs(x.a[i] - y.a[i]));
        }
        for (std::size_t i = 0; i < x.rows; ++i)
            d.force = std::max(d.force, std::abs(x.channel("contact_force")[i] - y.channel(force_y)[i]));
        return d;
    };
    double qmax = 0, amax = 0, fmax = 0;
    for (std::size_t i = 0; i < a.q.size(); ++i) qmax = std::max(qmax, std::abs(a.q[i])), amax = std::max(amax, std::abs(a.a[i]));
    for (std::size_t i = 0; i < a.rows; ++i) fmax = std::max(fmax, a.channel("contact_force")[i]);
    const Spread preset_vs_old = spread(a, b, "cam.force"), rounding = spread(a, c, "contact_force");
    INFO("relative differences over one revolution, preset vs original: q " << preset_vs_old.q / qmax << ", a "
         << preset_vs_old.a / amax << ", force " << preset_vs_old.force / fmax << "; original, two linear solvers: q "
         << rounding.q / qmax << ", a " << rounding.a / amax << ", force " << rounding.force / fmax);
    CHECK(preset_vs_old.q <= 1e-12 * qmax);
    CHECK(preset_vs_old.a <= 10 * rounding.a);
    CHECK(preset_vs_old.force <= 10 * rounding.force);
    CHECK(a.stats.newton_iterations == b.stats.newton_iterations);

    // Natural frequencies at three cam angles.
    for (double theta_deg : {0.0, 100.0, 290.0}) {
        const double theta = degrees_to_radians(theta_deg);
        const ModalResult old_modes = modal_analysis(old_model, theta);
        const auto q = preset.static_equilibrium(theta);
        const Eigen::GeneralizedSelfAdjointEigenSolver<Mechanism<7>::Matrix> eig(preset.tangent_stiffness(theta, q),
                                                                                  preset.mass());
        const Eigen::Matrix<double, 7, 1> f = eig.eigenvalues().cwiseSqrt() / two_pi;
        INFO("theta = " << theta_deg << " deg");
        CHECK((f - old_modes.frequencies_hz).cwiseAbs().maxCoeff() <= 1e-12 * old_modes.frequencies_hz.maxCoeff());
    }
}

// The paper's imposed backlash (its eqs 12-18) as the preset's named option against the original model
// that first implemented it (offset e +- b in the geometry, with the offset's rate; K_rb b s on x3).
TEST_CASE("paper preset's imposed backlash equals the original model's, hard and ramped switch") {
    // The hard switch (width 0) makes the follower chatter on the cam after each switch, a motion
    // that amplifies rounding (the two differ by 1e-14 at 107 deg, 5e-7 m by the end): compared
    // over the first 100 deg, which hold the first switch and its contact losses. Ramped: the whole
    // revolution.
    for (const auto& [width_deg, window_deg] : {std::pair{0.0, 100.0}, std::pair{10.0, 360.0}, std::pair{30.0, 360.0}}) {
        INFO("switch width " << width_deg << " deg");
        Defects defects;
        defects.backlash = 1e-4;
        defects.backlash_switch_width = degrees_to_radians(width_deg);
        const CamFollowerModel old_model({}, MotionProgram::paper_default(), defects);
        presets::PaperOptions options;
        options.paper_backlash = defects.backlash;
        options.paper_backlash_switch_width = defects.backlash_switch_width;
        const Mechanism<7> preset = presets::paper({}, MotionProgram::paper_default(), options);
        const double q_scale = old_model.initial_state().cwiseAbs().maxCoeff();
        CHECK((preset.initial_displacement() - old_model.initial_state()).cwiseAbs().maxCoeff() <= 1e-12 * q_scale);
        SolverSettings s;
        const double duration = degrees_to_radians(window_deg) / old_model.omega();
        const auto a = run(old_model, s, duration, 1);
        const auto b = run(preset, s, duration, 1);
        REQUIRE(a.rows == b.rows);
        double dq = 0, qmax = 0, df = 0, fmax = 0, dx3 = 0, x3max = 0;
        for (std::size_t i = 0; i < a.q.size(); ++i)
            dq = std::max(dq, std::abs(a.q[i] - b.q[i])), qmax = std::max(qmax, std::abs(a.q[i]));
        for (std::size_t i = 0; i < a.rows; ++i) {
            df = std::max(df, std::abs(a.channel("contact_force")[i] - b.channel("cam.force")[i]));
            fmax = std::max(fmax, a.channel("contact_force")[i]);
            // The rod's lateral position x3 (the last DOF) follows the imposed side, about +-b.
            dx3 = std::max(dx3, std::abs(a.q[i * 7 + 6] - b.q[i * 7 + 6]));
            x3max = std::max(x3max, std::abs(a.q[i * 7 + 6]));
        }
        INFO("relative differences: q " << dq / qmax << ", x3 " << dx3 / x3max << ", force " << df / fmax);
        CHECK(x3max > 0.5 * defects.backlash);  // the side switch moves the rod
        CHECK(dq <= 1e-11 * qmax);  // measured up to 1e-12 (-O1), 2e-12 in x3, 2e-10 in force
        CHECK(dx3 <= 1e-10 * x3max);
        CHECK(df <= 2e-9 * fmax);
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
    ContactPairSpec c{"cam", program, follower, HertzContact{1e11, 1.5, 0.5}, 0.3, "cx", "cy", "s", "ground", CamEccentricity{}, "ground"};
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

TEST_CASE("two cams on one shaft: rank-two Woodbury update equals the dense LU, contacts tracked apart") {
    MechanismBuilder b;
    b.add_dof("shaft", 1.1, {0, 1, 0});
    b.add_spring("bearing", "shaft", "ground", 2.6e8, 750.0);
    for (const char* name : {"a", "b"}) {
        const std::string f = std::string("follower_") + name;
        b.add_dof(f, 0.4, {0, 1, 0});
        b.add_spring("spring_" + std::string(name), f, "ground", 1.4e4, 0.0, 180.0);
        b.add_contact({std::string("cam_") + name, MotionProgram::paper_default(), TranslatingRoller(0.03, 0.008, 0.01),
                       HertzContact{1.9e8, 1.0, 0.0}, name[0] == 'a' ? 0.0 : pi, "ground", "shaft", f, "ground", CamEccentricity{}, "ground"});
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
    CHECK_THROWS_WITH(Mechanism<3>(b), Catch::Contains("Mechanism<3> built from a description with 1 DOFs"));
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
    auto contact = [](const std::string& cam_x, const std::string& cam_y, const std::string& lateral, const std::string& twist) {
        return ContactPairSpec{"cam", MotionProgram::paper_default(), TranslatingRoller(0.03, 0.008, 0.0), HertzContact{},
                               0.0, cam_x, cam_y, "f", lateral, CamEccentricity{}, twist};
    };
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "ground", "f", "ground")),
                      Catch::Contains("contact 'cam': lateral and follower_dof both name DOF 'f'"));
    CHECK_THROWS_WITH(b.add_contact(contact("ground", "f", "ground", "ground")),
                      Catch::Contains("follower_dof and cam_y both name DOF 'f'"));
    CHECK_THROWS_WITH(b.add_contact(contact("g", "g", "ground", "ground")), Catch::Contains("cam_y and cam_x both name DOF 'g'"));
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
    CHECK_THROWS_WITH(b.add_clearance(same_name), Catch::Contains("clearance 'cam': the name is taken by contact 'cam'"));
    CHECK_THROWS_WITH(b.add_spring("cam", "g", "ground", 1.0), Catch::Contains("element 'cam': the name is taken by contact"));
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
