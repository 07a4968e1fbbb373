// SPDX-License-Identifier: BSD-3-Clause
// Flexible camshafts in a mechanism: the shaft against Timoshenko's closed forms (statics, natural
// frequencies), a surging spring against the distributed spring's frequencies, the twisting cam's
// moment against the contact energy, the rigid-shaft limit against the paper preset, and the sparse
// backend against the dense one.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/sparse_newton.hpp"
#include "run.hpp"

using namespace camfollower;

namespace {

constexpr double E = 2.1e11, nu = 0.3, rho = 7850.0;
constexpr double bearing_stiffness = 1e12;  // N/m

BeamSection shaft_section(double d = 0.025) { return BeamSection::solid_circle(d, E, nu, rho); }

// A simply supported shaft (stiff bearings at both ends) with a stiff drive at x = 0.
MechanismBuilder supported_shaft(double length, int elements, const std::vector<double>& stations) {
    MechanismBuilder b;
    b.add_shaft({"s", shaft_section(), length, length / elements, stations, false});
    // Stiff enough to hold (1e-6 of the shaft's own compliance), soft enough for the eigen solver's rounding.
    b.add_bearing("left", "s", 0.0, bearing_stiffness);
    b.add_bearing("right", "s", length, bearing_stiffness);
    b.add_drive("drive", "s", 0.0, 1e12);
    return b;
}

// Generalized eigenvalues (rad/s) of a mechanism's tangent stiffness and mass at its equilibrium.
Eigen::VectorXd natural_frequencies(const Mechanism<>& m) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
        m.tangent_stiffness(0.0, m.initial_displacement()), m.mass(), Eigen::EigenvaluesOnly);
    return eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

double nearest(const Eigen::VectorXd& values, double target) {
    double best = values[0];
    for (double v : values)
        if (std::abs(v - target) < std::abs(best - target)) best = v;
    return best;
}

}  // namespace

TEST_CASE("a shaft in a mechanism: midspan load and own weight give Timoshenko's closed-form deflections") {
    const double L = 0.5, P = 1000.0, g = 9.81;
    const BeamSection sec = shaft_section();
    const double EI = E * sec.second_moment_y, kGA = sec.shear_coefficient_z * sec.shear_modulus * sec.area;
    const double w = rho * sec.area * g;  // weight per length, N/m
    // 8 elements (dense static solve) and 48 (sparse LU above 200 DOFs).
    for (int elements : {8, 48}) {
        INFO(elements << " elements");
        MechanismBuilder b = supported_shaft(L, elements, {0.5 * L});
        b.add_load(b.structure.shaft_dof_at("s", 0.5 * L, 2), -P);
        const Mechanism<> point(b);
        REQUIRE(point.size() == 5 * (elements + 1));
        // Bending, shear, and the bearings' own give under their reactions (a rigid translation).
        const double exact_point = P * L * L * L / (48.0 * EI) + P * L / (4.0 * kGA) + 0.5 * P / bearing_stiffness;
        const double mid_point =
            point.initial_displacement()[point.dof_index(b.structure.shaft_dof_at("s", 0.5 * L, 2))];
        CHECK(-mid_point == Approx(exact_point).epsilon(1e-9));

        MechanismBuilder heavy = supported_shaft(L, elements, {0.5 * L});
        heavy.set_gravity({0.0, 0.0, -g});
        const Mechanism<> weight(heavy);
        const double exact_weight =
            5.0 * w * std::pow(L, 4) / (384.0 * EI) + w * L * L / (8.0 * kGA) + 0.5 * w * L / bearing_stiffness;
        const double mid_weight =
            weight.initial_displacement()[weight.dof_index(heavy.structure.shaft_dof_at("s", 0.5 * L, 2))];
        CHECK(-mid_weight == Approx(exact_weight).epsilon(1e-9));
    }
}

