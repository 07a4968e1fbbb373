// SPDX-License-Identifier: BSD-3-Clause
// Pin joints and coupler linkages: the joint's force is the gradient of its spring energy and its
// tangent the derivative of its force (central differences), Taylor arithmetic against closed-form
// derivatives, the assembled linkage unloaded at q = 0.
#include <catch2/catch.hpp>

#include <cmath>

#include "camfollower/linkage/coupler_linkage.hpp"
#include "camfollower/linkage/taylor.hpp"
#include "camfollower/model/elements/pin_joint_element.hpp"
#include "camfollower/model/mechanism.hpp"

using namespace camfollower;

namespace {

// Collects the tangent's column pairs into a dense matrix: sum of u v^T.
struct DenseSink {
    Eigen::MatrixXd A;
    Eigen::VectorXd u, v;
    bool open = false;
    explicit DenseSink(int n) : A(Eigen::MatrixXd::Zero(n, n)), u(Eigen::VectorXd::Zero(n)), v(u) {}
    void flush() {
        if (open) A += u * v.transpose();
        u.setZero(), v.setZero();
    }
    void start_column() {
        flush();
        open = true;
    }
    void add(int dof, double a, double b) { u[dof] += a, v[dof] += b; }
};

NetworkSpec five_dofs() {
    NetworkSpec net;
    for (const char* name : {"arm", "slide", "c.x", "c.y", "c.angle"}) net.add_dof(name, 1.0);
    return net;
}

}  // namespace

TEST_CASE("pin joint: force is the energy's gradient, tangent the force's derivative") {
    const NetworkSpec net = five_dofs();
    PinJointSpec spec{"j", PlanarPoint::on_rotating("arm", {0.01, -0.02}, 0.1, 0.7, -1.0),
                      PlanarPoint::on_body({"c.x", "c.y", "c.angle"}, {0.08, 0.05}, 0.3, {-0.12, 0.01}), 3e6, 40.0};
    const PinJointElement joint(spec, net, SpeedProgram::constant(1.0));
    const Eigen::VectorXd q = (Eigen::VectorXd(5) << 0.2, 0.0, 0.003, -0.002, -0.15).finished();
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(5);
    const auto energy = [&](const Eigen::VectorXd& x) {
        PinJointElement::State s;
        Eigen::VectorXd f = zero;
        joint.add_force(0.0, x, zero, s, f);
        return 0.5 * s.force.squaredNorm() / spec.stiffness;  // |k d|^2 / (2 k)
    };
    const auto force = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
        PinJointElement::State s;
        Eigen::VectorXd f = zero;
        joint.add_force(0.0, x, v, s, f);
        return f;
    };
    const Eigen::VectorXd f = force(q, zero);
    const double h = 1e-7;
    for (int i = 0; i < 5; ++i) {
        Eigen::VectorXd a = q, b = q;
        a[i] += h, b[i] -= h;
        CHECK(f[i] == Approx((energy(a) - energy(b)) / (2 * h)).margin(1e-6 * f.cwiseAbs().maxCoeff()));
    }
    // Tangent at rest (no damping rate term to leave out): cq = 1 against differences of the force;
    // cv = 1 against differences in v.
    const Eigen::VectorXd v = (Eigen::VectorXd(5) << 0.3, 0.0, -0.1, 0.2, 0.5).finished();
    PinJointElement::State s;
    Eigen::VectorXd scratch = zero;
    joint.add_force(0.0, q, zero, s, scratch);
    DenseSink stiffness(5), damping(5);
    joint.add_tangent(s, zero, 1.0, 0.0, stiffness);
    stiffness.flush();
    joint.add_force(0.0, q, v, s, scratch);
    joint.add_tangent(s, v, 0.0, 1.0, damping);
    damping.flush();
    for (int i = 0; i < 5; ++i) {
        Eigen::VectorXd a = q, b = q, va = v, vb = v;
        a[i] += h, b[i] -= h, va[i] += 1e-3, vb[i] -= 1e-3;
        const Eigen::VectorXd dq = (force(a, zero) - force(b, zero)) / (2 * h);
        const Eigen::VectorXd dv = (force(q, va) - force(q, vb)) / 2e-3;
        for (int r = 0; r < 5; ++r) {
            CHECK(stiffness.A(r, i) == Approx(dq[r]).margin(1e-5 * spec.stiffness));
            CHECK(damping.A(r, i) == Approx(dv[r]).margin(1e-8 * spec.damping));
        }
    }
}