TEST_CASE("a shaft in a mechanism: bending and torsional frequencies converge to the closed forms") {
    const double L = 0.5;
    const BeamSection sec = shaft_section();
    // Simply supported Timoshenko beam, mode 1 (k = pi / L): the smaller root of
    // (rho A w^2 - kGA k^2)(rho I w^2 - EI k^2 - kGA) = (kGA k)^2.
    const double k = pi / L, kGA = sec.shear_coefficient_z * sec.shear_modulus * sec.area;
    const double rA = rho * sec.area, rI = rho * sec.second_moment_y, EI = E * sec.second_moment_y;
    const double a2 = rA * rI, a1 = -(rA * (EI * k * k + kGA) + rI * kGA * k * k), a0 = kGA * k * k * EI * k * k;
    const double bending = std::sqrt((-a1 - std::sqrt(a1 * a1 - 4 * a2 * a0)) / (2 * a2));
    // Torsion fixed (stiff drive) at x = 0, free at x = L: omega = (pi / 2L) sqrt(G / rho).
    const double torsion = pi / (2.0 * L) * std::sqrt(sec.shear_modulus / rho);
    std::vector<double> bending_errors;
    for (int elements : {4, 8, 16}) {
        const Eigen::VectorXd w = natural_frequencies(Mechanism<>(supported_shaft(L, elements, {})));
        const double bending_error = std::abs(w[0] / bending - 1.0),
                     torsion_error = std::abs(nearest(w, torsion) / torsion - 1.0);
        INFO(elements << " elements: bending " << w[0] / two_pi << " Hz (exact " << bending / two_pi << "), error "
                      << bending_error << "; torsion error " << torsion_error);
        CHECK(w[1] == Approx(w[0]).epsilon(1e-6));            // the two bending planes
        CHECK(torsion_error < 0.12 / (elements * elements));  // the linear bar: second order
        bending_errors.push_back(bending_error);
    }
    CHECK(bending_errors[0] > 8.0 * bending_errors[1]);  // fourth order in the element length
    CHECK(bending_errors[2] < 1e-5);
}

TEST_CASE("a spring with its own mass surges at the distributed spring's frequencies") {
    // One end held (ground), the other free on a light retainer: f_j = (2j - 1) / 4 sqrt(k / m).
    const double k = 2.5e4, m = 0.05;
    double previous_error = 1.0;
    for (int elements : {8, 16, 32}) {
        MechanismBuilder b;
        b.add_dof("retainer", 1e-9, {0, 0, 1});
        b.add_spring_chain("valve_spring", "retainer", "ground", k, m, elements, 0.0, 0.0, {0, 0, 1});
        const Mechanism<> chain(b);
        REQUIRE(chain.size() == elements);
        const Eigen::VectorXd w = natural_frequencies(chain);
        double worst = 0.0;
        for (int j = 1; j <= 3; ++j) {
            const double exact = (2.0 * j - 1.0) / 4.0 * std::sqrt(k / m) * two_pi;
            worst = std::max(worst, std::abs(w[j - 1] / exact - 1.0));
        }
        INFO(elements << " elements: worst relative error of the first three surge frequencies " << worst);
        CHECK(worst < previous_error / 3.5);  // the lumped chain converges at second order
        previous_error = worst;
    }
    CHECK(previous_error < 5e-3);
    // The static deflection under a load is the spring's, whatever the chain: F / k.
    MechanismBuilder b;
    b.add_dof("retainer", 1e-3, {0, 0, 1});
    b.add_spring_chain("valve_spring", "retainer", "ground", k, m, 7, 0.0, 0.0, {0, 0, 1});
    b.add_load("retainer", 100.0);
    CHECK(Mechanism<>(b).initial_displacement()[0] == Approx(100.0 / k).epsilon(1e-12));
}

namespace {

// A cam on a twisting camshaft (one torsional DOF "twist") driving follower "s" against a spring.
MechanismBuilder twisting_cam(const Follower& follower, const MotionProgram& program, bool translating) {
    MechanismBuilder b;
    b.add_dof("twist", 2e-3);
    b.add_spring("drive", "twist", "ground", 5e3);
    b.add_dof("s", translating ? 0.3 : 4e-4, {0, 1, 0});
    b.add_spring("spring", "s", "ground", translating ? 2e4 : 40.0, 0.0, translating ? 150.0 : 4.0);
    ContactPairSpec c{"cam",    program, follower, HertzContact{2e8, 1.5, 0.0}, 0.4,    "ground",
                      "ground", "s",     "ground", CamEccentricity{},           "twist"};
    b.add_contact(c);
    return b;
}

}  // namespace

TEST_CASE("a twisting cam: the moment on the shaft is the derivative of the contact energy") {
    const MotionProgram lift = MotionProgram::paper_default(0.010), swing = MotionProgram::paper_default(0.2618);
    const Eigen::Vector2d pivot(0.06, 0.05);
    const struct {
        Follower follower;
        const MotionProgram& program;
        bool translating;
    } cases[] = {{TranslatingRoller(0.03, 0.008, 0.01), lift, true},
                 {TranslatingFlat(0.03, degrees_to_radians(5.0), 0.002), lift, true},
                 {OscillatingRoller(0.03, 0.008, pivot, 0.06), swing, false},
                 {OscillatingFlat(0.03, pivot, 0.0), swing, false}};
    for (const auto& c : cases) {
        const Mechanism<> m(twisting_cam(c.follower, c.program, c.translating));
        INFO("follower " << follower_type_name(c.follower));
        for (double theta_deg : {40.0, 100.0, 200.0}) {
            INFO("theta = " << theta_deg << " deg");
            const double t = degrees_to_radians(theta_deg) / m.omega();
            auto w = m.workspace();
            m.prepare(t, w);
            Eigen::VectorXd q = m.static_equilibrium(degrees_to_radians(theta_deg));
            q[1] += c.translating ? -2e-6 : -2e-4;  // a little more penetration than at rest
            const Eigen::VectorXd v = Eigen::VectorXd::Zero(m.size());
            // Contact energy V = k delta^(n+1) / (n + 1), from the force F = k delta^n.
            const double kc = 2e8, n = 1.5;
            auto energy = [&](const Eigen::VectorXd& x) {
                Eigen::VectorXd f(m.size());
                m.force(w, x, v, f);
                const double F = w.contact(0).last.force;
                return kc * std::pow(F / kc, (n + 1.0) / n) / (n + 1.0);
            };
            Eigen::VectorXd f(m.size());
            m.force(w, q, v, f);
            const Eigen::VectorXd contact = f + m.constant_load();
            REQUIRE(w.contact(0).last.force > 0.0);
            for (int dof = 0; dof < 2; ++dof) {
                const double h = dof == 0 ? 1e-7 : 1e-9;
                Eigen::VectorXd qp = q, qm = q;
                qp[dof] += h, qm[dof] -= h;
                const double fd = (energy(qp) - energy(qm)) / (2 * h);
                INFO("dof " << dof << ": generalized contact force " << contact[dof] << ", energy derivative " << fd);
                CHECK(contact[dof] == Approx(fd).epsilon(1e-5).margin(1e-6 * std::abs(contact[1])));
            }
        }
    }
}

TEST_CASE("a stiff drive: the twisting camshaft tends to the rigid one (the paper preset)") {
    const Mechanism<7> rigid = presets::paper();
    SolverSettings s;
    const double duration = 0.5 * rigid.period();
    const auto reference = run(rigid, s, duration, 20);
    double fmax = 0.0;
    for (std::size_t i = 0; i < reference.rows; ++i) fmax = std::max(fmax, reference.channel("cam.force")[i]);
    double previous = 1.0;
    for (double drive : {1e5, 1e6, 1e7}) {
        MechanismBuilder b = rigid.description();
        b.add_dof("twist", 1e-3);
        b.add_spring("drive", "twist", "ground", drive);
        b.contacts[0].cam_twist = "twist";
        const Mechanism<> twisting(b);
        const auto r = run(twisting, s, duration, 20);
        REQUIRE(r.rows == reference.rows);
        double df = 0.0;
        for (std::size_t i = 0; i < r.rows; ++i)
            df = std::max(df, std::abs(r.channel("cam.force")[i] - reference.channel("cam.force")[i]));
        INFO("drive stiffness " << drive << " N m/rad: max contact-force difference " << df / fmax << " of its peak");
        CHECK(df / fmax < previous / 5.0);
        previous = df / fmax;
    }
    CHECK(previous < 2e-3);
}