TEST_CASE("Taylor arithmetic carries three derivatives exactly") {
    // f(t) = atan2(sin(2t) + 3, sqrt(1 + t^2)) / (2 + cos t), derivatives by sympy-free differences of
    // a function whose derivatives are known: g(t) = sqrt(1 + t^2) * sin(t) / (t + 2).
    const double t0 = 0.7;
    const Taylor3 t(t0, 1.0, 0.0, 0.0);
    const Taylor3 g = sqrt(Taylor3(1.0) + t * t) * sin(t) / (t + Taylor3(2.0));
    const auto G = [](double x) { return std::sqrt(1 + x * x) * std::sin(x) / (x + 2); };
    const double h = 1e-3;
    CHECK(g.v == Approx(G(t0)).epsilon(1e-15));
    CHECK(g.d1 == Approx((G(t0 + h) - G(t0 - h)) / (2 * h)).epsilon(1e-6));
    CHECK(g.d2 == Approx((G(t0 + h) - 2 * G(t0) + G(t0 - h)) / (h * h)).epsilon(1e-5));
    CHECK(g.d3 ==
          Approx((G(t0 + 2 * h) - 2 * G(t0 + h) + 2 * G(t0 - h) - G(t0 - 2 * h)) / (2 * h * h * h)).epsilon(1e-4));
    const Taylor3 a = atan2(t * t + Taylor3(1.0), cos(t) * Taylor3(3.0));
    const auto A = [](double x) { return std::atan2(x * x + 1, 3 * std::cos(x)); };
    CHECK(a.d1 == Approx((A(t0 + h) - A(t0 - h)) / (2 * h)).epsilon(1e-6));
    CHECK(a.d3 ==
          Approx((A(t0 + 2 * h) - 2 * A(t0 + h) + 2 * A(t0 - h) - A(t0 - 2 * h)) / (2 * h * h * h)).epsilon(1e-4));
}

TEST_CASE("a coupler linkage is assembled and unloaded at q = 0") {
    MechanismBuilder b;
    b.add_dof("arm", 1e-3);
    b.add_dof("rocker", 2e-3);
    b.add_spring("arm_spring", "arm", ground_name, 10.0);
    b.add_spring("rocker_spring", "rocker", ground_name, 10.0);
    CouplerLinkage link;
    link.name = "bar";
    link.arm_dof = "arm";
    link.arm_length = 0.08, link.arm_angle = 1.7;
    link.coupler_length = 0.25, link.coupler_mass = 0.3, link.coupler_inertia = 2e-3;
    link.output = CouplerLinkage::Output::rocker;
    link.output_dof = "rocker";
    link.output_origin = {0.22, 0.02};
    link.output_length = 0.12;
    link.joint_stiffness = 1e8;
    b.add_linkage(link);
    const Mechanism<> m(b);
    CHECK(m.initial_displacement().cwiseAbs().maxCoeff() < 1e-14);
    // Turned by 0.2 rad statically against the springs: the rocker sits where the rigid linkage puts it.
    const Eigen::Vector2d A = link.arm_pin_at(0.2), B = link.output_pin(0.2);
    CHECK((B - A).norm() == Approx(0.25).epsilon(1e-13));
    CHECK((B - link.output_origin).norm() == Approx(0.12).epsilon(1e-13));
    CHECK(link.input_at(link.output_at(0.2)) == Approx(0.2).epsilon(1e-12));
    link.output_length = 0.005;
    CHECK_THROWS_WITH(link.validate(), Catch::Contains("linkage 'bar'") && Catch::Contains("cannot close"));
}