namespace {

// n cams along one shaft (each with a translating roller follower and a surging spring).
MechanismBuilder camshaft(int cams, int elements_per_bay, bool contact_damping) {
    const double pitch = 0.05, length = pitch * (cams + 1);
    std::vector<double> stations;
    for (int i = 1; i <= cams; ++i) stations.push_back(pitch * i);
    MechanismBuilder b;
    b.add_shaft({"cs", shaft_section(0.03), length, pitch / elements_per_bay, stations, false});
    b.add_bearing("b0", "cs", 0.0, 2e8, 200.0);
    b.add_bearing("b1", "cs", length, 2e8, 200.0);
    b.add_drive("drive", "cs", 0.0, 2e4, 2.0);
    b.set_gravity({0, 0, -9.81});
    b.camshaft_speed = 1500.0 * two_pi / 60.0;
    for (int i = 0; i < cams; ++i) {
        const std::string f = "valve" + std::to_string(i);
        b.add_dof(f, 0.1, {0, 0, 1});
        b.add_spring_chain("spring" + std::to_string(i), f, "ground", 3e4, 0.04, 4, 2.0, 250.0, {0, 0, 1});
        ContactPairSpec c{"cam" + std::to_string(i),
                          MotionProgram::paper_default(0.008),
                          TranslatingRoller(0.02, 0.008, 0.0),
                          HertzContact{2e8, 1.0, contact_damping ? 2e-5 : 0.0},
                          two_pi * i / cams,
                          "ground",
                          "ground",
                          f,
                          "ground",
                          CamEccentricity{},
                          "ground"};
        b.mount_cam(c, "cs", stations[std::size_t(i)], 0.015, 0.3, 1e-4);
    }
    return b;
}

// max |a - b| / max |a|.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        d = std::max(d, std::abs(a[i] - b[i])), scale = std::max(scale, std::abs(a[i]));
    return d / scale;
}

}  // namespace

TEST_CASE("the sparse backend (KLU, CHOLMOD) reproduces the dense one on a four-cam shaft") {
    for (bool damped : {false, true}) {
        INFO((damped ? "with" : "without") << " contact damping");
        const Mechanism<> m(camshaft(4, 8, damped));
        REQUIRE(m.size() > sparse_backend_threshold);
        SolverSettings s;
        s.time_step = 2e-5;
        s.backend = Backend::dense;
        const double duration = 0.25 * m.period();
        const auto dense = run(m, s, duration, 10);
        s.backend = Backend::sparse;
        const auto sparse = run(m, s, duration, 10);
        s.sparse_factorization = SparseFactorization::klu;
        const auto klu = run(m, s, duration, 10);
        INFO("relative differences from dense: automatic "
             << relative_difference(dense.q, sparse.q) << ", KLU " << relative_difference(dense.q, klu.q)
             << "; Newton iterations per step " << dense.stats.mean_iterations() << " dense, "
             << sparse.stats.mean_iterations() << " sparse");
        CHECK(relative_difference(dense.q, sparse.q) <= 1e-9);
        CHECK(relative_difference(dense.q, klu.q) <= 1e-9);
        CHECK(relative_difference(dense.q, sparse.q) > 0.0);  // the backends really differ (in rounding)
        CHECK(sparse.stats.mean_iterations() < 3.0);
        // Every cam turns with its own twist and carries its moment.
        CHECK(sparse.recording.channel("cam2.cam_torque") != nullptr);
        SparseNewmark<Mechanism<>> stepper(m, s);
        auto state = stepper.start(0.0, m.initial_displacement(), m.initial_velocity());
        SolverStatistics stats;
        stepper.step(state, stats);
        CHECK(std::string(stepper.linear_solver().last_factorization()) == "klu");
        s.sparse_factorization = SparseFactorization::automatic;
        SparseNewmark<Mechanism<>> automatic(m, s);
        state = automatic.start(0.0, m.initial_displacement(), m.initial_velocity());
        automatic.step(state, stats);
        CHECK(std::string(automatic.linear_solver().last_factorization()) == (damped ? "klu" : "cholmod"));
    }
}

TEST_CASE("camshaft bad input: cams outside or overlapping, bearings twice at a station, a shaft held by nothing") {
    MechanismBuilder b;
    b.add_shaft({"cs", shaft_section(), 0.3, 0.05, {0.1, 0.11, 0.2}, false});
    ContactPairSpec c{"cam",
                      MotionProgram::paper_default(0.008),
                      TranslatingRoller(0.02, 0.008, 0.0),
                      HertzContact{},
                      0.0,
                      "ground",
                      "ground",
                      "ground",
                      "ground",
                      CamEccentricity{},
                      "ground"};
    CHECK_THROWS_WITH(b.mount_cam(c, "cs", 0.4),
                      Catch::Contains("cam 'cam' at x = 0.4 m is outside shaft 'cs' [0, 0.3] m"));
    CHECK_THROWS_WITH(b.mount_cam(c, "cs", 0.15), Catch::Contains("shaft 'cs' has no node at x = 0.15 m"));
    CHECK_THROWS_WITH(b.mount_cam(c, "nowhere", 0.1), Catch::Contains("no shaft named 'nowhere'"));
    b.add_dof("f1", 0.1, {0, 0, 1});
    c.follower_dof = "f1";
    b.mount_cam(c, "cs", 0.1, 0.015);
    c.name = "cam2";
    CHECK_THROWS_WITH(b.mount_cam(c, "cs", 0.11, 0.015),
                      Catch::Contains("cams 'cam' (x = 0.1 m, width 0.015 m) and 'cam2'"));
    b.add_bearing("b", "cs", 0.0, 1e8);
    CHECK_THROWS_WITH(b.add_bearing("b2", "cs", 0.0, 1e8),
                      Catch::Contains("bearings 'b' and 'b2' are at the same station"));
    CHECK_THROWS_WITH(b.add_shaft({"cs", shaft_section(), 0.3, 0.05, {}, false}),
                      Catch::Contains("shaft 'cs' is defined twice"));
    CHECK_THROWS_WITH(b.add_shaft({"t", shaft_section(), -1.0, 0.0, {}, false}), Catch::Contains("shaft 't' length"));
    CHECK_THROWS_WITH(b.add_shaft({"t", shaft_section(), 1.0, 0.0, {1.5}, false}),
                      Catch::Contains("station x = 1.5 m is outside"));
    BeamSection bad = shaft_section();
    bad.area = NAN;
    CHECK_THROWS_WITH(b.add_shaft({"t", bad, 1.0, 0.0, {}, false}), Catch::Contains("shaft 't' section: area"));
    // One bearing, no drive: the shaft tilts and spins freely; the error names those DOFs.
    b.add_spring("return", "f1", "ground", 1e4, 0.0, 100.0);
    CHECK_THROWS_WITH(Mechanism<>(b), Catch::Contains("not held in place") && Catch::Contains("unconstrained: cs."));
}

TEST_CASE("the valve-train preset: lowest modes by sparse shift-invert equal the dense solver's") {
    const Mechanism<> m(presets::valve_train());
    REQUIRE(m.size() > dense_modes_limit);
    REQUIRE(m.contacts().size() == 8);
    const MechanismModes sparse = lowest_modes(m, 0.3, 12);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(
        m.tangent_stiffness(0.3, m.static_equilibrium(0.3)), m.mass());
    REQUIRE(dense.info() == Eigen::Success);
    for (int k = 0; k < 12; ++k) {
        const double f = std::sqrt(std::max(dense.eigenvalues()[k], 0.0)) / two_pi;
        INFO("mode " << k + 1 << ": " << sparse.frequencies_hz[k] << " Hz (dense " << f << " Hz)");
        CHECK(sparse.frequencies_hz[k] == Approx(f).epsilon(1e-8));
        CHECK(sparse.shapes.col(k).dot(m.mass() * sparse.shapes.col(k)) == Approx(1.0).epsilon(1e-8));
    }
    // Every valve is held on its base circle or its flank by the spring's preload at the start.
    for (std::size_t i = 0; i < m.contacts().size(); ++i)
        CHECK(m.static_contact_force(0.0, m.initial_displacement(), i) > 150.0);
}

TEST_CASE("a motor drive: its torque twists the shaft by torque / position gain, and a motor needs that gain") {
    MechanismBuilder b;
    b.add_shaft({"s", shaft_section(), 0.4, 0.05, {0.2}, false});
    b.add_bearing("front", "s", 0.0, 1e8);
    b.add_bearing("rear", "s", 0.4, 1e8);
    const double torque = 12.0, gain = 3e3;
    b.add_motor("motor", "s", 0.0, 2e-3, gain, 5.0, torque);
    const Mechanism<> m(b);
    // No other torque on the shaft: it turns rigidly ahead of the nominal rotation by T / k_p.
    for (const char* node : {"s.0.rx", "s.4.rx", "s.8.rx"})
        CHECK(m.initial_displacement()[m.dof_index(node)] == Approx(torque / gain).epsilon(1e-9));
    MechanismBuilder free;
    free.add_shaft({"s", shaft_section(), 0.4, 0.05, {}, false});
    CHECK_THROWS_WITH(free.add_motor("motor", "s", 0.0, 2e-3, 0.0, 5.0, 1.0),
                      Catch::Contains("position_gain of motor 'motor' must be finite and > 0"));
}
